"""The ``planar-tui`` command line (Typer).

Batch jobs run from TOML presets and write CSV. Exit codes: 0 ok, 1 a job failed,
2 bad input (preset or option), 130 interrupted (Ctrl-C), 143 terminated (SIGTERM). Progress bars go to stderr; tables
and summaries to stdout. Heavy modules (numba, SALib, Textual) are imported only when
a job or the app runs, so ``planar-tui --help`` is instant.
"""

from __future__ import annotations

import dataclasses
import gc
import os
import signal
import sys
import threading
from collections.abc import Iterator, Mapping, Sequence
from contextlib import ExitStack, contextmanager
from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer
from rich.console import Console
from typer.core import TyperCommand, TyperGroup

from planar_tui import __version__, csvio
from planar_tui.errors import Cancelled, ExitCode, PresetError, Terminated
from planar_tui.resources import bundled_presets, preset_description

if TYPE_CHECKING:
    from planar_tui.jobkind import Job
    from planar_tui.presets import Preset


class _FlagsWithoutMetavar:
    """Help for flags (``--map/--no-map``, ``--version``, ``--help``) without a value
    placeholder: Typer's rich help otherwise prints ``<bool>`` after them, as if they took
    a value. A flag's metavar is only ever shown in help. Help texts are shown as
    written: Typer reads them as Rich markup, which would swallow ``[[sweep]]``, so
    brackets are escaped (:func:`rich.markup.escape`)."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self.help = _escaped(self.help)
        self.short_help = _escaped(self.short_help)

    def get_params(self, ctx):
        params = super().get_params(ctx)
        for param in params:
            if getattr(param, "is_flag", False) and param.metavar is None:
                param.metavar = ""
            if getattr(param, "help", None) and not getattr(param, "_escaped", False):
                param.help = _escaped(param.help)
                param._escaped = True
        return params


def _escaped(text: str | None) -> str | None:
    """``text`` with Rich markup escaped (shown as written)."""
    from rich.markup import escape

    return None if text is None else escape(text)


class Group(_FlagsWithoutMetavar, TyperGroup):
    """The ``planar-tui`` command group."""


class Command(_FlagsWithoutMetavar, TyperCommand):
    """A ``planar-tui`` command."""


app = typer.Typer(
    name="planar-tui",
    cls=Group,
    help="Terminal workbench for planar robots: NOC dynamics, Sobol/eFAST sensitivity, "
    "3-RRR workspace by interval analysis. Without a command, opens the Textual app "
    "(in a terminal; without one, prints this help and exits with code 2).",
    add_completion=False,
    no_args_is_help=False,
    pretty_exceptions_enable=False,
)
stdout = Console(highlight=False)
stderr = Console(stderr=True, highlight=False)

PresetArg = Annotated[
    str, typer.Argument(help="Preset file, or a bundled preset name (see `planar-tui presets`).")
]
OutOption = Annotated[
    Path | None,
    typer.Option(
        "--out", "-o", help="CSV file to write (with several jobs: FILE-1.csv, FILE-2.csv ...)."
    ),
]
OutDirOption = Annotated[
    Path, typer.Option("--out-dir", "-d", help="Folder for the presets' output files.")
]
JobOption = Annotated[
    list[str] | None,
    typer.Option(
        "--job",
        "-j",
        metavar="NAME",
        help="Run only this job, named by its table key (workspace[2], simulate), "
        "PRESET:KEY or its output file name; repeatable.",
    ),
]
PlotOption = Annotated[
    Path | None,
    typer.Option(
        "--plot",
        metavar="FILE",
        help="Also draw the result's figure into FILE (.svg, .png or .pdf; with several "
        "jobs: FILE-1.png, FILE-2.png ...); overrides the jobs' `plot` keys.",
    ),
]
#: How an override appears in the names of the files it changes (``--precision-0.5``).
OVERRIDE_LABELS = {"precision_cm": "precision", "methods": "method"}


#: Whether this process has printed its one-line outcome (see :func:`main`).
_REPORTED = False
#: Set by every Ctrl-C (:func:`_interrupt`). The ``KeyboardInterrupt`` it raises can land
#: where Python can only report it and go on (a weakref callback of the import system:
#: "Exception ignored in ..."), so the runners' progress checks ask this too
#: (``should_stop``) and such a report is silenced (:func:`_unraisable`).
_INTERRUPTED = threading.Event()


def _interrupt(signum, frame) -> None:
    _INTERRUPTED.set()
    raise KeyboardInterrupt


def _unraisable(unraisable) -> None:
    """``sys.unraisablehook``: a Ctrl-C that could not be raised where it landed stops
    the run at its next progress check instead of printing a traceback and being lost."""
    if isinstance(unraisable.exc_value, KeyboardInterrupt):
        _INTERRUPTED.set()
        return
    sys.__unraisablehook__(unraisable)


def fail(message: str, code: ExitCode = ExitCode.BAD_INPUT) -> typer.Exit:
    """Print ``message`` on stderr and return the exit to raise."""
    global _REPORTED
    stderr.print(message, markup=False, highlight=False, soft_wrap=True)
    _REPORTED = True
    return typer.Exit(int(code))


@contextmanager
def reported_errors() -> Iterator[None]:
    """Turn preset errors, interrupts and job failures into one line and an exit code."""
    try:
        yield
    except PresetError as error:  # a job out of its budget while running: exit 1
        raise fail(str(error), getattr(error, "exit_code", ExitCode.BAD_INPUT)) from None
    except Terminated:
        raise fail(
            "terminated: the running job's output was not written", ExitCode.TERMINATED
        ) from None
    except (KeyboardInterrupt, Cancelled):
        raise fail(
            "interrupted: the running job's output was not written", ExitCode.INTERRUPTED
        ) from None


def check_figure_option(path: Path | None, option: str = "--plot") -> None:
    """Refuse a figure path whose suffix names no format (:class:`PresetError`, exit 2)."""
    from planar_tui.schema import FIGURE_SUFFIXES, figure_suffix_problem

    problem = None if path is None else figure_suffix_problem(str(path))
    if problem is not None:
        raise PresetError(
            "command line", option, f"is {str(path)!r}: {problem}",
            "a file ending " + ", ".join(FIGURE_SUFFIXES),
        )  # fmt: skip


def check_workers(workers: int | None) -> None:
    """Refuse ``--workers`` out of range (:class:`PresetError`, exit 2), in one line as the
    job options' ranges are (checked here, not by Typer, whose usage box takes many lines)."""
    from planar_tui.sweep.budget import check_workers as check

    check(workers)


def load_presets(arguments: Sequence[str]) -> list[Preset]:
    """Resolve and validate every preset before anything runs."""
    from planar_tui.presets import load_preset
    from planar_tui.resources import resolve_preset

    return [load_preset(resolve_preset(argument)) for argument in arguments]


def clock_text(seconds: float) -> str:
    """``H:MM:SS`` of a duration (rounded to whole seconds)."""
    whole = round(max(seconds, 0.0))
    return f"{whole // 3600}:{whole % 3600 // 60:02d}:{whole % 60:02d}"


def progress_figures(
    completed: float, total: float, remaining_s: float | None, done_s: float | None = None
) -> str:
    """The figures beside a job's bar: percent, ``done/total`` when the runner counts whole
    units (steps, states, evaluations; a workspace counts a fraction and shows its boxes in
    the detail line), and ``ETA H:MM:SS`` (``-:--:--`` until known), or ``in H:MM:SS``
    once the job is done (``done_s`` seconds after it started)."""
    parts = [f"{100.0 * completed / total if total else 100.0:3.0f}%"]
    if total > 1 and float(total).is_integer():
        parts.append(f"{completed:,.0f}/{total:,.0f}")
    if done_s is not None:
        parts.append(f"in {clock_text(done_s)}")
    else:
        parts.append("ETA " + ("-:--:--" if remaining_s is None else clock_text(remaining_s)))
    return "  ".join(parts)


def job_progress_display(console: Console):
    """A rich progress display for one job, complete at 80 columns: the job and stage on
    their own line, then the bar with percent, count and ETA, then the runner's detail
    (folded, never cut). Its task takes ``detail`` and ``done_s`` fields."""
    from rich.progress import BarColumn, Progress, ProgressColumn
    from rich.table import Column
    from rich.text import Text

    class FiguresColumn(ProgressColumn):
        def render(self, task) -> Text:
            figures = progress_figures(
                task.completed, task.total or 0.0, task.time_remaining, task.fields["done_s"]
            )
            return Text(figures, no_wrap=True)

    class JobProgress(Progress):
        def get_renderables(self):
            for task in self.tasks:
                yield Text(task.description, overflow="fold")
                yield self.make_tasks_table([task])
                if task.fields.get("detail"):
                    yield Text(f"  {task.fields['detail']}", overflow="fold")

    bar = BarColumn(bar_width=None, table_column=Column(ratio=1))
    figures = FiguresColumn(table_column=Column(no_wrap=True))
    return JobProgress(bar, figures, console=console, transient=False, expand=True)


def _raise_terminated(signum, frame) -> None:
    raise Terminated("SIGTERM")


@contextmanager
def sigterm_as_interrupt() -> Iterator[None]:
    """While jobs run, SIGTERM raises :class:`~planar_tui.errors.Terminated` (a
    ``KeyboardInterrupt``) so it cleans up like Ctrl-C: no temporary file is left."""
    previous = signal.signal(signal.SIGTERM, _raise_terminated)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


@contextmanager
def progress_bar(bars, job: Job):
    """One progress task for ``job`` (stage, figures and detail), as a
    :class:`~planar_tui.progress.Progress` for the runner. A new stage restarts the bar and
    its speed estimate; the last line says ``done`` with the total time and the runner's
    last detail (a workspace's final area bracket)."""
    import time

    from planar_tui.progress import Progress

    started = time.monotonic()
    task = bars.add_task(job.label, total=1.0, detail="", done_s=None)
    warned = set()
    stage = None

    def update(state) -> None:
        nonlocal stage
        if state.warning and state.warning not in warned:
            warned.add(state.warning)
            bars.console.print(f"warning: {job.label}: {state.warning}", markup=False)
        if state.stage != stage:
            stage = state.stage
            bars.reset(task, total=state.total, completed=state.completed)
        bars.update(
            task,
            completed=state.completed,
            total=state.total,
            description=f"{job.label} {state.stage}".strip(),
            detail=state.detail,
        )

    yield Progress(on_update=update, should_stop=_INTERRUPTED.is_set)
    (current,) = (t for t in bars.tasks if t.id == task)
    done_s = time.monotonic() - started
    bars.update(task, completed=current.total, description=f"{job.label} done", done_s=done_s)


def execute(
    jobs: Sequence[Job],
    out_dir: Path,
    *,
    out: Path | None = None,
    extra_out: Mapping[str, Path | None] | None = None,
    show: bool = True,
    plot: Path | None = None,
) -> None:
    """Run ``jobs`` through the batch service, one progress bar each, then print a summary.

    Output paths are checked, then every job prepared (:func:`batch.prepare_jobs`: e.g.
    isotropic postures solved), before the first job runs; each job's files are written as
    soon as it finishes. A job that raises an unexpected error, or an output that cannot be
    written, ends the run with one ``error:`` line and exit code 1 (``PLANAR_TUI_DEBUG=1``
    shows the traceback). ``show`` prints each kind's terminal view.
    """
    from rich.table import Table
    from rich.text import Text

    from planar_tui import batch
    from planar_tui.registry import JOB_KINDS

    plans = batch.plan_outputs(jobs, out_dir, out, extra_out, plot)
    batch.check_plans(plans)
    prepared = batch.prepare_jobs(jobs)
    plans = [dataclasses.replace(plan, job=job) for plan, job in zip(plans, prepared, strict=True)]

    @contextmanager
    def progress_for(job: Job):
        with job_progress_display(stderr) as bars, progress_bar(bars, job) as progress:
            yield progress

    def render(job: Job, result) -> None:
        view = JOB_KINDS[job.kind].render
        if show and view is not None:
            view(job, result, stdout)

    debug = os.environ.get("PLANAR_TUI_DEBUG", "") not in ("", "0")
    try:
        with sigterm_as_interrupt():
            rows = list(batch.run_plans(plans, progress_for, render))
    except batch.JobFailed as error:
        if debug:
            raise error.__cause__ from None
        raise fail(f"error: {error}", ExitCode.RUN_FAILED) from None
    except (batch.OutputFailed, batch.NonFiniteResult) as error:
        raise fail(f"error: {error}", ExitCode.RUN_FAILED) from None

    summary = Table(title="planar-tui run summary", title_justify="left", show_lines=True)
    summary.add_column("job", no_wrap=True)
    summary.add_column("seconds", justify="right", no_wrap=True)
    summary.add_column("output and result", overflow="fold")
    for row in rows:
        summary.add_row(Text(row.label), f"{row.seconds:.3f}", Text(f"{row.output}\n{row.summary}"))
    stdout.print(summary)


def run_kind(
    kind: str,
    preset_argument: str,
    out: Path | None,
    out_dir: Path,
    options: Mapping[str, object] | None = None,
    *,
    names: Sequence[str] | None = None,
    extra_out: Mapping[str, Path | None] | None = None,
    show: bool = True,
    plot: Path | None = None,
) -> None:
    """Run the jobs of one kind in a preset (the ``simulate``/``torques``... commands):
    all of them, or those ``names`` selects (``--job``); ``options`` are command-line
    overrides, applied and checked by the job kind."""
    with reported_errors():
        from planar_tui.batch import apply_overrides, select_jobs

        check_figure_option(plot)
        (preset,) = load_presets([preset_argument])
        jobs = preset.jobs_of(kind)
        if not jobs:
            raise PresetError(
                preset.path, kind, f"no [{kind}] job in this preset", f"a [{kind}] table"
            )
        jobs = select_jobs(jobs, names)
        if options:
            jobs = apply_overrides(jobs, options, OVERRIDE_LABELS)
        execute(jobs, out_dir, out=out, extra_out=extra_out, show=show, plot=plot)


def _notice(text: str) -> None:
    """A one-line note of the core (stale temporary files removed) on stderr."""
    stderr.print(text, markup=False, highlight=False, soft_wrap=True)


def version_callback(value: bool) -> None:
    if value:
        stdout.print(f"planar-tui {__version__}")
        raise typer.Exit()


@app.callback(invoke_without_command=True)
def root(
    context: typer.Context,
    version: Annotated[
        bool,
        typer.Option(
            "--version", callback=version_callback, is_eager=True, help="Print the version."
        ),
    ] = False,
) -> None:
    """Without a command: open the Textual app on a bundled preset (in a terminal)."""
    csvio.notice = _notice
    if context.invoked_subcommand is None:
        if not (sys.stdin.isatty() and sys.stdout.isatty()):
            help_text = context.get_help()  # Typer's rich help prints itself, returns ""
            if help_text:
                typer.echo(help_text)
            raise fail(
                "error: no command given, and the app needs a terminal (stdin and stdout "
                "are not both one): name a command, e.g. planar-tui run PRESET"
            )
        open_app(None)


def open_app(preset_argument: str | None) -> None:
    """Open the Textual workbench (imported only now)."""
    with reported_errors():
        from planar_tui.app import run_app

        run_app(preset_argument)


@app.command(cls=Command)
def tui(
    preset: Annotated[
        str | None,
        typer.Argument(help="Preset file or bundled preset name (default: paper-a-table1)."),
    ] = None,
) -> None:
    """Open the Textual workbench on a preset (what `planar-tui` alone does)."""
    open_app(preset)


@app.command(cls=Command)
def simulate(
    preset: PresetArg,
    job_name: JobOption = None,
    out: OutOption = None,
    out_dir: OutDirOption = Path("."),
    plot: PlotOption = None,
) -> None:
    """Integrate the forward dynamics (RK4) of every simulate job; one CSV per job."""
    run_kind("simulate", preset, out, out_dir, names=job_name, plot=plot)


@app.command(cls=Command)
def torques(
    preset: PresetArg,
    job_name: JobOption = None,
    out: OutOption = None,
    out_dir: OutDirOption = Path("."),
    plot: PlotOption = None,
) -> None:
    """Inverse dynamics at the listed states of every torques job; one CSV per job."""
    run_kind("torques", preset, out, out_dir, names=job_name, plot=plot)


@app.command(
    cls=Command,
    help="Sobol'/eFAST sensitivity of the joint torques of every sensitivity job; one CSV "
    "each.\n\nAn option that changes a job's setting is appended to the stem of the file "
    "the preset names (tiny-sensitivity--samples-512.csv); a name given with --out is kept.",
)
def sensitivity(
    preset: PresetArg,
    method: Annotated[
        list[str] | None,
        typer.Option("--method", "-m", help="sobol or efast (repeatable); overrides `methods`."),
    ] = None,
    samples: Annotated[
        int | None, typer.Option(help="Sobol' base N (a power of two); overrides `samples`.")
    ] = None,
    seed: Annotated[int | None, typer.Option(help="Seed >= 1; overrides `seed`.")] = None,
    job_name: JobOption = None,
    out: OutOption = None,
    out_dir: OutDirOption = Path("."),
    plot: PlotOption = None,
) -> None:
    """Sobol'/eFAST sensitivity of the joint torques of every sensitivity job; one CSV each."""

    options = {"methods": method, "samples": samples, "seed": seed}
    run_kind("sensitivity", preset, out, out_dir, options, names=job_name, plot=plot)


@app.command(
    "motion",
    cls=Command,
    help="Monte-Carlo band and Sobol'/eFAST indices of the motion of every "
    "motion_uncertainty job under length and mass tolerances: band CSV, indices CSV (the "
    "job's indices_output, or OUTPUT-indices.csv) and a Table-4-shaped table per time.\n\n"
    "An option that changes a job's setting is appended to the stem of the files the preset "
    "names; a name given with --out is kept.",
)
def motion(
    preset: PresetArg,
    method: Annotated[
        list[str] | None,
        typer.Option(
            "--method", "-m", help="montecarlo, sobol or efast (repeatable); overrides `methods`."
        ),
    ] = None,
    samples: Annotated[int | None, typer.Option(help="N; overrides `samples`.")] = None,
    seed: Annotated[int | None, typer.Option(help="Seed >= 1; overrides `seed`.")] = None,
    device: Annotated[
        str | None, typer.Option(help="cpu, cuda or auto; overrides `device`.")
    ] = None,
    job_name: JobOption = None,
    out: OutOption = None,
    out_dir: OutDirOption = Path("."),
    plot: PlotOption = None,
) -> None:
    """Band and indices of the motion under tolerances of every motion_uncertainty job."""
    options = {"methods": method, "samples": samples, "seed": seed, "device": device}
    run_kind("motion_uncertainty", preset, out, out_dir, options, names=job_name, plot=plot)


@app.command(
    cls=Command,
    help="3-RRR workspace of every workspace job: summary CSV, boxes CSV (--boxes or the "
    "preset's boxes_output) and a map titled with the job, form and precision.\n\n"
    "--form and --precision apply to every selected job; each one that changes a job's "
    "setting is appended to the stem of the files the preset names (table3-natural.csv "
    "run with --form mean-value writes table3-natural--form-mean-value.csv); names given "
    "with --out and --boxes are kept.",
)
def workspace(
    preset: PresetArg,
    form: Annotated[
        str | None,
        typer.Option(
            help="natural, mean-value, slope, arc-distance or geometric; overrides `form`."
        ),
    ] = None,
    precision: Annotated[
        float | None, typer.Option(help="Precision epsilon in cm; overrides `precision_cm`.")
    ] = None,
    out: OutOption = None,
    boxes: Annotated[
        Path | None,
        typer.Option(help="CSV of the kept boxes (with several jobs: FILE-1.csv ...)."),
    ] = None,
    show_map: Annotated[
        bool, typer.Option("--map/--no-map", help="Print the character-cell map.")
    ] = True,
    job_name: JobOption = None,
    out_dir: OutDirOption = Path("."),
    plot: PlotOption = None,
) -> None:
    """3-RRR workspace of every workspace job: summary CSV, boxes CSV and a titled map."""

    options = {"form": form, "precision_cm": precision}
    extra_out = {"boxes": boxes}
    run_kind(
        "workspace",
        preset,
        out,
        out_dir,
        options,
        names=job_name,
        extra_out=extra_out,
        show=show_map,
        plot=plot,
    )


WorkersOption = Annotated[
    int | None,
    typer.Option(
        "--workers",
        "-w",
        help="Sweeps: points run on a local Dask cluster of N worker processes "
        "(default: the machine's cores); 1 runs them in this process.",
    ),
]
SchedulerOption = Annotated[
    str | None,
    typer.Option(
        "--scheduler",
        metavar="ADDRESS",
        help="Sweeps: submit the points to this existing Dask scheduler (tcp://host:8786; "
        "default: $PLANAR_TUI_SCHEDULER unless --workers is given). Connecting may take "
        "$PLANAR_TUI_SCHEDULER_TIMEOUT_S seconds (default 10).",
    ),
]
ResumeOption = Annotated[
    bool,
    typer.Option("--resume", help="Sweeps: finish an interrupted sweep from its checkpoint."),
]


@app.command(cls=Command)
def run(
    presets: Annotated[list[str], typer.Argument(help="Preset files or bundled preset names.")],
    job_name: JobOption = None,
    out_dir: OutDirOption = Path("."),
    plot: PlotOption = None,
    workers: WorkersOption = None,
    scheduler: SchedulerOption = None,
    resume: ResumeOption = False,
) -> None:
    """Run every job of every preset (or those --job names), files named as the presets
    say, then the presets' sweeps (not with --job)."""
    with reported_errors():
        from planar_tui.batch import select_jobs

        check_figure_option(plot)
        check_workers(workers)
        loaded = load_presets(presets)
        from planar_tui.sweep.spec import check_has_work

        for preset in loaded:
            check_has_work(preset)
        jobs = select_jobs([job for preset in loaded for job in preset.jobs], job_name)
        prepared = prepare_sweeps([] if job_name else loaded, out_dir, jobs, job_plot=plot,
                                  resume=resume)  # fmt: skip
        scheduler = check_sweep_budget(prepared, workers, scheduler)
        if jobs:
            execute(jobs, out_dir, plot=plot)
        run_sweeps(prepared, out_dir, workers, scheduler, resume)


@app.command("plot", cls=Command)
def plot_csv(
    result: Annotated[Path, typer.Argument(help="A CSV file planar-tui wrote (any kind).")],
    out: Annotated[
        Path | None,
        typer.Option(
            "--out", "-o", help="Figure file (.svg, .png or .pdf; default: RESULT.png beside it)."
        ),
    ] = None,
) -> None:
    """Draw the figure of a result CSV (its kind recognised from its header), e.g. a
    cluster run's result, later, on a laptop."""
    with reported_errors():
        from planar_tui.batch import check_writable

        check_figure_option(out, "--out")
        if result.is_dir():
            raise PresetError(result, "(file)", "is a folder", "a result CSV file")
        target = out if out is not None else result.with_suffix(".png")
        from planar_tui.figures import UnknownTable, figure_for_table, read_table
        from planar_tui.figures.canvas import save
        from planar_tui.figures.dispatch import is_same_file

        if is_same_file(result, target):
            raise PresetError("command line", "--out", f"is the input {result} (it would be "
                              "overwritten by its figure)", "another figure file")  # fmt: skip

        try:
            table = read_table(result)
        except FileNotFoundError:
            raise PresetError(result, "(file)", "no such file", "a result CSV") from None
        except (OSError, UnicodeDecodeError, ValueError) as error:
            raise PresetError(
                result, "(file)", f"cannot be read: {error}", "a result CSV"
            ) from None
        check_writable(target, "figure file")
        try:
            figure = figure_for_table(table, result.name)
        except UnknownTable as error:
            raise PresetError(result, "(header)", *error.args) from None
        except ValueError as error:  # no rows, or a recognised table the figure cannot show
            raise PresetError(result, "(content)", f"cannot be drawn: {error}") from None
        try:
            written = save(figure, target)
        except OSError as error:
            raise fail(f"error: {target}: cannot write: {error.strerror or error}") from None
    stdout.print(f"wrote {written}", markup=False)


@app.command("sweep", cls=Command)
def sweep_command(
    preset: PresetArg,
    workers: WorkersOption = None,
    scheduler: SchedulerOption = None,
    resume: ResumeOption = False,
    out_dir: OutDirOption = Path("."),
    plot: PlotOption = None,
) -> None:
    """Run the preset's sweeps ([[sweep]] tables): one CSV each, one row per point."""
    with reported_errors():
        if plot is not None:
            check_figure_option(plot)
        check_workers(workers)
        (loaded,) = load_presets([preset])
        prepared = prepare_sweeps([loaded], out_dir, plot=plot, resume=resume)
        if not prepared:
            raise PresetError(loaded.path, "sweep", "no [[sweep]] table in this preset",
                              "a [[sweep]] table")  # fmt: skip
        scheduler = check_sweep_budget(prepared, workers, scheduler)
        run_sweeps(prepared, out_dir, workers, scheduler, resume)


def check_sweep_budget(
    prepared: Sequence, workers: int | None, scheduler: str | None
) -> str | None:
    """Refuse sweeps over the limits before anything runs (:mod:`planar_tui.sweep.budget`);
    the scheduler to use (:func:`planar_tui.sweep.execute.scheduler_address`)."""
    from planar_tui.sweep.execute import scheduler_address

    scheduler = scheduler_address(scheduler, workers)
    if prepared:
        from planar_tui.sweep.budget import check_sweep_budget as check

        check(prepared, workers, scheduler)
    return scheduler


def prepare_sweeps(
    loaded: Sequence[Preset],
    out_dir: Path,
    jobs: Sequence[Job] = (),
    plot: Path | None = None,
    *,
    job_plot: Path | None = None,
    resume: bool = False,
) -> list:
    """Every sweep of the presets with its points, all validated, before anything runs:
    the run's planned files (the ``jobs``' files, their figures under ``job_plot``, and
    every sweep's) checked together by :func:`planar_tui.batch.check_planned`, each
    ``plot`` checked drawable, and a checkpoint of the same sweep refused without
    ``resume`` (one of another sweep is replaced, said on stderr). ``plot`` (``--plot``
    of ``sweep``) replaces the sweeps' ``plot`` keys (numbered ``FILE-1.png`` ... for
    several sweeps)."""
    from planar_tui.batch import check_planned, numbered_path, plan_files, plan_outputs
    from planar_tui.sweep.checkpoint import checkpoint_path, existing_fingerprint
    from planar_tui.sweep.points import make_points
    from planar_tui.sweep.service import (
        check_figure,
        check_point_outputs,
        output_path,
        planned_files,
    )
    from planar_tui.sweep.spec import parse_sweeps

    sweeps = [sweep for preset in loaded for sweep in parse_sweeps(preset)]
    if plot is not None:
        sweeps = [
            # absolute: a path given on the command line is taken from the current folder,
            # as the jobs' --plot is, not from --out-dir as the preset's plot key is
            dataclasses.replace(
                sweep, plot=str(numbered_path(plot, number, len(sweeps)).absolute())
            )
            for number, sweep in enumerate(sweeps, start=1)
        ]
    prepared = [(sweep, make_points(sweep)) for sweep in sweeps]
    files = plan_files(plan_outputs(jobs, out_dir, plot=job_plot))
    files += [planned for sweep in sweeps for planned in planned_files(sweep, out_dir)]
    presets = {job.preset_path: job.label for job in jobs}
    presets.update({sweep.preset_path: sweep.label for sweep in sweeps})
    check_planned(files, presets)
    for sweep, points in prepared:
        check_figure(sweep, points)
        check_point_outputs(sweep, out_dir)
    for sweep, _ in prepared:
        checkpoint = checkpoint_path(output_path(sweep, out_dir))
        found = existing_fingerprint(checkpoint)
        if found is None or (resume and found == sweep.fingerprint()):
            continue
        if found == sweep.fingerprint():
            raise PresetError(
                checkpoint, "(checkpoint)",
                f"holds finished points of {sweep.label}, an interrupted run",
                "--resume to finish it, or delete the file to start over",
            )  # fmt: skip
        stderr.print(
            f"note: {checkpoint} belongs to an earlier version of {sweep.label} (the preset "
            "changed): it is replaced", markup=False, highlight=False, soft_wrap=True,
        )  # fmt: skip
    return prepared


def sweep_progress_display(console: Console):
    """A rich display with one bar per sweep: points done/total, failures, rate, ETA."""
    from rich import progress as bar
    from rich.table import Column
    from rich.text import Text

    class RateColumn(bar.ProgressColumn):
        def render(self, task) -> Text:
            speed = task.finished_speed or task.speed
            return Text("-- pt/s" if speed is None else f"{speed:.3g} pt/s")

    return bar.Progress(
        bar.TextColumn("{task.description}", markup=False), bar.BarColumn(bar_width=None),
        bar.MofNCompleteColumn(), bar.TextColumn("{task.fields[failed]} failed"), RateColumn(table_column=Column(no_wrap=True)),
        bar.TextColumn("ETA"), bar.TimeRemainingColumn(), console=console, expand=True,
    )  # fmt: skip


def run_sweeps(
    prepared: Sequence, out_dir: Path, workers: int | None, scheduler: str | None, resume: bool
) -> None:
    """Run validated sweeps, one progress bar each; a summary line per sweep on stdout.
    Exit code 1 when a point failed (its row says why) or a sweep's file could not be
    written (one ``error:`` line each; the later sweeps still run). Every sweep's
    checkpoint is kept until all of them are done, then those of the sweeps whose CSV was
    written are deleted: Ctrl-C keeps them all, so ``--resume`` rebuilds the finished
    sweeps from theirs and computes only what is left."""
    from planar_tui.batch import OutputFailed
    from planar_tui.progress import Progress
    from planar_tui.sweep.execute import default_workers
    from planar_tui.sweep.service import resume_note, run_sweep

    count = workers or default_workers()
    failed = 0
    unwritten = 0
    done = []
    try:
        with sigterm_as_interrupt(), ExitStack() as stack:
            client = None

            def announce(text: str) -> None:
                stderr.print(text, markup=False, highlight=False, soft_wrap=True)

            if prepared and (scheduler is not None or count > 1):
                from planar_tui.sweep.execute import DaskTarget, dask_client

                client = stack.enter_context(dask_client(DaskTarget(count, scheduler), announce))
            for sweep, points in prepared:
                with sweep_progress_display(stderr) as bars:
                    task = bars.add_task(sweep.label, total=len(points), failed=0)

                    def update(state, bars=bars, task=task, label=sweep.label) -> None:
                        if state.stage == label:
                            bars.update(task, completed=state.completed,
                                        failed=int(state.figures.get("failed", 0)))  # fmt: skip

                    try:
                        result = run_sweep(
                            sweep, Progress(on_update=update, should_stop=_INTERRUPTED.is_set),
                            points=points, out_dir=out_dir,
                            resume=resume, client=client, keep_checkpoint=True,
                            announce=announce,
                        )  # fmt: skip
                    except OutputFailed as error:
                        unwritten += 1
                        stderr.print(f"error: {sweep.label}: {error} (finished points are "
                                     "in its checkpoint)", markup=False, highlight=False,
                                     soft_wrap=True)  # fmt: skip
                        continue
                done.append(result)
                failed += result.failed
                resumed = resume_note(result)
                figure = "" if result.figure is None else f", figure {result.figure}"
                stdout.print(
                    f"{sweep.label}: {len(points)} points, {result.failed} failed{resumed} "
                    f"-> {result.output}{figure}", markup=False, highlight=False,
                    soft_wrap=True,
                )  # fmt: skip
                if result.figure_error is not None:
                    unwritten += 1
                    stderr.print(f"error: {sweep.label}: {result.figure_error}", markup=False,
                                 highlight=False, soft_wrap=True)  # fmt: skip
    except Terminated:
        raise fail(
            "terminated: finished points are in the sweeps' checkpoints (--resume "
            "finishes them); the running sweep's CSV was not written",
            ExitCode.TERMINATED,
        ) from None
    except (KeyboardInterrupt, Cancelled):
        raise fail(
            "interrupted: finished points are in the sweeps' checkpoints (--resume "
            "finishes them); the running sweep's CSV was not written",
            ExitCode.INTERRUPTED,
        ) from None
    for result in done:
        if result.checkpoint is not None:
            result.checkpoint.unlink(missing_ok=True)
    if failed or unwritten:
        parts = [f"{failed} sweep point(s) failed (status failed in the CSV)"] if failed else []
        if unwritten:
            parts.append(f"{unwritten} sweep file(s) not written (see above)")
        raise fail("error: " + "; ".join(parts), ExitCode.RUN_FAILED)


@app.command("warmup", cls=Command)
def warmup() -> None:
    """Compile every job kind's kernels into the cache (for batch machines: later runs
    start without the first-run compilation)."""
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

    from planar_tui import progress as core
    from planar_tui.registry import JOB_KINDS
    from planar_tui.warmup import warm_kernels

    columns = (TextColumn("{task.description}", markup=False), BarColumn(bar_width=24),
               MofNCompleteColumn())  # fmt: skip
    with reported_errors(), Progress(*columns, TimeElapsedColumn(), console=stderr) as bars:
        task = bars.add_task("kernels", total=len(JOB_KINDS))

        def update(state) -> None:
            bars.update(task, completed=state.completed, description=state.detail[:40])

        done = warm_kernels(
            JOB_KINDS, core.Progress(on_update=update, should_stop=_INTERRUPTED.is_set)
        )
        bars.update(task, completed=len(JOB_KINDS), description="kernels ready")
    stdout.print(f"compiled: {', '.join(done) or 'nothing (all cached)'}", markup=False)


@app.command("presets", cls=Command)
def list_presets(
    name: Annotated[
        str | None, typer.Argument(help="A bundled preset: print its text (or --copy it).")
    ] = None,
    copy: Annotated[
        Path | None,
        typer.Option(
            "--copy",
            metavar="PATH",
            help="Write the preset NAME to this new file "
            "to start from (an existing file is never overwritten).",
        ),
    ] = None,
) -> None:
    """List the bundled presets, one line each; with NAME, print that preset."""
    from planar_tui.presets import copy_bundled_preset
    from planar_tui.resources import bundled_preset

    with reported_errors():
        if name is None:
            if copy is not None:
                raise PresetError("command line", "--copy", "is given without NAME",
                                  "planar-tui presets NAME --copy PATH")  # fmt: skip
            for path in bundled_presets():
                typer.echo(f"{path.stem:<24} {preset_description(path)}")
        elif copy is None:
            typer.echo(bundled_preset(name).read_text(encoding="utf-8"), nl=False)
        else:
            stdout.print(f"wrote {copy_bundled_preset(name, copy)}", markup=False)


def main() -> None:
    """Run the CLI (called by :func:`planar_tui.entry.main`, the console script): Ctrl-C
    raises ``KeyboardInterrupt`` again (and is remembered, :data:`_INTERRUPTED`) and
    SIGTERM has its default action, except while jobs run (:func:`sigterm_as_interrupt`)."""
    from planar_tui.runtime import configure_process

    try:
        sys.unraisablehook = _unraisable
        signal.signal(signal.SIGINT, _interrupt)
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
        configure_process()
        app(prog_name="planar-tui")
    except KeyboardInterrupt:
        # Ctrl-C before Typer's own handling starts: while it builds the Click command
        # from the commands' signatures (~50 ms after the imports).
        if not _REPORTED:
            os.write(2, b"interrupted: nothing was written\n")
        sys.exit(ExitCode.INTERRUPTED)
    except SystemExit as exit_:
        # Typer turns a Ctrl-C outside the commands' own handling (while a command's
        # modules load, say) into a silent exit 130: say it in one line too.
        if exit_.code == ExitCode.INTERRUPTED and not _REPORTED:
            os.write(2, b"interrupted: nothing was written\n")
        raise
    finally:
        # Exit without the interpreter's last full garbage collection over every object of
        # numba, rich and typer: ~0.3 s of a jitted command's wall time (measured with
        # `planar-tui run paper-a-table4 paper-a-table5`). Reference counting still frees.
        gc.freeze()


if __name__ == "__main__":
    main()
    sys.exit(0)

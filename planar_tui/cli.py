"""The ``planar-tui`` command line (Typer).

Batch jobs run from TOML presets and write CSV. Exit codes: 0 ok, 1 a job failed,
2 bad input (preset or option), 130 interrupted. Progress bars go to stderr; tables
and summaries to stdout. Heavy modules (numba, SALib, Textual) are imported only when
a job or the app runs, so ``planar-tui --help`` is instant.
"""

from __future__ import annotations

import gc
import os
import sys
from collections.abc import Iterator, Mapping, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer
from rich.console import Console

from planar_tui import __version__
from planar_tui.errors import Cancelled, ExitCode, PresetError
from planar_tui.resources import bundled_presets, preset_description

if TYPE_CHECKING:
    from planar_tui.jobkind import Job
    from planar_tui.presets import Preset

app = typer.Typer(
    name="planar-tui",
    help="Terminal workbench for planar robots: NOC dynamics, Sobol/eFAST sensitivity, "
    "3-RRR workspace by interval analysis. Without a command, opens the Textual app.",
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


def fail(message: str, code: ExitCode = ExitCode.BAD_INPUT) -> typer.Exit:
    """Print ``message`` on stderr and return the exit to raise."""
    stderr.print(message, markup=False, highlight=False, soft_wrap=True)
    return typer.Exit(int(code))


@contextmanager
def reported_errors() -> Iterator[None]:
    """Turn preset errors, interrupts and job failures into one line and an exit code."""
    try:
        yield
    except PresetError as error:
        raise fail(str(error), ExitCode.BAD_INPUT) from None
    except (KeyboardInterrupt, Cancelled):
        raise fail(
            "interrupted: the running job's output was not written", ExitCode.INTERRUPTED
        ) from None


def load_presets(arguments: Sequence[str]) -> list[Preset]:
    """Resolve and validate every preset before anything runs."""
    from planar_tui.presets import load_preset
    from planar_tui.resources import resolve_preset

    return [load_preset(resolve_preset(argument)) for argument in arguments]


@contextmanager
def progress_bar(bars, job: Job):
    """One rich progress bar for ``job`` (stage and detail beside it), as a
    :class:`~planar_tui.progress.Progress` for the runner."""
    from planar_tui.progress import Progress

    task = bars.add_task(job.label, total=1.0, detail="")
    warned = set()

    def update(state) -> None:
        if state.warning and state.warning not in warned:
            warned.add(state.warning)
            bars.console.print(f"warning: {job.label}: {state.warning}", markup=False)
        bars.update(
            task,
            completed=state.completed,
            total=state.total,
            description=f"{job.label} {state.stage}".strip(),
            detail=state.detail,
        )

    yield Progress(on_update=update)
    bars.update(task, completed=1.0, total=1.0, description=f"{job.label} done")


def execute(
    jobs: Sequence[Job],
    out_dir: Path,
    *,
    out: Path | None = None,
    extra_out: Mapping[str, Path | None] | None = None,
    show: bool = True,
) -> None:
    """Run ``jobs`` through the batch service, one progress bar each, then print a summary.

    Output paths are checked before the first job runs; each job's files are written as
    soon as it finishes. A job that raises an unexpected error, or an output that cannot be
    written, ends the run with one ``error:`` line and exit code 1 (``PLANAR_TUI_DEBUG=1``
    shows the traceback). ``show`` prints each kind's terminal view.
    """
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn
    from rich.table import Table

    from planar_tui import batch
    from planar_tui.registry import JOB_KINDS

    plans = batch.plan_outputs(jobs, out_dir, out, extra_out)
    batch.check_plans(plans)
    columns = (
        TextColumn("{task.description}"),
        BarColumn(bar_width=24),
        MofNCompleteColumn(),
        TimeElapsedColumn(),
        TextColumn("{task.fields[detail]}"),
    )

    @contextmanager
    def progress_for(job: Job):
        with (
            Progress(*columns, console=stderr, transient=False) as bars,
            progress_bar(bars, job) as progress,
        ):
            yield progress

    def render(job: Job, result) -> None:
        view = JOB_KINDS[job.kind].render
        if show and view is not None:
            view(job, result, stdout)

    debug = os.environ.get("PLANAR_TUI_DEBUG", "") not in ("", "0")
    try:
        rows = list(batch.run_plans(plans, progress_for, render))
    except batch.JobFailed as error:
        if debug:
            raise error.__cause__ from None
        raise fail(f"error: {error}", ExitCode.RUN_FAILED) from None
    except batch.OutputFailed as error:
        raise fail(f"error: {error}", ExitCode.RUN_FAILED) from None

    summary = Table(title="planar-tui run summary", title_justify="left", show_lines=True)
    summary.add_column("job", no_wrap=True)
    summary.add_column("seconds", justify="right", no_wrap=True)
    summary.add_column("output and result", overflow="fold")
    for row in rows:
        summary.add_row(row.label, f"{row.seconds:.3f}", f"{row.output}\n{row.summary}")
    stdout.print(summary)


def run_kind(
    kind: str,
    preset_argument: str,
    out: Path | None,
    out_dir: Path,
    options: Mapping[str, object] | None = None,
    *,
    extra_out: Mapping[str, Path | None] | None = None,
    show: bool = True,
) -> None:
    """Run every job of one kind in a preset (the ``simulate``/``torques``... commands);
    ``options`` are command-line overrides, applied and checked by the job kind."""
    from planar_tui.batch import apply_overrides

    with reported_errors():
        (preset,) = load_presets([preset_argument])
        jobs = preset.jobs_of(kind)
        if not jobs:
            raise PresetError(
                preset.path, kind, f"no [{kind}] job in this preset", f"a [{kind}] table"
            )
        if options:
            jobs = apply_overrides(jobs, options)
        execute(jobs, out_dir, out=out, extra_out=extra_out, show=show)


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
    """Without a command: open the Textual app on a bundled preset."""
    if context.invoked_subcommand is None:
        open_app(None)


def open_app(preset_argument: str | None) -> None:
    """Open the Textual workbench (imported only now)."""
    from planar_tui.app import run_app

    with reported_errors():
        run_app(preset_argument)


@app.command()
def tui(
    preset: Annotated[
        str | None,
        typer.Argument(help="Preset file or bundled preset name (default: paper-a-table1)."),
    ] = None,
) -> None:
    """Open the Textual workbench on a preset (what `planar-tui` alone does)."""
    open_app(preset)


@app.command()
def simulate(preset: PresetArg, out: OutOption = None, out_dir: OutDirOption = Path(".")) -> None:
    """Integrate the forward dynamics (RK4) of every simulate job; one CSV per job."""
    run_kind("simulate", preset, out, out_dir)


@app.command()
def torques(preset: PresetArg, out: OutOption = None, out_dir: OutDirOption = Path(".")) -> None:
    """Inverse dynamics at the listed states of every torques job; one CSV per job."""
    run_kind("torques", preset, out, out_dir)


@app.command()
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
    out: OutOption = None,
    out_dir: OutDirOption = Path("."),
) -> None:
    """Sobol'/eFAST sensitivity of the joint torques of every sensitivity job; one CSV each."""

    options = {"methods": method, "samples": samples, "seed": seed}
    run_kind("sensitivity", preset, out, out_dir, options)


@app.command()
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
    out_dir: OutDirOption = Path("."),
) -> None:
    """3-RRR workspace of every workspace job: summary CSV, optional boxes CSV and map."""

    options = {"form": form, "precision_cm": precision}
    extra_out = {"boxes": boxes}
    run_kind("workspace", preset, out, out_dir, options, extra_out=extra_out, show=show_map)


@app.command()
def run(
    presets: Annotated[list[str], typer.Argument(help="Preset files or bundled preset names.")],
    out_dir: OutDirOption = Path("."),
) -> None:
    """Run every job of every preset; output files named as the presets say."""
    with reported_errors():
        loaded = load_presets(presets)
        execute([job for preset in loaded for job in preset.jobs], out_dir)


@app.command("warmup")
def warmup() -> None:
    """Compile every job kind's kernels into the cache (for batch machines: later runs
    start without the first-run compilation)."""
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

    from planar_tui import progress as core
    from planar_tui.registry import JOB_KINDS
    from planar_tui.warmup import warm_kernels

    columns = (TextColumn("{task.description}"), BarColumn(bar_width=24), MofNCompleteColumn())
    with reported_errors(), Progress(*columns, TimeElapsedColumn(), console=stderr) as bars:
        task = bars.add_task("kernels", total=len(JOB_KINDS))

        def update(state) -> None:
            bars.update(task, completed=state.completed, description=state.detail[:40])

        done = warm_kernels(JOB_KINDS, core.Progress(on_update=update))
        bars.update(task, completed=len(JOB_KINDS), description="kernels ready")
    stdout.print(f"compiled: {', '.join(done) or 'nothing (all cached)'}", markup=False)


@app.command("presets")
def list_presets() -> None:
    """List the bundled presets, one line each."""
    for path in bundled_presets():
        typer.echo(f"{path.stem:<24} {preset_description(path)}")


def main() -> None:
    """Console-script entry point."""
    from planar_tui.runtime import configure_process

    configure_process()
    try:
        app(prog_name="planar-tui")
    finally:
        # Exit without the interpreter's last full garbage collection over every object of
        # numba, rich and typer: ~0.3 s of a jitted command's wall time (measured with
        # `planar-tui run paper-a-table4 paper-a-table5`). Reference counting still frees.
        gc.freeze()


if __name__ == "__main__":
    main()
    sys.exit(0)

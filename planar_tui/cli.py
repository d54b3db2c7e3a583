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
from collections.abc import Callable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import Annotated

import typer
from rich.console import Console

from planar_tui import __version__
from planar_tui.errors import Cancelled, ExitCode, PresetError
from planar_tui.jobs import JOB_KINDS, JobResult
from planar_tui.paths import bundled_presets, preset_description, resolve_preset
from planar_tui.presets import Job, Preset, load_preset

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
    return [load_preset(resolve_preset(argument)) for argument in arguments]


def numbered_path(base: Path, number: int, count: int) -> Path:
    """``base`` itself for a single job, ``stem-NUMBER.suffix`` when there are several."""
    return base if count == 1 else base.with_name(f"{base.stem}-{number}{base.suffix or '.csv'}")


def run_one(job: Job, progress_bars) -> JobResult:
    """Run one job with its own rich progress bar (stage and detail beside it)."""
    from planar_tui.progress import Progress

    task = progress_bars.add_task(job.label, total=1.0, detail="")

    def update(state) -> None:
        progress_bars.update(
            task,
            completed=state.completed,
            total=state.total,
            description=f"{job.label} {state.stage}".strip(),
            detail=state.detail,
        )

    result = JOB_KINDS[job.kind].run(job, Progress(on_update=update))
    progress_bars.update(task, completed=1.0, total=1.0, description=f"{job.label} done")
    return result


def output_paths(
    jobs: Sequence[Job],
    out_dir: Path,
    out: Path | None,
    extra_out: Mapping[str, Path | None] | None,
) -> list[tuple[Path, dict[str, Path]]]:
    """Every job's main CSV path and its extra tables' paths, in job order.

    The main CSV goes to ``out_dir / job.output``, or to ``out`` (numbered ``FILE-1.csv``,
    ``FILE-2.csv`` ... when there are several jobs). Extra tables (e.g. a workspace's
    ``boxes``) go where the job kind's ``extra_outputs`` says, relative to ``out_dir``, or
    to the paths in ``extra_out`` by table name (numbered likewise).
    """
    plans = []
    for number, job in enumerate(jobs, start=1):
        main_path = numbered_path(out, number, len(jobs)) if out else out_dir / job.output
        extra_paths = {
            name: out_dir / relative
            for name, relative in JOB_KINDS[job.kind].extra_outputs(job.spec).items()
        }
        for name, override in (extra_out or {}).items():
            if override is not None:
                extra_paths[name] = numbered_path(override, number, len(jobs))
        plans.append((main_path, extra_paths))
    return plans


def check_writable(path: Path) -> None:
    """Refuse, before any job runs, an output path that cannot be written: a folder, or a
    path whose nearest existing ancestor is not a writable folder."""
    if path.is_dir():
        raise PresetError(path, "(output)", "is a folder", "a CSV file path")
    ancestor = path.parent
    while not ancestor.exists() and ancestor != ancestor.parent:
        ancestor = ancestor.parent
    if not ancestor.is_dir() or not os.access(ancestor, os.W_OK | os.X_OK):
        raise PresetError(
            path, "(output)", f"cannot be created: {ancestor} is not a writable folder",
            "a path inside a writable folder",
        )  # fmt: skip


def execute(
    jobs: Sequence[Job],
    out_dir: Path,
    *,
    out: Path | None = None,
    extra_out: Mapping[str, Path | None] | None = None,
    show: bool = True,
) -> list[tuple[Job, JobResult, Path]]:
    """Run ``jobs`` in order, writing each job's CSV files atomically as soon as it finishes.

    Output paths (see :func:`output_paths`) are checked before the first job runs. A job
    that raises an unexpected error, or an output that cannot be written, ends the run
    with one ``error:`` line and exit code 1 (``PLANAR_TUI_DEBUG=1`` shows the traceback).
    ``show`` prints each kind's terminal view. A summary table follows the last job.
    """
    import time

    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn
    from rich.table import Table

    from planar_tui.csvio import write_csv_atomic

    plans = output_paths(jobs, out_dir, out, extra_out)
    for main_path, extra_paths in plans:
        for path in (main_path, *extra_paths.values()):
            check_writable(path)
    columns = (
        TextColumn("{task.description}"),
        BarColumn(bar_width=24),
        MofNCompleteColumn(),
        TimeElapsedColumn(),
        TextColumn("{task.fields[detail]}"),
    )
    debug = os.environ.get("PLANAR_TUI_DEBUG", "") not in ("", "0")
    done: list[tuple[Job, JobResult, Path, float]] = []
    for job, (path, extra_paths) in zip(jobs, plans, strict=True):
        started = time.perf_counter()
        try:
            with Progress(*columns, console=stderr, transient=False) as bars:
                result = run_one(job, bars)
        except (PresetError, Cancelled, KeyboardInterrupt):
            raise
        except Exception as error:
            if debug:
                raise
            message = f"error: {job.label} failed: {type(error).__name__}: {error}"
            raise fail(message, ExitCode.RUN_FAILED) from None
        seconds = time.perf_counter() - started
        try:
            write_csv_atomic(path, result.table)
            for name, extra_path in extra_paths.items():
                write_csv_atomic(extra_path, result.extra_tables[name])
        except OSError as error:
            where = error.filename or path
            raise fail(
                f"error: {where}: cannot write: {error.strerror}", ExitCode.RUN_FAILED
            ) from None
        if show:
            JOB_KINDS[job.kind].show(job, result, stdout)
        done.append((job, result, path, seconds))

    summary = Table(title="planar-tui run summary", title_justify="left", show_lines=True)
    summary.add_column("job", no_wrap=True)
    summary.add_column("seconds", justify="right", no_wrap=True)
    summary.add_column("output and result", overflow="fold")
    for job, result, path, seconds in done:
        summary.add_row(job.label, f"{seconds:.3f}", f"{path}\n{result.summary}")
    stdout.print(summary)
    return [(job, result, path) for job, result, path, _ in done]


def run_kind(
    kind: str,
    preset_argument: str,
    out: Path | None,
    out_dir: Path,
    adjust: Callable[[Job], Job] | None = None,
    *,
    extra_out: Mapping[str, Path | None] | None = None,
    show: bool = True,
) -> None:
    """Run every job of one kind in a preset (the ``simulate``/``torques``... commands);
    ``adjust`` applies command-line overrides to each job before anything runs."""
    with reported_errors():
        (preset,) = load_presets([preset_argument])
        jobs = preset.jobs_of(kind)
        if not jobs:
            raise PresetError(
                preset.path, kind, f"no [{kind}] job in this preset", f"a [{kind}] table"
            )
        if adjust is not None:
            jobs = tuple(adjust(job) for job in jobs)
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

    def adjust(job: Job) -> Job:
        import dataclasses

        from planar_tui.jobs.sensitivity import with_overrides

        spec = with_overrides(job.spec, methods=method, samples=samples, seed=seed)
        return dataclasses.replace(job, spec=spec)

    run_kind("sensitivity", preset, out, out_dir, adjust)


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

    def adjust(job: Job) -> Job:
        import dataclasses

        from planar_tui.jobs.workspace import FORMS, with_overrides

        if form is not None and form not in FORMS:
            raise PresetError("--form", "form", f"is {form!r}", "one of " + ", ".join(FORMS))
        if precision is not None and not precision > 0:
            raise PresetError("--precision", "precision", f"is {precision:g}", "a number > 0")
        return dataclasses.replace(
            job, spec=with_overrides(job.spec, form=form, precision_cm=precision)
        )

    run_kind("workspace", preset, out, out_dir, adjust, extra_out={"boxes": boxes}, show=show_map)


@app.command()
def run(
    presets: Annotated[list[str], typer.Argument(help="Preset files or bundled preset names.")],
    out_dir: OutDirOption = Path("."),
) -> None:
    """Run every job of every preset; output files named as the presets say."""
    with reported_errors():
        loaded = load_presets(presets)
        execute([job for preset in loaded for job in preset.jobs], out_dir)


@app.command("presets")
def list_presets() -> None:
    """List the bundled presets, one line each."""
    for path in bundled_presets():
        typer.echo(f"{path.stem:<24} {preset_description(path)}")


def main() -> None:
    """Console-script entry point."""
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

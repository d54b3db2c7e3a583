"""The ``planar-tui`` command line (Typer).

Batch jobs run from TOML presets and write CSV. Exit codes: 0 ok, 1 a job failed,
2 bad input (preset or option), 130 interrupted (Ctrl-C), 143 terminated (SIGTERM).
Progress bars go to stderr; tables and summaries to stdout. Heavy modules (numpy, numba,
SALib, Textual) are imported only when a job or the app runs, so ``planar-tui --help`` is
instant.

The commands are made by :func:`build_app` when the CLI runs, from the registry: each
job kind's own command (:mod:`planar_tui.cli.kinds`, from its declared
:class:`~planar_tui.jobkind.Command`), then the commands that are not one kind's
(:data:`COMMANDS`: ``run``, ``plot``, ``sweep``, ``warmup``, ``presets``; a new one is a
function here and a line there). A command only turns its options into a
:class:`~planar_tui.plan.RunPlan` (:func:`planar_tui.plan.plan_run`) and prints
(:mod:`planar_tui.cli.running`, :mod:`planar_tui.cli.output`).
"""

from __future__ import annotations

import gc
import os
import signal
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Annotated, Any

import typer

from planar_tui import __version__
from planar_tui.cli import output
from planar_tui.cli.kinds import JobOption, OutDirOption, PlotOption, PresetArg, kind_command
from planar_tui.cli.output import (
    _INTERRUPTED,
    Command,
    Group,
    check_figure_option,
    check_workers,
    fail,
    job_progress_display,
    load_presets,
    progress_bar,
    reported_errors,
    stderr,
    stdout,
)
from planar_tui.errors import ExitCode, PresetError
from planar_tui.resources import bundled_presets, preset_description

__all__ = ["app", "build_app", "job_progress_display", "main", "progress_bar"]

HELP = (
    "Terminal workbench for planar robots: NOC dynamics, Sobol/eFAST sensitivity, "
    "3-RRR workspace by interval analysis. Without a command, opens the Textual app "
    "(in a terminal; without one, prints this help and exits with code 2)."
)


def version_callback(value: bool) -> None:
    if value:
        stdout.print(f"planar-tui {__version__}")
        raise typer.Exit()


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


def tui(
    preset: Annotated[
        str | None,
        typer.Argument(help="Preset file or bundled preset name (default: paper-a-table1)."),
    ] = None,
) -> None:
    """Open the Textual workbench on a preset (what `planar-tui` alone does)."""
    open_app(preset)


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
        envvar="PLANAR_TUI_SCHEDULER",
        metavar="ADDRESS",
        help="Sweeps: submit the points to this existing Dask scheduler (tcp://host:8786).",
    ),
]
ResumeOption = Annotated[
    bool,
    typer.Option("--resume", help="Sweeps: finish an interrupted sweep from its checkpoint."),
]


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
    from planar_tui.cli.running import print_notes, run_jobs, run_sweeps

    with reported_errors():
        from planar_tui.batch import select_jobs
        from planar_tui.plan import plan_run

        check_figure_option(plot)
        check_workers(workers)
        loaded = load_presets(presets)
        jobs = select_jobs([job for preset in loaded for job in preset.jobs], job_name)
        plan = plan_run(jobs, out_dir, plot=plot, sweeps_of=[] if job_name else loaded,
                        resume=resume)  # fmt: skip
        print_notes(plan)
        if plan.jobs:
            run_jobs(plan)
        run_sweeps(plan, workers, scheduler)


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


def sweep_command(
    preset: PresetArg,
    workers: WorkersOption = None,
    scheduler: SchedulerOption = None,
    resume: ResumeOption = False,
    out_dir: OutDirOption = Path("."),
    plot: PlotOption = None,
) -> None:
    """Run the preset's sweeps ([[sweep]] tables): one CSV each, one row per point."""
    from planar_tui.cli.running import print_notes, run_sweeps

    with reported_errors():
        from planar_tui.plan import plan_run

        check_figure_option(plot)
        check_workers(workers)
        (loaded,) = load_presets([preset])
        plan = plan_run([], out_dir, sweeps_of=[loaded], sweep_plot=plot, resume=resume)
        if not plan.sweeps:
            raise PresetError(loaded.path, "sweep", "no [[sweep]] table in this preset",
                              "a [[sweep]] table")  # fmt: skip
        print_notes(plan)
        run_sweeps(plan, workers, scheduler)


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

        done = warm_kernels(
            JOB_KINDS, core.Progress(on_update=update, should_stop=_INTERRUPTED.is_set)
        )
        bars.update(task, completed=len(JOB_KINDS), description="kernels ready")
    stdout.print(f"compiled: {', '.join(done) or 'nothing (all cached)'}", markup=False)


def list_presets() -> None:
    """List the bundled presets, one line each."""
    for path in bundled_presets():
        typer.echo(f"{path.stem:<24} {preset_description(path)}")


#: The commands that are not one job kind's, in the order of ``planar-tui --help``, after
#: ``tui`` and the kinds' own: (name, function).
COMMANDS: tuple[tuple[str, Callable[..., None]], ...] = (
    ("run", run),
    ("plot", plot_csv),
    ("sweep", sweep_command),
    ("warmup", warmup),
    ("presets", list_presets),
)


def build_app() -> typer.Typer:
    """The ``planar-tui`` Typer app, its job commands made from the registry now (a kind
    registered before this call has its command, :func:`planar_tui.registry.registered`)."""
    from planar_tui.registry import JOB_KINDS

    app = typer.Typer(name="planar-tui", cls=Group, help=HELP, add_completion=False,
                      no_args_is_help=False, pretty_exceptions_enable=False)  # fmt: skip
    app.callback(invoke_without_command=True)(root)
    app.command(cls=Command)(tui)
    for kind in JOB_KINDS.values():
        if kind.command is not None:
            app.command(kind.command.name, cls=Command, help=kind.command.help)(kind_command(kind))
    for name, function in COMMANDS:
        app.command(name, cls=Command)(function)
    return app


def __getattr__(name: str) -> Any:
    """``planar_tui.cli.app``: the app built now (:func:`build_app`)."""
    if name == "app":
        return build_app()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def main() -> None:
    """Run the CLI (called by :func:`planar_tui.entry.main`, the console script): Ctrl-C
    raises ``KeyboardInterrupt`` again (and is remembered, :data:`_INTERRUPTED`) and
    SIGTERM has its default action, except while jobs run (:func:`sigterm_as_interrupt`)."""
    from planar_tui.runtime import configure_process

    try:
        sys.unraisablehook = output._unraisable
        signal.signal(signal.SIGINT, output._interrupt)
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
        configure_process()
        build_app()(prog_name="planar-tui")
    except KeyboardInterrupt:
        # Ctrl-C before Typer's own handling starts: while it builds the Click command
        # from the commands' signatures (~50 ms after the imports).
        if not output._REPORTED:
            os.write(2, b"interrupted: nothing was written\n")
        sys.exit(ExitCode.INTERRUPTED)
    except SystemExit as exit_:
        # Typer turns a Ctrl-C outside the commands' own handling (while a command's
        # modules load, say) into a silent exit 130: say it in one line too.
        if exit_.code == ExitCode.INTERRUPTED and not output._REPORTED:
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

"""The commands of ``planar-tui`` that are not one job kind's: ``tui``, ``run``, ``plot``,
``sweep``, ``optimise``, ``warmup`` and ``presets`` (:data:`COMMANDS`). A new one (``export``, say) is a
function here and a line in :data:`COMMANDS`; :func:`planar_tui.cli.build_app` adds them
after the job kinds' own commands. A command turns its options into a
:class:`~planar_tui.plan.RunPlan` (:func:`planar_tui.plan.plan_run`) and prints
(:mod:`planar_tui.cli.running`)."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Annotated

import typer

from planar_tui.batch import check_writable
from planar_tui.cli import interop
from planar_tui.cli.kinds import JobOption, OutDirOption, PlotOption, PresetArg
from planar_tui.cli.output import (
    check_figure_option,
    check_workers,
    fail,
    load_presets,
    progress_display,
    reported_errors,
    said,
    stdout,
)
from planar_tui.cli.running import print_notes, run_jobs, run_optimisations, run_sweeps
from planar_tui.cli.serve import AppPresetArg, OpenOption, serve
from planar_tui.errors import PresetError
from planar_tui.figures import UnknownTable, figure_for_table, read_table
from planar_tui.figures.canvas import display_notes, save
from planar_tui.figures.dispatch import BOUNDED_FIGURES, is_same_file, recognise
from planar_tui.overrides import select_jobs
from planar_tui.plan import check_has_work, has_studies, plan_run
from planar_tui.presets import copy_bundled_preset
from planar_tui.registry import JOB_KINDS
from planar_tui.resources import bundled_preset, bundled_presets, preset_description


def open_app(preset_argument: str | None, opened: tuple[str, ...] = ()) -> None:
    """Open the Textual workbench (imported only now), with result CSVs ``opened`` into
    its run history."""
    with reported_errors():
        from planar_tui.app import run_app

        run_app(preset_argument, opened)


def tui(preset: AppPresetArg = None, open_results: OpenOption = None) -> None:
    """Open the Textual workbench on a preset (what `planar-tui` alone does)."""
    open_app(preset, tuple(open_results or ()))


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
    say, then the presets' sweeps and optimisations (not with --job)."""
    with reported_errors():
        check_figure_option(plot)
        check_workers(workers)
        loaded = load_presets(presets)
        for preset in loaded:
            check_has_work(preset)
        jobs = select_jobs([job for preset in loaded for job in preset.jobs], job_name)
        studies = [] if job_name else [preset for preset in loaded if has_studies(preset)]
        if studies:  # a run of jobs alone imports no sweep module
            from planar_tui.sweep.execute import scheduler_address

            scheduler = scheduler_address(scheduler, workers)
        plan = plan_run(
            jobs,
            out_dir,
            plot=plot,
            sweeps_of=studies,
            optimise_of=studies,
            resume=resume,
            workers=workers,
            scheduler=scheduler,
        )
        print_notes(plan)
        if plan.jobs:
            run_jobs(plan, "run")
        if plan.sweeps:
            run_sweeps(plan, workers, scheduler)
        if plan.optimisations:
            run_optimisations(plan, workers, scheduler)


#: Rows of a result CSV from which ``plot`` says, before drawing, that it can take
#: minutes: 200 000 workspace boxes took 43 s (load 14 on 2 cores), and the 64 MiB a
#: result CSV may have holds about 900 000.
SLOW_FIGURE_ROWS = 100_000


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
        check_figure_option(out, "--out")
        if result.is_dir():
            raise PresetError(result, "(file)", "is a folder", "a result CSV file")
        target = out if out is not None else result.with_suffix(".png")

        if is_same_file(result, target):
            raise PresetError(
                "command line",
                "--out",
                f"is the input {result} (it would be overwritten by its figure)",
                "another figure file",
            )

        try:
            table = read_table(result)
        except FileNotFoundError:
            raise PresetError(result, "(file)", "no such file", "a result CSV") from None
        except (OSError, UnicodeDecodeError, ValueError) as error:
            raise PresetError(
                result, "(file)", f"cannot be read: {error}", "a result CSV"
            ) from None
        check_writable(target, "figure file")

        slow = recognise(table.header) not in BOUNDED_FIGURES
        if slow and len(table.rows) > SLOW_FIGURE_ROWS:  # minutes to draw: say so first
            said(
                f"drawing {len(table.rows):,} rows of {result.name}: a figure of this size can "
                "take minutes"
            )
        try:
            figure = figure_for_table(table, result.name)
        except UnknownTable as error:
            raise PresetError(result, "(header)", *error.args) from None
        except ValueError as error:  # no rows, or a recognised table the figure cannot show
            raise PresetError(result, "(content)", f"cannot be drawn: {error}") from None
        for note in display_notes(figure):
            said(f"{result.name}: {note}")
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
    run_studies("sweep", preset, workers, scheduler, resume, out_dir, plot)


def optimise_command(
    preset: PresetArg,
    workers: WorkersOption = None,
    scheduler: SchedulerOption = None,
    resume: ResumeOption = False,
    out_dir: OutDirOption = Path("."),
    plot: PlotOption = None,
) -> None:
    """Run the preset's optimisations (its optimise tables): a CSV of every evaluation, the
    optimum or Pareto set re-run at the job's own settings."""
    run_studies("optimise", preset, workers, scheduler, resume, out_dir, plot)


def run_studies(
    table: str,
    preset: str,
    workers: int | None,
    scheduler: str | None,
    resume: bool,
    out_dir: Path,
    plot: Path | None,
) -> None:
    """The ``sweep`` and ``optimise`` commands: the preset's ``[[table]]`` tables planned
    (refused, exit 2, when there is none) and run."""
    with reported_errors():
        check_figure_option(plot)
        check_workers(workers)
        from planar_tui.sweep.execute import scheduler_address

        scheduler = scheduler_address(scheduler, workers)
        (loaded,) = load_presets([preset])
        sweeps = table == "sweep"
        plan = plan_run(
            [],
            out_dir,
            sweeps_of=[loaded] if sweeps else [],
            sweep_plot=plot if sweeps else None,
            optimise_of=[] if sweeps else [loaded],
            optimise_plot=None if sweeps else plot,
            resume=resume,
            workers=workers,
            scheduler=scheduler,
        )
        if not (plan.sweeps if sweeps else plan.optimisations):
            article = "a" if sweeps else "an"
            raise PresetError(
                loaded.path,
                table,
                f"no [[{table}]] table in this preset",
                f"{article} [[{table}]] table",
            )
        print_notes(plan)
        (run_sweeps if sweeps else run_optimisations)(plan, workers, scheduler)


def warmup() -> None:
    """Compile every job kind's kernels into the cache (for batch machines: later runs
    start without the first-run compilation)."""
    from planar_tui.warmup import missing, warm_kernels_in_processes

    with reported_errors():
        todo = missing(JOB_KINDS)  # warm-up units: a kind, or a part of one
        with progress_display("warmup") as progress:
            done = warm_kernels_in_processes(todo, progress)
    stdout.print(f"compiled: {', '.join(done) or 'nothing (all cached)'}", markup=False)


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
    with reported_errors():
        if name is None:
            if copy is not None:
                raise PresetError(
                    "command line",
                    "--copy",
                    "is given without NAME",
                    "planar-tui presets NAME --copy PATH",
                )
            paths = bundled_presets()
            width = max((len(path.stem) for path in paths), default=0)
            for path in paths:
                typer.echo(f"{path.stem:<{width}}  {preset_description(path)}")
        elif copy is None:
            typer.echo(bundled_preset(name).read_text(encoding="utf-8"), nl=False)
        else:
            stdout.print(f"wrote {copy_bundled_preset(name, copy)}", markup=False)


#: The commands that are not one job kind's, in the order of ``planar-tui --help`` (``tui``
#: first, then the job kinds' own commands, then the others): (name, function).
COMMANDS: tuple[tuple[str, Callable[..., None]], ...] = (
    ("tui", tui),
    ("run", run),
    ("plot", plot_csv),
    ("sweep", sweep_command),
    ("optimise", optimise_command),
    ("warmup", warmup),
    ("presets", list_presets),
    ("serve", serve),
    *interop.COMMANDS,
)

"""Running a :class:`~planar_tui.plan.RunPlan` in the terminal: its jobs through the batch
service, one progress bar each, then a summary table; its sweeps, one bar each, then a
line each. What runs and where it writes was decided by the plan, before anything ran."""

from __future__ import annotations

import os
from collections.abc import Callable
from contextlib import AbstractContextManager, ExitStack
from pathlib import Path
from typing import TYPE_CHECKING, Any

from planar_tui import batch
from planar_tui.cli.output import (
    fail,
    progress_display,
    said,
    sigterm_as_interrupt,
    stdout,
)
from planar_tui.errors import Cancelled, ExitCode, OutputFailed, Terminated
from planar_tui.registry import JOB_KINDS

if TYPE_CHECKING:
    from planar_tui.jobkind import Job
    from planar_tui.plan import RunPlan
    from planar_tui.progress import Progress


def print_notes(plan: RunPlan) -> None:
    """What the plan says before it runs (a replaced checkpoint), on stderr."""
    for note in plan.notes:
        said(note)


def summary_title(command: str, plan: RunPlan) -> str:
    """The summary table's title: the command, the presets it ran and how many jobs
    (``simulate paper-a-table1: 3 jobs``)."""
    presets = dict.fromkeys(Path(entry.job.preset_path).stem for entry in plan.jobs)
    count = len(plan.jobs)
    return f"{command} {', '.join(presets)}: {count} job{'s' if count != 1 else ''}"


def run_jobs(
    plan: RunPlan,
    command: str,
    *,
    show: bool = True,
    after: Callable[[Job, Any], None] | None = None,
) -> None:
    """Run the plan's jobs through the batch service, one progress display each
    (:func:`~planar_tui.cli.output.progress_display`), then print a summary titled by
    ``command`` and the presets (:func:`summary_title`): its ``compile s`` are the first
    run's kernel compilation (the stage :data:`planar_tui.warmup.STAGE`), its ``run s``
    the rest of the job (a workspace CSV's ``seconds`` are its computation alone). Each
    job's files are written as soon as it finishes. A job that raises an
    unexpected error, or an output that cannot be written, ends the run with one
    ``error:`` line and exit code 1 (``PLANAR_TUI_DEBUG=1`` shows the traceback). ``show``
    prints each kind's terminal view; ``after(job, result)`` writes what the command's
    other options ask once a job's files are written (:func:`planar_tui.cli.interop.
    job_exports`)."""
    from rich.table import Table
    from rich.text import Text

    def progress_for(job: Job) -> AbstractContextManager[Progress]:
        return progress_display(job.label)

    def render(job: Job, result) -> None:
        if after is not None:
            after(job, result)
        view = JOB_KINDS[job.kind].render
        if show and view is not None:
            view(job, result, stdout)

    debug = os.environ.get("PLANAR_TUI_DEBUG", "") not in ("", "0")
    try:
        with sigterm_as_interrupt():
            rows = list(batch.run_plans(plan.jobs, progress_for, render))
    except batch.JobFailed as error:
        if debug:
            raise error.__cause__ from None
        raise fail(f"error: {error}", ExitCode.RUN_FAILED) from None
    except (OutputFailed, batch.NonFiniteResult) as error:
        raise fail(f"error: {error}", ExitCode.RUN_FAILED) from None

    summary = Table(title=summary_title(command, plan), title_justify="left", show_lines=True)
    names = [(row.label, shown_path(row.output, plan.out_dir)) for row in rows]
    summary.add_column("job and file", no_wrap=True, overflow="fold")
    summary.add_column("run s", justify="right", no_wrap=True)
    summary.add_column("compile s", justify="right", no_wrap=True)
    summary.add_column("result")
    for row, (label, name) in zip(rows, names, strict=True):
        summary.add_row(
            Text(f"{label}\n{name}"),
            f"{row.seconds - row.compile_seconds:.3f}",
            f"{row.compile_seconds:.3f}",
            Text(row.summary),
        )
    stdout.print(summary)
    if plan.out_dir is not None and any(is_inside(row.output, plan.out_dir) for row in rows):
        stdout.print(f"files in {plan.out_dir}", markup=False, highlight=False, soft_wrap=True)


def is_inside(path: Path, folder: Path) -> bool:
    """Whether ``path`` lies in ``folder`` (compared as absolute paths)."""
    return Path(os.path.abspath(path)).is_relative_to(os.path.abspath(folder))


def shown_path(path: Path, out_dir: Path | None) -> str:
    """A written file as the summary names it: relative to the output folder when inside
    it (the folder is said once, below the table), else as given."""
    if out_dir is None or not is_inside(path, out_dir):
        return str(path)
    return os.path.relpath(os.path.abspath(path), os.path.abspath(out_dir))


def study_client(stack: ExitStack, wanted: bool, workers: int | None, scheduler: str | None) -> Any:
    """The Dask client a run's sweeps (or optimisations) share, entered on ``stack``:
    ``None`` when there are none (``wanted`` false) or they run in this process (one
    worker, no scheduler); else a local cluster of ``workers`` processes (default: the
    cores) or the scheduler at ``scheduler``."""
    from planar_tui.sweep.execute import DaskTarget, dask_client, default_workers

    count = workers or default_workers()
    if not wanted or (scheduler is None and count <= 1):
        return None

    return stack.enter_context(dask_client(DaskTarget(count, scheduler), said))


def run_sweeps(plan: RunPlan, workers: int | None, scheduler: str | None) -> None:
    """Run the plan's sweeps, one progress bar each; a summary line per sweep on stdout.
    Exit code 1 when a point failed (its row says why) or a sweep's file could not be
    written (one ``error:`` line each; the later sweeps still run). Every sweep's
    checkpoint is kept until all of them are done, then those of the sweeps whose CSV was
    written are deleted: Ctrl-C keeps them all, so ``--resume`` rebuilds the finished
    sweeps from theirs and computes only what is left."""
    from planar_tui.sweep.service import resume_note, run_sweep  # a plain run: no sweep

    failed = 0
    unwritten = 0
    done = []
    try:
        with sigterm_as_interrupt(), ExitStack() as stack:
            client = study_client(stack, bool(plan.sweeps), workers, scheduler)
            for entry in plan.sweeps:
                sweep, points = entry.sweep, entry.points
                try:
                    with progress_display(sweep.label, "pt") as progress:
                        result = run_sweep(
                            sweep,
                            progress,
                            points=points,
                            out_dir=plan.out_dir,
                            resume=plan.resume,
                            client=client,
                            keep_checkpoint=True,
                            announce=said,
                        )
                except OutputFailed as error:
                    unwritten += 1
                    said(f"error: {sweep.label}: {error} (finished points are in its checkpoint)")
                    continue
                done.append(result)
                failed += result.failed
                resumed = resume_note(result)
                figure = "" if result.figure is None else f", figure {result.figure}"
                stdout.print(
                    f"{sweep.label}: {len(points)} points, {result.failed} failed{resumed} "
                    f"-> {result.output}{figure}",
                    markup=False,
                    highlight=False,
                    soft_wrap=True,
                )
                if result.figure_error is not None:
                    unwritten += 1
                    said(f"error: {sweep.label}: {result.figure_error}")
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


def run_optimisations(plan: RunPlan, workers: int | None, scheduler: str | None) -> None:
    """Run the plan's optimisations, one progress bar each (evaluations, failures), a
    summary line each on stdout: its evaluations, failures, the optimum or Pareto set
    re-run at the job's settings and its files. An infeasible evaluation (a design its job
    refuses: a centre its mode cannot reach) is the optimisation's business and counted;
    a failed one (the job broke) is counted too, the run goes on and its files are written,
    and the exit code is 1, as for a failed sweep point. Ctrl-C exits 130 with every
    finished evaluation in the checkpoint (``--resume``)."""
    from planar_tui.optimise.run import run_optimisation  # a plain run: no optimiser

    unwritten = 0
    failed = 0
    try:
        with sigterm_as_interrupt(), ExitStack() as stack:
            client = study_client(stack, bool(plan.optimisations), workers, scheduler)
            for opt in plan.optimisations:
                try:
                    with progress_display(opt.label, "eval") as progress:
                        result = run_optimisation(
                            opt,
                            progress,
                            client=client,
                            out_dir=plan.out_dir,
                            resume=plan.resume,
                            announce=said,
                        )
                except OutputFailed as error:
                    unwritten += 1
                    said(
                        f"error: {opt.label}: {error} (finished evaluations are in its checkpoint)"
                    )
                    continue
                best = result.certified
                failed += result.failed
                found = (
                    "no feasible design"
                    if not best
                    else (
                        f"optimum: evaluation {best[0][0].number}"
                        if len(opt.objectives) == 1
                        else f"Pareto set of {len(best)}"
                    )
                )
                figure = "" if result.figure is None else f", figure {result.figure}"
                resumed = f", {result.resumed} from the checkpoint" if result.resumed else ""
                stdout.print(
                    f"{opt.label}: {len(result.evaluations)} evaluations in "
                    f"{result.generations} generations, {result.infeasible} infeasible, "
                    f"{result.failed} failed{resumed}; "
                    f"{found} -> {result.output}, {result.pareto}{figure}",
                    markup=False,
                    highlight=False,
                    soft_wrap=True,
                )
                if result.figure_error is not None:
                    unwritten += 1
                    said(f"error: {opt.label}: {result.figure_error}")
    except Terminated:
        raise fail(
            "terminated: finished evaluations are in the optimisation's checkpoint "
            "(--resume finishes it)",
            ExitCode.TERMINATED,
        ) from None
    except (KeyboardInterrupt, Cancelled):
        raise fail(
            "interrupted: finished evaluations are in the optimisation's checkpoint "
            "(--resume finishes it)",
            ExitCode.INTERRUPTED,
        ) from None
    if failed or unwritten:
        parts = [f"{failed} evaluation(s) failed (status failed in the CSV)"] if failed else []
        if unwritten:
            parts.append(f"{unwritten} optimisation file(s) not written (see above)")
        raise fail("error: " + "; ".join(parts), ExitCode.RUN_FAILED)

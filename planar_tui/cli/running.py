"""Running a :class:`~planar_tui.plan.RunPlan` in the terminal: its jobs through the batch
service, one progress bar each, then a summary table; its sweeps, one bar each, then a
line each. What runs and where it writes was decided by the plan, before anything ran."""

from __future__ import annotations

import os
from collections.abc import Callable
from contextlib import ExitStack, contextmanager
from typing import TYPE_CHECKING, Any

from planar_tui.cli.output import (
    _INTERRUPTED,
    fail,
    job_progress_display,
    progress_bar,
    sigterm_as_interrupt,
    stderr,
    stdout,
    sweep_progress_display,
)
from planar_tui.errors import Cancelled, ExitCode, Terminated

if TYPE_CHECKING:
    from planar_tui.jobkind import Job
    from planar_tui.plan import RunPlan


def print_notes(plan: RunPlan) -> None:
    """What the plan says before it runs (a replaced checkpoint), on stderr."""
    for note in plan.notes:
        stderr.print(note, markup=False, highlight=False, soft_wrap=True)


def run_jobs(
    plan: RunPlan, *, show: bool = True, after: Callable[[Job, Any], None] | None = None
) -> None:
    """Run the plan's jobs through the batch service, one progress bar each, then print a
    summary; each job's files are written as soon as it finishes. A job that raises an
    unexpected error, or an output that cannot be written, ends the run with one
    ``error:`` line and exit code 1 (``PLANAR_TUI_DEBUG=1`` shows the traceback). ``show``
    prints each kind's terminal view; ``after(job, result)`` writes what the command's
    other options ask once a job's files are written (:func:`planar_tui.cli.interop.
    job_exports`)."""
    from rich.table import Table
    from rich.text import Text

    from planar_tui import batch
    from planar_tui.registry import JOB_KINDS

    @contextmanager
    def progress_for(job: Job):
        with job_progress_display(stderr) as bars, progress_bar(bars, job) as progress:
            yield progress

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
    except (batch.OutputFailed, batch.NonFiniteResult) as error:
        raise fail(f"error: {error}", ExitCode.RUN_FAILED) from None

    summary = Table(title="planar-tui run summary", title_justify="left", show_lines=True)
    summary.add_column("job", no_wrap=True)
    summary.add_column("seconds", justify="right", no_wrap=True)
    summary.add_column("output and result", overflow="fold")
    for row in rows:
        summary.add_row(Text(row.label), f"{row.seconds:.3f}", Text(f"{row.output}\n{row.summary}"))
    stdout.print(summary)


def _said(text: str) -> None:
    stderr.print(text, markup=False, highlight=False, soft_wrap=True)


def study_client(stack: ExitStack, wanted: bool, workers: int | None, scheduler: str | None
                 ) -> Any:  # fmt: skip
    """The Dask client a run's sweeps (or optimisations) share, entered on ``stack``:
    ``None`` when there are none (``wanted`` false) or they run in this process (one
    worker, no scheduler); else a local cluster of ``workers`` processes (default: the
    cores) or the scheduler at ``scheduler``."""
    from planar_tui.sweep.execute import default_workers

    count = workers or default_workers()
    if not wanted or (scheduler is None and count <= 1):
        return None
    from planar_tui.sweep.execute import DaskTarget, dask_client

    return stack.enter_context(dask_client(DaskTarget(count, scheduler), _said))


def run_sweeps(plan: RunPlan, workers: int | None, scheduler: str | None) -> None:
    """Run the plan's sweeps, one progress bar each; a summary line per sweep on stdout.
    Exit code 1 when a point failed (its row says why) or a sweep's file could not be
    written (one ``error:`` line each; the later sweeps still run). Every sweep's
    checkpoint is kept until all of them are done, then those of the sweeps whose CSV was
    written are deleted: Ctrl-C keeps them all, so ``--resume`` rebuilds the finished
    sweeps from theirs and computes only what is left."""
    from planar_tui.batch import OutputFailed
    from planar_tui.progress import Progress
    from planar_tui.sweep.service import resume_note, run_sweep

    failed = 0
    unwritten = 0
    done = []
    try:
        with sigterm_as_interrupt(), ExitStack() as stack:
            client = study_client(stack, bool(plan.sweeps), workers, scheduler)
            for entry in plan.sweeps:
                sweep, points = entry.sweep, entry.points
                with sweep_progress_display(stderr) as bars:
                    task = bars.add_task(sweep.label, total=len(points), failed=0)

                    def update(state, bars=bars, task=task, label=sweep.label) -> None:
                        if state.stage == label:
                            bars.update(task, completed=state.completed,
                                        failed=int(state.figures.get("failed", 0)))  # fmt: skip

                    try:
                        result = run_sweep(
                            sweep, Progress(on_update=update, should_stop=_INTERRUPTED.is_set),
                            points=points, out_dir=plan.out_dir,
                            resume=plan.resume, client=client, keep_checkpoint=True,
                            announce=_said,
                        )  # fmt: skip
                    except OutputFailed as error:
                        unwritten += 1
                        _said(f"error: {sweep.label}: {error} (finished points are in its "
                              "checkpoint)")  # fmt: skip
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
                    _said(f"error: {sweep.label}: {result.figure_error}")
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
    re-run at the job's settings and its files. A failed evaluation is counted, not fatal;
    Ctrl-C exits 130 with every finished evaluation in the checkpoint (``--resume``)."""
    from planar_tui.batch import OutputFailed
    from planar_tui.optimise.run import run_optimisation
    from planar_tui.progress import Progress

    unwritten = 0
    try:
        with sigterm_as_interrupt(), ExitStack() as stack:
            client = study_client(stack, bool(plan.optimisations), workers, scheduler)
            for opt in plan.optimisations:
                with sweep_progress_display(stderr) as bars:
                    task = bars.add_task(opt.label, total=opt.budget, failed=0)

                    def update(state, bars=bars, task=task) -> None:
                        bars.update(task, completed=state.completed, total=state.total,
                                    description=state.stage,
                                    failed=int(state.figures.get("failed", 0)))  # fmt: skip

                    try:
                        result = run_optimisation(
                            opt, Progress(on_update=update, should_stop=_INTERRUPTED.is_set),
                            client=client, out_dir=plan.out_dir, resume=plan.resume,
                            announce=_said,
                        )  # fmt: skip
                    except OutputFailed as error:
                        unwritten += 1
                        _said(f"error: {opt.label}: {error} (finished evaluations are in its "
                              "checkpoint)")  # fmt: skip
                        continue
                best = result.certified
                found = "no feasible design" if not best else (
                    f"optimum: evaluation {best[0][0].number}" if len(opt.objectives) == 1
                    else f"Pareto set of {len(best)}")  # fmt: skip
                figure = "" if result.figure is None else f", figure {result.figure}"
                resumed = f", {result.resumed} from the checkpoint" if result.resumed else ""
                stdout.print(
                    f"{opt.label}: {len(result.evaluations)} evaluations in "
                    f"{result.generations} generations, {result.failed} failed{resumed}; "
                    f"{found} -> {result.output}, {result.pareto}{figure}",
                    markup=False, highlight=False, soft_wrap=True,
                )  # fmt: skip
                if result.figure_error is not None:
                    unwritten += 1
                    _said(f"error: {opt.label}: {result.figure_error}")
    except Terminated:
        raise fail("terminated: finished evaluations are in the optimisation's checkpoint "
                   "(--resume finishes it)", ExitCode.TERMINATED) from None  # fmt: skip
    except (KeyboardInterrupt, Cancelled):
        raise fail("interrupted: finished evaluations are in the optimisation's checkpoint "
                   "(--resume finishes it)", ExitCode.INTERRUPTED) from None  # fmt: skip
    if unwritten:
        raise fail(f"error: {unwritten} optimisation file(s) not written (see above)",
                   ExitCode.RUN_FAILED)  # fmt: skip

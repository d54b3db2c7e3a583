"""Job control for the workbench: one job at a time, in a thread worker.

:meth:`JobRunner.start` runs :func:`planar_tui.batch.run_job` (the batch service the CLI
uses) in a Textual thread worker; the kernels release the GIL, so the UI keeps running.
The runner's progress snapshots are kept as they arrive (:attr:`JobRunner.latest`) for a
UI timer to show. :meth:`JobRunner.cancel` sets the flag that
:meth:`planar_tui.progress.Progress.check` polls between chunks, so the runner raises
:class:`~planar_tui.errors.Cancelled` at its next chunk and nothing is written. The
outcome comes back to the app as a :class:`JobFinished` message.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from textual.message import Message
from textual.worker import get_current_worker

from planar_tui import batch
from planar_tui.batch import JobFailed, run_plans
from planar_tui.errors import Cancelled
from planar_tui.optimise.run import run_optimisation
from planar_tui.plan import plan_sweep
from planar_tui.progress import Progress, ProgressState
from planar_tui.sweep.service import SweepRun, run_sweep

if TYPE_CHECKING:
    from textual.app import App

    from planar_tui.jobkind import Job, JobResult


class RunEnded(Message):
    """What every kind of run posts when its thread ends: ``pane`` (the widget that asked
    for it and shows the outcome), ``error`` on failure, ``cancelled`` when stopped,
    ``seconds`` from start to end; each subclass adds what the run produced."""

    def __init__(self, pane: Any):
        super().__init__()
        self.pane = pane
        self.error: BaseException | None = None
        self.cancelled = False
        self.seconds = 0.0


class JobFinished(RunEnded):
    """A job ended: ``result`` (a :class:`~planar_tui.jobkind.JobResult`) on success;
    ``document_sha256``: the SHA-256 of the document it ran from (``None``: the file's)."""

    def __init__(self, pane: Any, job: Job, document_sha256: str | None = None):
        super().__init__(pane)
        self.job = job
        self.result: JobResult | None = None
        self.document_sha256 = document_sha256


class BatchJobDone(Message):
    """One job of a "run all" finished and its files are written."""

    def __init__(self, job: Job, result: JobResult):
        super().__init__()
        self.job = job
        self.result = result


class BatchFinished(RunEnded):
    """A "run all" ended: ``rows`` (the summary rows of the jobs done, their files
    written) of ``total``; ``error`` or ``cancelled`` when it stopped early."""

    def __init__(self, pane: Any, total: int):
        super().__init__(pane)
        self.rows: list = []
        self.total = total


class SweepFinished(RunEnded):
    """A sweep ended: ``run`` (a :class:`~planar_tui.sweep.service.SweepRun`) when every
    point ran (some may have failed: their rows say why), or the points finished before a
    cancel (``cancelled``; the run marks the others); ``error`` when it could not run
    (a point invalid for its key)."""

    def __init__(self, pane: Any, sweep: Any):
        super().__init__(pane)
        self.sweep = sweep
        self.run: Any = None


class OptimiseFinished(RunEnded):
    """An optimisation ended: ``run`` (a :class:`~planar_tui.optimise.evaluations.OptimiseRun`),
    ``cancelled`` (its finished evaluations kept) or not; ``error`` when it could not run."""

    def __init__(self, pane: Any, optimisation: Any):
        super().__init__(pane)
        self.optimisation = optimisation
        self.run: Any = None


class GenerationDone(Message):
    """A generation of the running optimisation is back: ``run`` holds every evaluation so
    far (the optimise screen redraws)."""

    def __init__(self, run: Any):
        super().__init__()
        self.run = run


class JobRunner:
    """Runs the app's jobs, one at a time, and reports each outcome to ``app``.

    Parameters
    ----------
    app
        The app whose worker manager runs the thread and which receives
        :class:`JobFinished`.
    """

    #: The worker group of job threads.
    GROUP = "job"

    def __init__(self, app: App):
        self._app = app
        self._done = threading.Event()
        self._done.set()
        self._stop = threading.Event()
        #: The pane whose job runs (or ran last); ``None`` before the first job.
        self.pane: Any = None
        #: The latest progress snapshot of the running job (``None`` until its first).
        self.latest: ProgressState | None = None

    @property
    def running(self) -> bool:
        """Whether a job thread is still working (until the runner has returned)."""
        return not self._done.is_set()

    def start(self, pane: Any, job: Job, document_sha256: str | None = None) -> None:
        """Run ``job`` for ``pane`` (:func:`planar_tui.batch.run_job`, as the CLI runs it);
        posts :class:`JobFinished` (carrying ``document_sha256``, the edited document's
        digest when the job ran from one)."""

        finished = JobFinished(pane, job, document_sha256)

        def compute(stopping: Callable[[], bool]) -> None:
            finished.result = batch.run_job(
                job, Progress(on_update=self._store, should_stop=stopping)
            )

        self._launch(job.label, finished, compute)

    def start_all(self, pane: Any, plans: list) -> None:
        """Run every planned job in order as ``planar-tui run`` does
        (:func:`planar_tui.batch.run_plans`: each job's files written when it finishes),
        showing progress on ``pane``; posts :class:`BatchJobDone` per job, then
        :class:`BatchFinished`."""
        import contextlib
        import dataclasses

        finished = BatchFinished(pane, len(plans))
        numbers = {id(plan.job): n for n, plan in enumerate(plans, start=1)}

        def compute(stopping: Callable[[], bool]) -> None:
            @contextlib.contextmanager
            def progress_for(job: Job):
                prefix = f"job {numbers[id(job)]}/{len(plans)} {job.key}:"

                def store(state: ProgressState) -> None:
                    self._store(dataclasses.replace(state, stage=f"{prefix} {state.stage}"))

                yield Progress(on_update=store, should_stop=stopping)

            def done(job: Job, result: JobResult) -> None:
                self._app.post_message(BatchJobDone(job, result))

            finished.rows.extend(run_plans(plans, progress_for, done))

        self._launch("run all", finished, compute)

    def start_sweep(self, pane: Any, sweep: Any, workers: int = 1, points: Any = None) -> None:
        """Run every point of ``sweep`` (:func:`planar_tui.sweep.service.run_sweep`: in this
        process with ``workers == 1``, else on a local Dask cluster of ``workers``
        processes), showing progress on ``pane``; posts :class:`SweepFinished`. ``points``
        are the sweep's validated points (made and checked in the thread when ``None``).
        Nothing is written (the sweep screen exports the CSV). A cancelled sweep's
        finished points are kept: ``finished.run`` is the partial run (``cancelled``)."""
        finished = SweepFinished(pane, sweep)

        def compute(stopping: Callable[[], bool]) -> None:
            checked = plan_sweep(sweep).points if points is None else points
            progress = Progress(on_update=self._store, should_stop=stopping)
            done: dict = {}

            def keep(outcome: Any) -> None:
                done[outcome.number] = outcome

            try:
                finished.run = run_sweep(
                    sweep, progress, points=checked, workers=workers, on_outcome=keep
                )
            except (Cancelled, KeyboardInterrupt):
                finished.run = SweepRun(sweep, checked, done, cancelled=True)
                raise

        self._launch(sweep.label, finished, compute)

    def start_optimise(self, pane: Any, optimisation: Any, workers: int = 1) -> None:
        """Run ``optimisation`` (:func:`planar_tui.optimise.run.run_optimisation`, in this
        process or on a local cluster of ``workers`` processes), posting
        :class:`GenerationDone` after each generation and :class:`OptimiseFinished` at the
        end. Nothing is written (the optimise screen exports the CSVs)."""
        finished = OptimiseFinished(pane, optimisation)

        def generation(run: Any) -> None:
            finished.run = run
            self._app.post_message(GenerationDone(run))

        def compute(stopping: Callable[[], bool]) -> None:
            progress = Progress(on_update=self._store, should_stop=stopping)
            finished.run = run_optimisation(
                optimisation, progress, workers=workers, on_generation=generation
            )

        self._launch(optimisation.label, finished, compute)

    def _launch(
        self, name: str, finished: RunEnded, compute: Callable[[Callable[[], bool]], None]
    ) -> None:
        """Run ``compute(stopping)`` in a thread worker (one run at a time), showing progress
        on ``finished.pane``; ``stopping()`` says whether a cancel was asked (or the app is
        closing). Then fill in and post ``finished``: a cancel sets ``cancelled``, a failure
        ``error`` (a job's own error rather than the batch service's wrapper: shown in a
        dialog, never as a traceback)."""
        if self.running:
            raise RuntimeError("a job is already running")
        self.pane = finished.pane
        self.latest = None
        self._stop.clear()
        self._done.clear()

        def work() -> None:
            worker = get_current_worker()  # cancelled by Textual when the app closes
            started = time.perf_counter()
            try:
                compute(lambda: self._stop.is_set() or worker.is_cancelled)
            except (Cancelled, KeyboardInterrupt):
                finished.cancelled = True
            except JobFailed as failure:
                finished.error = failure.__cause__ or failure
            except Exception as error:  # e.g. the job's own PresetError (a box budget)
                finished.error = error
            finally:
                self.latest = None  # its partial results (views of the run's arrays) go too
                self._done.set()
            finished.seconds = time.perf_counter() - started
            self._app.post_message(finished)

        self._app.run_worker(
            work, name=name, group=self.GROUP, thread=True, exclusive=True, exit_on_error=False
        )

    def cancel(self) -> bool:
        """Ask the running job to stop at its next chunk; ``False`` when none runs."""
        if not self.running:
            return False
        self._stop.set()
        return True

    def _store(self, state: ProgressState) -> None:
        """Called in the worker thread: keep the latest snapshot for the UI timer."""
        self.latest = state

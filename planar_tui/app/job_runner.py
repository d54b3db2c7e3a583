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
from typing import TYPE_CHECKING, Any

from textual.message import Message
from textual.worker import get_current_worker

from planar_tui.errors import Cancelled
from planar_tui.progress import Progress, ProgressState

if TYPE_CHECKING:
    from textual.app import App

    from planar_tui.jobkind import Job, JobResult


class JobFinished(Message):
    """A job ended: ``result`` on success, ``error`` on failure, ``cancelled`` otherwise.

    ``pane`` is the widget that asked for the job (it shows the outcome); ``seconds`` the
    time from the job's start to its end.
    """

    def __init__(
        self,
        pane: Any,
        job: Job,
        result: JobResult | None = None,
        error: BaseException | None = None,
        cancelled: bool = False,
        seconds: float = 0.0,
    ):
        super().__init__()
        self.pane = pane
        self.job = job
        self.result = result
        self.error = error
        self.cancelled = cancelled
        self.seconds = seconds


class BatchJobDone(Message):
    """One job of a "run all" finished and its files are written."""

    def __init__(self, job: Job, result: JobResult):
        super().__init__()
        self.job = job
        self.result = result


class BatchFinished(Message):
    """A "run all" ended: ``rows`` (the summary rows of the jobs done, their files
    written), ``error`` or ``cancelled`` when it stopped early; ``seconds`` in all."""

    def __init__(
        self,
        pane: Any,
        rows: list,
        total: int,
        error: BaseException | None = None,
        cancelled: bool = False,
        seconds: float = 0.0,
    ):
        super().__init__()
        self.pane = pane
        self.rows = rows
        self.total = total
        self.error = error
        self.cancelled = cancelled
        self.seconds = seconds


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

    def start(self, pane: Any, job: Job) -> None:
        """Run ``job`` for ``pane`` in a thread worker (one job at a time)."""
        if self.running:
            raise RuntimeError("a job is already running")
        self.pane = pane
        self.latest = None
        self._stop.clear()
        self._done.clear()
        self._app.run_worker(
            lambda: self._work(pane, job),
            name=job.label,
            group=self.GROUP,
            thread=True,
            exclusive=True,
            exit_on_error=False,
        )

    def start_all(self, pane: Any, plans: list) -> None:
        """Run every planned job in order as ``planar-tui run`` does
        (:func:`planar_tui.batch.run_plans`: each job's files written when it finishes),
        showing progress on ``pane``; posts :class:`BatchJobDone` per job, then
        :class:`BatchFinished`."""
        if self.running:
            raise RuntimeError("a job is already running")
        self.pane = pane
        self.latest = None
        self._stop.clear()
        self._done.clear()
        self._app.run_worker(
            lambda: self._work_all(pane, plans),
            name="run all",
            group=self.GROUP,
            thread=True,
            exclusive=True,
            exit_on_error=False,
        )

    def start_sweep(self, pane: Any, sweep: Any, workers: int = 1, points: Any = None) -> None:
        """Run every point of ``sweep`` (:func:`planar_tui.sweep.service.run_sweep`: in this
        process with ``workers == 1``, else on a local Dask cluster of ``workers``
        processes), showing progress on ``pane``; posts :class:`SweepFinished`. ``points``
        are the sweep's validated points (made and checked in the thread when ``None``).
        Nothing is written (the sweep screen exports the CSV)."""
        if self.running:
            raise RuntimeError("a job is already running")
        self.pane = pane
        self.latest = None
        self._stop.clear()
        self._done.clear()
        self._app.run_worker(
            lambda: self._work_sweep(pane, sweep, workers, points),
            name=sweep.label,
            group=self.GROUP,
            thread=True,
            exclusive=True,
            exit_on_error=False,
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

    def _work(self, pane: Any, job: Job) -> None:
        """The worker thread: run the job, then post its :class:`JobFinished`."""
        from planar_tui.batch import JobFailed, run_job

        worker = get_current_worker()  # cancelled by Textual when the app closes
        started = time.perf_counter()
        progress = Progress(
            on_update=self._store,
            should_stop=lambda: self._stop.is_set() or worker.is_cancelled,
        )
        try:
            result = run_job(job, progress)
        except Cancelled:
            finished = JobFinished(pane, job, cancelled=True)
        except JobFailed as failure:  # shown in a dialog, never as a traceback
            finished = JobFinished(pane, job, error=failure.__cause__ or failure)
        except Exception as error:  # e.g. the job's own PresetError (a box budget)
            finished = JobFinished(pane, job, error=error)
        else:
            finished = JobFinished(pane, job, result=result)
        finally:
            self.latest = None  # its partial results (views of the run's arrays) go too
            self._done.set()
        finished.seconds = time.perf_counter() - started
        self._app.post_message(finished)

    def _work_sweep(self, pane: Any, sweep: Any, workers: int, points: Any) -> None:
        """The worker thread of a sweep: validate every point, then run them."""
        from planar_tui.sweep.points import make_points
        from planar_tui.sweep.service import run_sweep

        worker = get_current_worker()
        started = time.perf_counter()
        progress = Progress(
            on_update=self._store,
            should_stop=lambda: self._stop.is_set() or worker.is_cancelled,
        )
        finished = SweepFinished(pane, sweep)
        try:
            points = make_points(sweep) if points is None else points
            finished.run = run_sweep(sweep, progress, points=points, workers=workers)
        except (Cancelled, KeyboardInterrupt):
            finished.cancelled = True
        except Exception as error:  # a point invalid for its key: a dialog says which
            finished.error = error
        finally:
            self.latest = None
            self._done.set()
        finished.seconds = time.perf_counter() - started
        self._app.post_message(finished)

    def _work_all(self, pane: Any, plans: list) -> None:
        """The worker thread of "run all": the batch service's loop over the plans."""
        import contextlib
        import dataclasses

        from planar_tui.batch import JobFailed, OutputFailed, run_plans

        worker = get_current_worker()
        started = time.perf_counter()
        numbers = {id(plan.job): n for n, plan in enumerate(plans, start=1)}
        rows: list = []

        @contextlib.contextmanager
        def progress_for(job: Job):
            prefix = f"job {numbers[id(job)]}/{len(plans)} {job.key}:"

            def store(state: ProgressState) -> None:
                self._store(dataclasses.replace(state, stage=f"{prefix} {state.stage}"))

            yield Progress(
                on_update=store, should_stop=lambda: self._stop.is_set() or worker.is_cancelled
            )

        def done(job: Job, result: JobResult) -> None:
            self._app.post_message(BatchJobDone(job, result))

        finished = BatchFinished(pane, rows, len(plans))
        try:
            rows.extend(run_plans(plans, progress_for, done))
        except Cancelled:
            finished.cancelled = True
        except JobFailed as failure:
            finished.error = failure.__cause__ or failure
        except (OutputFailed, Exception) as error:
            finished.error = error
        finally:
            self.latest = None
            self._done.set()
        finished.seconds = time.perf_counter() - started
        self._app.post_message(finished)


class SweepFinished(Message):
    """A sweep ended: ``run`` (a :class:`~planar_tui.sweep.service.SweepRun`) when every
    point ran (some may have failed: their rows say why), ``error`` when it could not run
    (a point invalid for its key), ``cancelled`` otherwise; ``seconds`` in all."""

    def __init__(
        self,
        pane: Any,
        sweep: Any,
        run: Any = None,
        error: BaseException | None = None,
        cancelled: bool = False,
        seconds: float = 0.0,
    ):
        super().__init__()
        self.pane = pane
        self.sweep = sweep
        self.run = run
        self.error = error
        self.cancelled = cancelled
        self.seconds = seconds

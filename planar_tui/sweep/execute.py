"""Running point tasks: in this process, one after the other, or on Dask.

``--workers 1`` runs in-process and imports no Dask. Otherwise the points go to a Dask
scheduler: a :class:`distributed.LocalCluster` of worker processes (one thread each; the
kernels compile once per worker, or load from the shared cache folder), or an existing
scheduler by address (``--scheduler``, ``PLANAR_TUI_SCHEDULER``). Tasks carry the point's
settings, not arrays. A worker process that dies is replaced by its nanny and its points
are run again by the scheduler (Dask's own rescheduling).

Outcomes are handed over as they arrive (``on_outcome``); the caller's
:class:`~planar_tui.progress.Progress` is checked at least every 0.1 s, and a cancel
(or Ctrl-C) cancels every outstanding task before :class:`Cancelled` propagates.
"""

from __future__ import annotations

import os
import secrets
import signal
import threading
import time
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from planar_tui.errors import PresetError
from planar_tui.progress import Progress
from planar_tui.sweep.worker import PointOutcome, PointTask, run_point

#: Environment variable naming an existing Dask scheduler (``tcp://host:8786``), used
#: when neither ``--scheduler`` nor ``--workers`` is given.
SCHEDULER_ENV_VAR = "PLANAR_TUI_SCHEDULER"
#: Environment variable setting how long connecting to a scheduler may take (seconds).
SCHEDULER_TIMEOUT_ENV_VAR = "PLANAR_TUI_SCHEDULER_TIMEOUT_S"
#: How long connecting to a scheduler may take unless the environment says otherwise: the
#: TCP connection and Dask's handshake (a peer that accepts and never answers included).
DEFAULT_SCHEDULER_TIMEOUT_S = 10.0
#: How often the Dask runner checks for a cancel while it waits (seconds).
POLL_S = 0.1


def default_workers() -> int:
    """The machine's cores available to this process."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # macOS, Windows
        return max(1, os.cpu_count() or 1)


def scheduler_address(option: str | None, workers: int | None) -> str | None:
    """The scheduler to use: ``--scheduler``, else :data:`SCHEDULER_ENV_VAR` unless
    ``--workers`` was given (``--workers 1`` runs in this process whatever the
    environment says)."""
    if option is not None:
        return option
    if workers is not None:
        return None
    return os.environ.get(SCHEDULER_ENV_VAR) or None


def scheduler_timeout_s() -> float:
    """How long connecting to a scheduler may take: :data:`SCHEDULER_TIMEOUT_ENV_VAR` or
    :data:`DEFAULT_SCHEDULER_TIMEOUT_S`; a value that is no number of seconds > 0 (at
    most a day) is a :class:`PresetError`."""
    import math

    text = os.environ.get(SCHEDULER_TIMEOUT_ENV_VAR, "").strip()
    if not text:
        return DEFAULT_SCHEDULER_TIMEOUT_S
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not 0 < value <= 86_400:
        raise PresetError(
            "environment",
            SCHEDULER_TIMEOUT_ENV_VAR,
            f"is {text[:40]!r}",
            "a number of seconds > 0 and at most 86400",
        )
    return value


def probe_scheduler(address: str, timeout_s: float) -> None:
    """Connect to the scheduler at ``address`` and complete Dask's handshake within
    ``timeout_s`` (``distributed.Client`` bounds the TCP connection, not the handshake: a
    peer that accepts and never answers would hang it), or raise :class:`TimeoutError` /
    :class:`OSError`."""
    import asyncio

    from distributed.comm import connect

    async def handshake() -> None:
        comm = await connect(address, timeout=timeout_s)
        await comm.close()

    async def bounded() -> None:
        await asyncio.wait_for(handshake(), timeout_s)

    asyncio.run(bounded())


def run_in_process(
    tasks: Iterable[PointTask | PointOutcome],
    progress: Progress,
    on_outcome: Callable[[PointOutcome], None],
) -> None:
    """Run the tasks one after the other in this process (an outcome among them, a point
    that could not be made, is handed over as it is); a cancel of ``progress`` stops the
    running point within its runner's check interval."""
    child = Progress(should_stop=lambda: progress.cancel_requested)
    for task in tasks:
        progress.check()
        on_outcome(task if isinstance(task, PointOutcome) else run_point(task, child))


@dataclass(frozen=True)
class DaskTarget:
    """Where Dask work goes: an existing scheduler's ``address``, or a local cluster of
    ``workers`` processes."""

    workers: int
    address: str | None = None


def kernel_threads(workers: int) -> int:
    """Numba threads for each of ``workers`` local worker processes: the machine's cores
    shared among them (at least 1), so N workers with parallel kernels (the leg-wise
    paving, the batched RK4) run N × threads ≤ cores threads, not N × cores."""
    return max(1, default_workers() // max(1, workers))


#: Dask settings of a local cluster, against its idle housekeeping: with Dask's defaults
#: (event-loop tick every 20 ms, system monitor every 0.5 s, each nanny's memory check
#: every 0.1 s, a statistical profiler sampling every worker thread every 10 ms) an idle
#: 2-worker cluster used 10 % of a core across its processes; with these 1.5 % (measured on
#: the project's 2-core machine), CPU the points get back. The profiler would only profile
#: the Python around the Numba kernels; the memory limit is still enforced, once a second.
LOCAL_CLUSTER_CONFIG = {
    "distributed.admin.tick.interval": "1s",
    "distributed.admin.system-monitor.interval": "1s",
    "distributed.worker.memory.monitor-interval": "1s",
    "distributed.worker.profile.enabled": False,
}


def local_cluster(workers: int, **options: Any) -> Any:
    """A :class:`distributed.LocalCluster` of ``workers`` worker processes, one Dask
    thread each, dashboard on a free port, each process's Numba kernels limited to
    :func:`kernel_threads` threads (``NUMBA_NUM_THREADS`` in the workers' environment,
    set by their nannies before Numba loads) and :data:`LOCAL_CLUSTER_CONFIG` (handed by
    the nannies to every worker they start, first or again)."""
    import copy

    import dask
    from distributed import LocalCluster

    env = {"NUMBA_NUM_THREADS": str(kernel_threads(workers))}
    with dask.config.set(LOCAL_CLUSTER_CONFIG):
        # a deep copy: a nanny keeps a shallow merge of the global configuration, whose
        # nested settings ``dask.config.set`` restores in place on leaving this block,
        # and a worker it starts again (after a crash) would get Dask's defaults back
        config = copy.deepcopy(dask.config.config)
        return LocalCluster(
            n_workers=workers,
            threads_per_worker=1,
            processes=True,
            dashboard_address=":0",
            env=env,
            config=config,
            **options,
        )


@contextmanager
def deferred_signals(*signums: int) -> Iterator[None]:
    """Hold back ``signums`` (their Python handlers: Ctrl-C's ``KeyboardInterrupt``, the
    CLI's SIGTERM) while the block runs, and deliver each one that came to its handler on
    leaving. Only the process's Python handlers change (in the main thread; elsewhere the
    block runs as is): child processes started meanwhile get their own defaults."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    caught: list[int] = []
    previous = {signum: signal.getsignal(signum) for signum in signums}
    for signum in signums:
        signal.signal(signum, lambda number, frame: caught.append(number))
    try:
        yield
    finally:
        for signum, handler in previous.items():
            signal.signal(signum, handler)
        for signum in dict.fromkeys(caught):
            signal.raise_signal(signum)


@contextmanager
def workers_ignoring_interrupts() -> Iterator[None]:
    """Worker processes started in the block ignore SIGINT from their first instruction:
    multiprocessing's spawn runs them through a two-line launcher (``trap '' INT``, then
    ``exec`` of this Python) for the block's length. An ignored SIGINT stays ignored
    across ``exec`` and Python leaves a SIGINT it finds ignored alone, so a starting
    worker never turns the terminal's Ctrl-C, sent to the whole process group, into a
    traceback (Dask's own comm printed them); this process keeps its handlers, and the
    client stops the cluster. POSIX only (elsewhere the block runs as is)."""
    if os.name != "posix" or not Path("/bin/sh").exists():
        yield
        return
    import multiprocessing
    import shlex
    import shutil
    import sys
    import tempfile
    from multiprocessing import spawn

    folder = Path(tempfile.mkdtemp(prefix="planar-tui-launcher-"))
    launcher = folder / "python"
    launcher.write_text(f"#!/bin/sh\ntrap '' INT\nexec {shlex.quote(sys.executable)} \"$@\"\n")
    launcher.chmod(0o700)
    previous = spawn.get_executable()
    multiprocessing.set_executable(str(launcher))
    try:
        yield
    finally:
        multiprocessing.set_executable(previous)
        shutil.rmtree(folder, ignore_errors=True)


@contextmanager
def dask_client(target: DaskTarget, announce: Callable[[str], None]) -> Iterator[Any]:
    """A ``distributed.Client`` on the target; a local cluster is started here (worker
    processes, one thread each, dashboard on a free port, announced) and shut down on
    leaving, Ctrl-C included. Ctrl-C or SIGTERM while the cluster starts is held back until
    the cluster exists (:func:`deferred_signals`), then shuts it down: a cluster
    interrupted half-way would be left to Dask's exit hook, which fails on it."""
    import logging

    from distributed import Client

    if target.address is not None:
        timeout_s = scheduler_timeout_s()
        try:
            probe_scheduler(target.address, timeout_s)
            client = Client(target.address, timeout=timeout_s)
        except (OSError, TimeoutError, ValueError) as error:
            problem = str(error) or (
                f"no answer within {timeout_s:g} s ({SCHEDULER_TIMEOUT_ENV_VAR})"
            )
            raise PresetError(
                "command line",
                "--scheduler",
                f"cannot reach {target.address}: {problem}",
                "the address of a running Dask scheduler (tcp://host:8786)",
            ) from None
        try:
            announce(f"dask: scheduler {target.address}, dashboard {client.dashboard_link}")
            yield client
        finally:
            client.close()
        return
    cluster = None
    try:
        with deferred_signals(signal.SIGINT, signal.SIGTERM), workers_ignoring_interrupts():
            # CRITICAL: a worker whose heartbeat meets the closing scheduler at Ctrl-C logs
            # an ERROR with a traceback; failures reach the client through the futures
            cluster = local_cluster(target.workers, silence_logs=logging.CRITICAL)
        client = Client(cluster)
        try:
            client.register_plugin(_ignore_interrupts_plugin(), name="planar-tui-ignore-sigint")
            announce(
                f"dask: local cluster of {target.workers} worker processes, dashboard "
                f"{cluster.dashboard_link}"
            )
            yield client
        finally:
            client.close()
    finally:
        if cluster is not None:
            cluster.close()


def _ignore_interrupts_plugin() -> Any:
    """A worker plugin for a local cluster's workers: Ctrl-C in the terminal reaches every
    process of the group, and the client alone handles it (cancels the tasks, shuts the
    cluster down); a worker would otherwise print a traceback as it dies. Restarted
    workers get it too."""
    from distributed import WorkerPlugin

    class IgnoreInterrupts(WorkerPlugin):
        idempotent = True

        def setup(self, worker) -> None:
            import signal
            import threading

            if threading.current_thread() is threading.main_thread():
                signal.signal(signal.SIGINT, signal.SIG_IGN)

    return IgnoreInterrupts()


#: Most tasks a sweep has submitted to Dask and not yet collected: more are submitted as
#: these finish, so a sweep of 100 000 points starts at once and the scheduler holds a
#: window of them, not all.
DASK_WINDOW = 1_000


def run_on_dask(
    client: Any,
    tasks: Iterable[PointTask | PointOutcome],
    progress: Progress,
    on_outcome: Callable[[PointOutcome], None],
    key_prefix: str,
) -> None:
    """Submit the tasks to ``client`` (at most :data:`DASK_WINDOW` outstanding; an outcome
    among them is handed over as it is) and hand over outcomes as they complete. A cancel
    (``progress``) or Ctrl-C cancels the outstanding tasks, then propagates."""
    from distributed import as_completed

    pending = iter(tasks)
    futures: dict[Any, PointTask] = {}
    # on ``client``'s event loop: without ``loop`` it tracks the futures on the default
    # client's (another client current in this thread, say), and a result lost with a
    # killed worker then fails as "bound to a different event loop" instead of being
    # computed again
    completed = as_completed(loop=client.loop)

    def submit_next() -> bool:
        """Submit the next task (handing over outcomes met on the way); False when none
        is left."""
        for task in pending:
            if isinstance(task, PointOutcome):
                on_outcome(task)
                continue
            future = client.submit(run_point, task, key=f"{key_prefix}-{task.number}", pure=False)
            futures[future] = task
            completed.add(future)
            return True
        return False

    try:
        while len(futures) < DASK_WINDOW and submit_next():
            progress.check()
        while futures:
            progress.check()
            batch = completed.next_batch(block=False)
            if not batch:
                time.sleep(POLL_S / 5)
                continue
            for future in batch:
                task = futures.pop(future)
                on_outcome(_outcome(future, task))
                submit_next()
    except BaseException:
        completed.clear()  # stop tracking: nothing more is handed over
        client.cancel(list(futures), force=True)
        raise


def _outcome(future: Any, task: PointTask) -> PointOutcome:
    """A completed future's outcome; a task Dask gave up on (its workers kept dying) is a
    failed point."""
    try:
        return future.result()
    except Exception as error:
        message = f"{task.job.label} failed on Dask: {type(error).__name__}: {error}"
        return PointOutcome(task.number, "failed", " ".join(message.split()), {}, 0.0)


class PointRunner:
    """Runs point tasks for a study (a sweep, an optimisation): on ``client`` when there is
    one (each batch's keys start ``prefix-TOKEN``, unique per call), else in this process;
    outcomes are handed over as they arrive."""

    def __init__(self, client: Any, progress: Progress, prefix: str):
        self.client, self.progress, self.prefix = client, progress, prefix

    def run(
        self,
        tasks: Iterable[PointTask | PointOutcome],
        on_outcome: Callable[[PointOutcome], None],
    ) -> None:
        """Run ``tasks`` (:func:`run_on_dask` or :func:`run_in_process`)."""
        if self.client is None:
            run_in_process(tasks, self.progress, on_outcome)
        else:
            prefix = f"{self.prefix}-{secrets.token_hex(4)}"
            run_on_dask(self.client, tasks, self.progress, on_outcome, prefix)


@contextmanager
def point_runner(
    client: Any,
    workers: int,
    scheduler: str | None,
    announce: Callable[[str], None],
    progress: Progress,
    prefix: str,
    *,
    needed: bool = True,
) -> Iterator[PointRunner]:
    """The study's :class:`PointRunner`: on ``client`` when given; else in this process for
    one worker without a scheduler; else on a Dask client (:func:`dask_client`: a local
    cluster of ``workers`` or the ``scheduler``) opened here and closed on leaving, when
    points are ``needed`` (none left to run: no cluster is started)."""
    if client is not None or (workers <= 1 and scheduler is None) or not needed:
        yield PointRunner(client, progress, prefix)
        return
    with dask_client(DaskTarget(workers, scheduler), announce) as opened:
        yield PointRunner(opened, progress, prefix)

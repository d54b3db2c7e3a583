"""Progress reporting and cancellation shared by every runner.

A runner works in chunks (RK4 step blocks, sample batches, bisection rounds) and calls
:meth:`Progress.advance` after each; the front end decides what an update looks like
(a rich bar in the CLI, a message to the Textual app) and whether to stop.

The promise every runner keeps: each stage calls :meth:`Progress.check` (``start`` and
``advance`` do) at least every :data:`CHECK_INTERVAL_S` of work, so a cancel is honoured
within that time (measured per stage by ``benchmarks/bench_cancel.py`` and bounded by
``tests/test_cancel_latency.py``).
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, TypeVar, Union

from planar_tui.errors import Cancelled

if TYPE_CHECKING:
    import numpy as np

#: Longest stretch of work between two cancel checks that a runner may do (seconds).
CHECK_INTERVAL_S = 0.2
#: How often :meth:`Progress.wait_for` checks for a cancel while a call runs (seconds).
POLL_S = 0.05
#: The name of :meth:`Progress.wait_for`'s helper thread.
WAIT_FOR_THREAD = "planar-tui-wait-for"


ArrayT = TypeVar("ArrayT", bound="np.ndarray")
ResultT = TypeVar("ResultT")
#: A live partial result: a read-only array view, or ``None`` (not available yet).
Partial = Union["np.ndarray", None]


def read_only(view: ArrayT) -> ArrayT:
    """A read-only view of the array ``view`` for :attr:`ProgressState.partial` (the
    runner's own array is not copied)."""
    shown = view.view()
    shown.flags.writeable = False
    return shown


@dataclass(frozen=True)
class ProgressState:
    """A snapshot of a running job: ``completed`` of ``total`` units in ``stage``.

    ``detail`` is a short text for people; ``figures`` holds the runner's live numbers
    as data (e.g. the workspace's ``area_lower_cm2`` / ``area_upper_cm2`` bracket and its
    ``boxes_estimate``). ``warning`` is a job-wide warning that outlives stage changes
    (e.g. the workspace's box estimate exceeding its budget), empty when none.
    ``partial`` maps names to live partial results: **read-only NumPy views** into the
    runner's own arrays (not copies), valid until the next update replaces them (e.g. the
    workspace's ``boxes_cm`` and ``status`` kept so far, see
    :mod:`planar_tui.workspace.paving.levels`); copy what must outlive the run.
    ``stage_started_s`` is the :func:`time.monotonic` time the stage began (for an ETA),
    ``cancel_requested`` whether a cancel was asked for (the runner stops at its next
    check); ``cancelled`` is true only on the last state of a run that stopped on a cancel.
    """

    completed: float
    total: float
    stage: str
    detail: str
    figures: Mapping[str, float] = field(default_factory=dict)
    warning: str = ""
    partial: Mapping[str, Partial] = field(default_factory=dict)
    stage_started_s: float = 0.0
    cancel_requested: bool = False
    cancelled: bool = False

    @property
    def fraction(self) -> float:
        """``completed / total`` in [0, 1]."""
        return min(max(self.completed / self.total, 0.0), 1.0) if self.total > 0 else 0.0

    def eta_s(self, now_s: float | None = None) -> float | None:
        """Seconds left in the stage at its rate so far,
        ``(total − completed) · elapsed / completed``; ``None`` before any work."""
        elapsed_s = (time.monotonic() if now_s is None else now_s) - self.stage_started_s
        if self.completed <= 0 or elapsed_s <= 0:
            return None
        return (self.total - self.completed) * elapsed_s / self.completed


class Progress:
    """Receives a runner's progress and tells it when to stop.

    Parameters
    ----------
    on_update
        Called with a :class:`ProgressState` after every change; ``None`` ignores them.
    should_stop
        Polled by :meth:`check`; when it returns ``True`` the runner raises
        :class:`~planar_tui.errors.Cancelled` and writes nothing. :meth:`request_cancel`
        does the same from any thread without a callback.
    """

    def __init__(
        self,
        on_update: Callable[[ProgressState], None] | None = None,
        should_stop: Callable[[], bool] | None = None,
    ):
        self._on_update = on_update
        self._should_stop = should_stop
        self._cancel = threading.Event()
        self.completed = 0.0
        self.total = 1.0
        self.stage = ""
        self.detail = ""
        self.warning = ""
        self.stage_started_s = time.monotonic()
        self.figures: dict[str, float] = {}
        self.partial: dict[str, Partial] = {}

    @property
    def cancel_requested(self) -> bool:
        """Whether a cancel was asked for (:meth:`request_cancel` or ``should_stop``)."""
        if not self._cancel.is_set() and self._should_stop is not None and self._should_stop():
            self._cancel.set()
        return self._cancel.is_set()

    def request_cancel(self) -> None:
        """Ask the runner to stop at its next check (thread-safe)."""
        self._cancel.set()

    def start(self, total: float, stage: str = "", detail: str = "") -> None:
        """Begin a stage of ``total`` units (``completed`` returns to 0; the previous
        stage's ``partial`` results are dropped)."""
        self.total = max(float(total), 1e-300)
        self.completed = 0.0
        self.stage = stage
        self.detail = detail
        self.partial = {}
        self.stage_started_s = time.monotonic()
        self._emit()
        self.check()

    def advance(self, amount: float = 1.0, detail: str | None = None, **figures: float) -> None:
        """Add ``amount`` completed units, update the detail text and live ``figures``,
        report, then stop if asked to."""
        self.completed = min(self.completed + amount, self.total)
        if detail is not None:
            self.detail = detail
        self.figures.update(figures)
        self._emit()
        self.check()

    def warn(self, text: str) -> None:
        """Set the job-wide warning (kept across stages), reported with the next update."""
        self.warning = text

    def show_partial(self, **views: Partial) -> None:
        """Publish live partial results (read-only views, see :class:`ProgressState`);
        reported with the next update."""
        self.partial.update(views)

    def wait_for(
        self,
        function: Callable[..., ResultT],
        *args: object,
        on_poll: Callable[[], None] | None = None,
    ) -> ResultT:
        """``function(*args)`` run in a helper thread while this thread checks for a cancel
        every :data:`POLL_S`: for one call that cannot be split (compiling a kernel, a slow
        import). On a cancel, :class:`Cancelled` is raised at once and the call finishes in
        the background (its result is dropped; it must be harmless, e.g. filling a cache).
        ``on_poll()`` (e.g. a detail update) runs in this thread at every check.
        Returns the call's result or raises its exception."""
        values: list[ResultT] = []
        errors: list[BaseException] = []
        done = threading.Event()

        def call() -> None:
            try:
                values.append(function(*args))
            except BaseException as error:  # handed to the waiting thread
                errors.append(error)
            finally:
                done.set()

        threading.Thread(target=call, name=WAIT_FOR_THREAD, daemon=True).start()
        while not done.wait(POLL_S):
            if on_poll is not None:
                on_poll()
            self.check()
        if errors:
            raise errors.pop()
        return values[0]

    def check(self) -> None:
        """Raise :class:`Cancelled` if the front end asked the run to stop; the last
        state (``cancelled=True``) is reported first."""
        if self.cancel_requested:
            self._emit(cancelled=True)
            raise Cancelled("cancelled by the user")

    def state(self, cancelled: bool = False) -> ProgressState:
        """The current snapshot."""
        return ProgressState(
            self.completed,
            self.total,
            self.stage,
            self.detail,
            dict(self.figures),
            self.warning,
            dict(self.partial),
            self.stage_started_s,
            self._cancel.is_set(),
            cancelled,
        )

    def _emit(self, cancelled: bool = False) -> None:
        if self._on_update is not None:
            self._on_update(self.state(cancelled))

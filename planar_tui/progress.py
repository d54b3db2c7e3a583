"""Progress reporting and cancellation shared by every runner.

A runner works in chunks (RK4 step blocks, sample batches, bisection rounds) and calls
:meth:`Progress.advance` after each; the front end decides what an update looks like
(a rich bar in the CLI, a message to the Textual app) and whether to stop.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

from planar_tui.errors import Cancelled


@dataclass(frozen=True)
class ProgressState:
    """A snapshot of a running job: ``completed`` of ``total`` units in ``stage``.

    ``detail`` is a short text for people; ``figures`` holds the runner's live numbers
    as data (e.g. the workspace's ``area_lower_cm2`` / ``area_upper_cm2`` bracket).
    """

    completed: float
    total: float
    stage: str
    detail: str
    figures: Mapping[str, float] = field(default_factory=dict)


class Progress:
    """Receives a runner's progress and tells it when to stop.

    Parameters
    ----------
    on_update
        Called with a :class:`ProgressState` after every change; ``None`` ignores them.
    should_stop
        Polled by :meth:`check`; when it returns ``True`` the runner raises
        :class:`~planar_tui.errors.Cancelled` and writes nothing.
    """

    def __init__(
        self,
        on_update: Callable[[ProgressState], None] | None = None,
        should_stop: Callable[[], bool] | None = None,
    ):
        self._on_update = on_update
        self._should_stop = should_stop
        self.completed = 0.0
        self.total = 1.0
        self.stage = ""
        self.detail = ""
        self.figures: dict[str, float] = {}

    def start(self, total: float, stage: str = "", detail: str = "") -> None:
        """Begin a stage of ``total`` units (``completed`` returns to 0)."""
        self.total = max(float(total), 1e-300)
        self.completed = 0.0
        self.stage = stage
        self.detail = detail
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

    def check(self) -> None:
        """Raise :class:`Cancelled` if the front end asked the run to stop."""
        if self._should_stop is not None and self._should_stop():
            raise Cancelled("cancelled by the user")

    def _emit(self) -> None:
        if self._on_update is not None:
            state = ProgressState(
                self.completed, self.total, self.stage, self.detail, dict(self.figures)
            )
            self._on_update(state)

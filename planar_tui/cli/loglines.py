"""Progress as plain lines, for a stderr that is not a terminal (a batch log, a pipe).

A rich progress bar draws nothing into a file until the job ends. :class:`ProgressLog`
writes one line (no escape codes) when a stage starts and at least every
:data:`INTERVAL_S` while it runs, even while one call runs for long without reporting (a
kernel compiling): a heartbeat thread repeats the latest state with the time gone by::

    sweep-3rrr-design:sweep[1]: 42% 21/50 0.35 pt/s ETA 0:01:23 elapsed 0:01:00
      21/50 points, 0 failed

The rate is the stage's units per second so far, ``completed / elapsed``, the ETA
``(total - completed) / rate`` (:meth:`~planar_tui.progress.ProgressState.eta_s`); both
are ``--`` before the first unit.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable

from planar_tui.progress import ProgressState


def clock_text(seconds: float) -> str:
    """``H:MM:SS`` of a duration (rounded to whole seconds)."""
    whole = round(max(seconds, 0.0))
    return f"{whole // 3600}:{whole % 3600 // 60:02d}:{whole % 60:02d}"


def stage_title(label: str, stage: str) -> str:
    """What a progress display calls a stage of ``label``'s run: ``LABEL STAGE``, or the
    stage alone where it already names the run (a sweep's counting stage is its label)."""
    return stage if stage.startswith(label) else f"{label} {stage}".strip()


#: Longest time between two lines of a running stage (seconds).
INTERVAL_S = 10.0
#: How often the heartbeat thread looks whether a line is due (seconds).
HEARTBEAT_S = 1.0


def rate_of(state: ProgressState, now_s: float) -> float | None:
    """The stage's units per second so far, ``completed / elapsed`` (at the
    :func:`time.monotonic` time ``now_s``); ``None`` before the first unit."""
    elapsed_s = now_s - state.stage_started_s
    return state.completed / elapsed_s if state.completed > 0 and elapsed_s > 0 else None


def rate_text(rate: float | None, unit: str) -> str:
    """A rate with three significant digits (``0.35 pt/s``), in whole units from 100 on
    (``48,733 pt/s``); ``-- pt/s`` when unknown."""
    if rate is None:
        return f"-- {unit}/s"
    return f"{rate:,.0f} {unit}/s" if rate >= 100 else f"{rate:.3g} {unit}/s"


def progress_line(label: str, state: ProgressState, now_s: float, unit: str = "") -> str:
    """One plain line of ``state`` at the :func:`time.monotonic` time ``now_s``: label and
    stage, percent, ``done/total`` when the runner counts whole units, rate, ETA and the
    stage's elapsed time, then the runner's detail on an indented line of its own."""
    elapsed_s = max(now_s - state.stage_started_s, 0.0)
    whole = state.total > 1 and float(state.total).is_integer()
    parts = [stage_title(label, state.stage) + ":", f"{100.0 * state.fraction:.0f}%"]
    if whole:
        parts.append(f"{state.completed:,.0f}/{state.total:,.0f}")
    rate = rate_of(state, now_s)
    if not whole and rate is not None:
        rate, unit = 100.0 * rate / state.total, "%"
    parts.append(rate_text(rate, unit or "units"))
    eta_s = state.eta_s(now_s)
    parts.append("ETA " + ("--" if eta_s is None else clock_text(eta_s)))
    parts.append(f"elapsed {clock_text(elapsed_s)}")
    line = " ".join(parts)
    return f"{line}\n  {state.detail}" if state.detail else line


class ProgressLog:
    """Writes plain progress lines of one job, sweep or optimisation (``label``).

    :meth:`update` takes every :class:`ProgressState`; a line is written when the stage
    changes and when :data:`INTERVAL_S` passed since the last line (by ``clock``, a
    :func:`time.monotonic` stand-in for tests). Used as a context manager, a heartbeat
    thread calls :meth:`heartbeat` every :data:`HEARTBEAT_S`, so a stage that reports
    nothing for long still gets its line every :data:`INTERVAL_S`. ``unit`` names what the
    runner counts in the rate (``pt`` for sweep points).
    """

    def __init__(
        self,
        label: str,
        write: Callable[[str], None],
        unit: str = "",
        clock: Callable[[], float] = time.monotonic,
        interval_s: float = INTERVAL_S,
    ):
        self.label = label
        self.unit = unit
        self._write = write
        self._clock = clock
        self._interval_s = interval_s
        self._lock = threading.Lock()
        self._state: ProgressState | None = None
        self._started_s = clock()
        self._last_line_s = self._started_s
        self._warned: set[str] = set()
        self._stopped = threading.Event()
        self._thread: threading.Thread | None = None

    def update(self, state: ProgressState) -> None:
        """Take the runner's latest state; write a line if one is due, and a job-wide
        warning once (``warning: LABEL: TEXT``)."""
        with self._lock:
            if state.warning and state.warning not in self._warned:
                self._warned.add(state.warning)
                self._write(f"warning: {self.label}: {state.warning}")
            new_stage = self._state is None or state.stage != self._state.stage
            self._state = state
            self._line_if_due(force=new_stage)

    def heartbeat(self) -> None:
        """Write the latest state again if :data:`INTERVAL_S` passed since the last line."""
        with self._lock:
            self._line_if_due(force=False)

    def done(self, seconds: float) -> None:
        """The last line: ``LABEL done in H:MM:SS``, then the runner's last detail (a
        workspace's final area bracket) if any."""
        with self._lock:
            text = f"{self.label} done in {clock_text(seconds)}"
            detail = "" if self._state is None else self._state.detail
            self._write(f"{text}\n  {detail}" if detail else text)

    def _line_if_due(self, force: bool) -> None:
        now_s = self._clock()
        if not (force or now_s - self._last_line_s >= self._interval_s):
            return
        self._last_line_s = now_s
        if self._state is None:  # nothing reported yet (imports, a set-up): still alive
            self._write(f"{self.label}: starting (elapsed {clock_text(now_s - self._started_s)})")
        else:
            self._write(progress_line(self.label, self._state, now_s, self.unit))

    def __enter__(self) -> ProgressLog:
        def beat() -> None:
            while not self._stopped.wait(HEARTBEAT_S):
                self.heartbeat()

        self._thread = threading.Thread(target=beat, name="planar-tui-log-lines", daemon=True)
        self._thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self._stopped.set()
        if self._thread is not None:
            self._thread.join()

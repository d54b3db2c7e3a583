"""A time scrubber over a finished run: a focusable drawing (:class:`~.robot_drawing.SceneView`)
that shows the frame at the scrubbed time and steps, plays and changes speed on keys.

Keys (when the drawing has the focus): ``←``/``→`` step by 1 % of the run (at least one
recorded row), ``home``/``end`` jump to the start/end, ``space`` plays or pauses at
:attr:`PlaybackView.speed` × real time (from the start again once at the end), ``[``/``]``
halve/double the speed (:data:`SPEEDS`). Every move posts :class:`PlaybackView.Moved`;
the owning pane redraws the plots' cursor and the read-out.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import ClassVar

import numpy as np
from textual.binding import Binding
from textual.message import Message

from planar_tui.app.widgets.robot_drawing import Scene, SceneView

#: Playback speeds (× real time) that ``[`` and ``]`` step through.
SPEEDS = (0.01, 0.02, 0.05, 0.1, 0.25, 0.5, 1.0, 2.0, 4.0, 10.0)
#: Seconds between two frames while playing.
FRAME_S = 0.1
#: Steps per run for ``←``/``→``.
STEPS_PER_RUN = 100


def wrap_deg(angle_deg):
    """Angles wrapped to (-180°, 180°]: ``θ - 360° ⌈(θ - 180°)/360°⌉``."""
    angle = np.asarray(angle_deg, dtype=np.float64)
    return angle - 360.0 * np.ceil((angle - 180.0) / 360.0)


class PlaybackView(SceneView):
    """The frame at the scrubbed time of ``times`` (drawn by ``frame_scene(row)``)."""

    can_focus = True
    BINDINGS: ClassVar = [
        Binding("left", "step(-1)", "◀ step", show=False),
        Binding("right", "step(1)", "step ▶", show=False),
        Binding("home", "jump(0)", "start", show=False),
        Binding("end", "jump(-1)", "end", show=False),
        Binding("space", "play", "Play/pause"),
        Binding("left_square_bracket", "speed(-1)", "Slower", key_display="[", show=False),
        Binding("right_square_bracket", "speed(1)", "Faster", key_display="]", show=False),
    ]
    DEFAULT_CSS = """
    PlaybackView { border: round $primary-darken-2; }
    PlaybackView:focus { border: round $accent; }
    """

    class Moved(Message):
        """The scrubbed row changed (or the playback started or stopped)."""

        def __init__(self, view: PlaybackView) -> None:
            super().__init__()
            self.view = view

    def __init__(self, placeholder: str = "", **kwargs):
        super().__init__(placeholder, **kwargs)
        self.times: np.ndarray = np.zeros(0)
        self.row = 0
        self.speed = 1.0
        self.playing = False
        self.frame_scene: Callable[[int], Scene] | None = None
        self._timer = None
        self._clock_s = 0.0
        self._play_t_s = 0.0

    # -- the run ------------------------------------------------------------------------
    def load(self, times, frame_scene: Callable[[int], Scene], row: int | None = None) -> None:
        """Scrub over ``times`` (recorded, increasing); keep the row when it still exists."""
        self.pause()
        self.times = np.asarray(times, dtype=np.float64)
        self.frame_scene = frame_scene
        self.row = 0 if row is None else max(0, min(row, len(self.times) - 1))
        self.redraw()

    @property
    def t_s(self) -> float:
        return float(self.times[self.row]) if len(self.times) else 0.0

    def seek(self, t_s: float) -> None:
        """Scrub to the recorded time nearest ``t_s``."""
        if len(self.times):
            self.row = int(np.argmin(np.abs(self.times - t_s)))
            self.redraw()

    def redraw(self) -> None:
        if self.frame_scene is not None and len(self.times):
            self.show(self.frame_scene(self.row))
        self.post_message(self.Moved(self))

    def status(self) -> str:
        """``t = 0.500 s / 1 s  ▶ ×1`` (``‖`` when paused)."""
        if not len(self.times):
            return ""
        state = "▶" if self.playing else "‖"
        return f"t = {self.t_s:.4g} s / {self.times[-1]:.4g} s {state} ×{self.speed:g}"

    # -- keys -----------------------------------------------------------------------------
    def action_step(self, direction: int) -> None:
        if len(self.times):
            stride = max(1, (len(self.times) - 1) // STEPS_PER_RUN)
            self.row = max(0, min(len(self.times) - 1, self.row + direction * stride))
            self.redraw()

    def action_jump(self, row: int) -> None:
        if len(self.times):
            self.row = row % len(self.times)
            self.redraw()

    def action_speed(self, direction: int) -> None:
        index = min(range(len(SPEEDS)), key=lambda i: abs(SPEEDS[i] - self.speed))
        self.speed = SPEEDS[max(0, min(len(SPEEDS) - 1, index + direction))]
        self._restart_clock()
        self.post_message(self.Moved(self))

    def action_play(self) -> None:
        if self.playing:
            self.pause()
        elif len(self.times) > 1:
            if self.row == len(self.times) - 1:
                self.row = 0
            self.playing = True
            self._restart_clock()
            self._timer = self.set_interval(FRAME_S, self._tick)
        self.post_message(self.Moved(self))

    def pause(self) -> None:
        self.playing = False
        if self._timer is not None:
            self._timer.stop()
            self._timer = None

    def _restart_clock(self) -> None:
        self._clock_s, self._play_t_s = time.monotonic(), self.t_s

    def _tick(self) -> None:
        """Show the last recorded row at or before the run's time elapsed × speed."""
        t_s = self._play_t_s + (time.monotonic() - self._clock_s) * self.speed
        last = len(self.times) - 1
        self.row = min(last, int(np.searchsorted(self.times, t_s, side="right")) - 1)
        if self.row >= last:
            self.pause()
        self.redraw()

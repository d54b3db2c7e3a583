"""Run / Cancel buttons, a progress bar and a one-line status for a job tab.

The status reads ``45% 9.0k/20k eta 3s sampling …``: percent, done/total and the time
left in the current stage come first, so they survive 80 columns; the stage's own detail
follows and is the part cut when the line is short. While a cancel is on its way the
status says ``cancelling…`` until the worker has really stopped (the app then calls
:meth:`JobControls.set_running` with ``False``).
"""

from __future__ import annotations

from textual.app import ComposeResult
from textual.containers import Horizontal
from textual.widgets import Button, Label, ProgressBar

from planar_tui.progress import ProgressState
from planar_tui.warmup import STAGE


def compact_count(value: float) -> str:
    """A count in at most 5 cells: ``950``, ``9.5k``, ``12k``, ``1.2M``."""
    for limit, suffix in ((1e9, "G"), (1e6, "M"), (1e3, "k")):
        if abs(value) >= limit:
            scaled = value / limit
            return f"{scaled:.1f}{suffix}" if scaled < 10 else f"{scaled:.0f}{suffix}"
    return f"{value:.0f}"


def format_duration(seconds: float) -> str:
    """``4s``, ``1:05``, ``2:03:04``: short enough for the status line."""
    seconds = max(0, round(seconds))
    if seconds < 60:
        return f"{seconds}s"
    minutes, seconds = divmod(seconds, 60)
    if minutes < 60:
        return f"{minutes}:{seconds:02d}"
    hours, minutes = divmod(minutes, 60)
    return f"{hours}:{minutes:02d}:{seconds:02d}"


def progress_text(state: ProgressState, eta_s: float | None) -> str:
    """``45% 9.0k/20k eta 3s stage detail`` (the figures first); while kernels compile,
    ``compiling kernels (first run only): detail 0/2`` (the words first: no ETA can be
    told, and the line says why nothing moves)."""
    total = max(state.total, 1e-300)
    if state.stage == STAGE:
        done = f"{compact_count(state.completed)}/{compact_count(state.total)}"
        return f"{state.stage}: {state.detail} {done}"
    percent = 100.0 * state.completed / total
    eta = "eta …" if eta_s is None else f"eta {format_duration(eta_s)}"
    counts = f"{compact_count(state.completed)}/{compact_count(state.total)}"
    return f"{percent:3.0f}% {counts} {eta} {state.stage} {state.detail}".rstrip()


class JobControls(Horizontal):
    """The bottom line of a job tab: ``[Run F5] [Cancel esc] ▕████░░▏ 45% 9k/20k eta 3s …``."""

    DEFAULT_CSS = """
    JobControls { height: 1; }
    JobControls Button { margin-right: 1; min-width: 8; }
    JobControls ProgressBar { width: 12; margin-right: 1; }
    JobControls ProgressBar Bar { width: 12; }
    JobControls #job-status { width: 1fr; }
    """

    def __init__(self, **kwargs) -> None:
        super().__init__(**kwargs)
        #: A cancel was asked and the worker has not stopped yet.
        self.cancelling = False

    def compose(self) -> ComposeResult:
        yield Button("Run F5", id="run", compact=True, variant="success")
        yield Button("Cancel esc", id="cancel", compact=True, variant="error", disabled=True)
        yield ProgressBar(total=1.0, show_eta=False, show_percentage=False, id="job-progress")
        yield Label("ready", id="job-status", markup=False)

    def set_running(self, running: bool) -> None:
        """Enable Cancel while a job runs, Run otherwise (and forget a cancel asked)."""
        for button in self.query("#run").results(Button):
            button.disabled = running
        for button in self.query("#cancel").results(Button):
            button.disabled = not running
        self.cancelling = False

    def show_cancelling(self) -> None:
        """Say ``cancelling…`` until the worker has stopped (progress keeps it)."""
        self.cancelling = True
        self.status("cancelling… (waiting for the job to stop)")

    def show_progress(self, state: ProgressState) -> None:
        """Show a runner's progress snapshot: bar, percent, done/total, ETA, stage."""
        for bar in self.query(ProgressBar):
            bar.update(total=state.total, progress=state.completed)
        text = progress_text(state, state.eta_s())
        self.status(f"cancelling… {text}" if self.cancelling else text)

    def finished(self) -> None:
        """Fill the bar (the last stage may end without a final update)."""
        for bar in self.query(ProgressBar):
            bar.update(progress=bar.total or 1.0)

    def status(self, text: str) -> None:
        """Replace the status text (nothing once the controls are gone: a job's last
        message may arrive as the app closes)."""
        for label in self.query("#job-status").results(Label):
            label.update(text)

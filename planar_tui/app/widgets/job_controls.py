"""Run / Cancel buttons, a progress bar and a one-line status for a job tab."""

from __future__ import annotations

from textual.app import ComposeResult
from textual.containers import Horizontal
from textual.widgets import Button, Label, ProgressBar

from planar_tui.progress import ProgressState


class JobControls(Horizontal):
    """The bottom line of a job tab: ``[Run F5] [Cancel esc] ▕████░░▏ 45% stage detail``."""

    DEFAULT_CSS = """
    JobControls { height: 1; }
    JobControls Button { margin-right: 1; min-width: 10; }
    JobControls ProgressBar { width: 22; }
    JobControls #job-status { width: 1fr; }
    """

    def compose(self) -> ComposeResult:
        yield Button("Run F5", id="run", compact=True, variant="success")
        yield Button("Cancel esc", id="cancel", compact=True, variant="error", disabled=True)
        yield ProgressBar(total=1.0, show_eta=False, id="job-progress")
        yield Label("ready", id="job-status")

    def set_running(self, running: bool) -> None:
        """Enable Cancel while a job runs, Run otherwise."""
        self.query_one("#run", Button).disabled = running
        self.query_one("#cancel", Button).disabled = not running

    def show_progress(self, state: ProgressState) -> None:
        """Show a runner's progress snapshot."""
        self.query_one(ProgressBar).update(total=state.total, progress=state.completed)
        self.status(f"{state.stage} {state.detail}".strip())

    def finished(self) -> None:
        """Fill the bar (the last stage may end without a final update)."""
        bar = self.query_one(ProgressBar)
        bar.update(progress=bar.total or 1.0)

    def status(self, text: str) -> None:
        """Replace the status text."""
        self.query_one("#job-status", Label).update(text)

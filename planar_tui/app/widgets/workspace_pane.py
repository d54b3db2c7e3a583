"""The Workspace tab: the 3-RRR workspace map (the CLI's renderer), the live area bracket
and box count while the bisection runs, and the summary."""

from __future__ import annotations

from typing import Any, ClassVar

from textual.app import ComposeResult
from textual.widgets import Static

from planar_tui.app.widgets.panes import JobPane
from planar_tui.jobs import JobResult
from planar_tui.presets import Job
from planar_tui.progress import ProgressState


class WorkspacePane(JobPane):
    """Form, precision, orientation, joint limits; the character-cell map and summary."""

    kind: ClassVar[str] = "workspace"

    def compose_results(self) -> ComposeResult:
        yield Static("Run the bisection (F5) to map the workspace.", id="result-text", markup=False)
        yield Static("", id="workspace-map", markup=False)

    def show_progress(self, state: ProgressState) -> None:
        super().show_progress(state)
        self.query_one("#result-text", Static).update(f"running {state.stage}: {state.detail}")

    def render_result(self, job: Job, result: JobResult) -> None:
        from planar_tui.workspace.render import render_map

        self.query_one("#result-text", Static).update(result.summary)
        outcome = result.data
        area = self.query_one("#workspace-map", Static)
        if outcome is None or len(outcome.boxes) == 0:
            area.update("(no box kept: the workspace is empty at this precision)")
            return
        results = self.query_one(".results")
        width = max(20, results.size.width - 1)
        height = max(8, results.size.height - self.query_one("#result-text").size.height - 1)
        lines = render_map(outcome.boxes, outcome.status, width=width, height=height)
        area.update("\n".join(lines))

    def on_resize(self) -> None:
        if self.result is not None and self.job is not None:
            self.call_after_refresh(self.render_result, self.job, self.result)

    def export_tables(self) -> dict[str, Any]:
        if self.result is None:
            return {}
        return {"": self.result.table, "boxes": self.result.extra_tables["boxes"]}

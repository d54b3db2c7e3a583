"""The Workspace tab: the 3-RRR workspace map (the CLI's renderer), the live area bracket
and box count while the bisection runs, and the summary."""

from __future__ import annotations

import time

import numpy as np
from textual.app import ComposeResult
from textual.widgets import Static

from planar_tui.app.widgets.panes import JobPane
from planar_tui.jobkind import JobResult
from planar_tui.presets import Job
from planar_tui.progress import ProgressState

#: Lines of :func:`planar_tui.workspace.map.render_map` below the plot rows.
MAP_FOOTER_LINES = 3
#: Seconds between two redraws of the map of the boxes kept so far while a job runs.
PARTIAL_MAP_EVERY_S = 0.5


def fitted_map(boxes, status, width: int, height: int, **overlays) -> list[str]:
    """The CLI's aspect-true map (a cell twice as tall as wide) in at most ``width`` ×
    ``height`` cells, without its legend line (the tab shows the legend wrapped).

    ``render_map`` picks the plot rows from the width; when that is too tall the width is
    narrowed until it fits. A y tick ``┤`` is kept only on rows that carry a label (the
    others show the plain axis ``│``), so each label points at its row. ``overlays`` are
    ``render_map``'s ``singular`` and ``circle``.
    """
    from planar_tui.workspace.map import render_map

    lines = render_map(boxes, status, width=width, **overlays)
    while len(lines) > height and width > 20:
        width = max(20, min(width - 1, width * height // len(lines)))
        lines = render_map(boxes, status, width=width, **overlays)
    while lines and not lines[-1].lstrip().startswith("x (cm)") and overlays:
        lines = lines[:-1]  # the overlays' legend line: the tab shows its own
    if lines and lines[-1].lstrip().startswith("x (cm)"):
        lines = lines[:-1]
    plot = lines[: len(lines) - MAP_FOOTER_LINES + 1]
    for row, line in enumerate(plot):
        tick = line.find("┤")
        if tick > 0 and not line[:tick].strip():
            plot[row] = f"{line[:tick]}│{line[tick + 1 :]}"
    return plot + lines[len(plot) :]


def map_legend() -> str:
    """The map's legend (76 cells: one line when the form is hidden)."""
    from planar_tui.workspace.map import BOUNDARY_GLYPH, INSIDE_GLYPH

    return (
        f"x, y in cm  {INSIDE_GLYPH} inside (proved)  "
        f"{BOUNDARY_GLYPH} boundary (kept, not proved)  blank outside"
    )


class WorkspacePane(JobPane):
    """Form, precision, orientation, joint limits; the character-cell map and summary."""

    kind = "workspace"
    _partial_drawn_s = 0.0

    def compose_results(self) -> ComposeResult:
        yield Static("Run the bisection (F5) to map the workspace.", id="result-text", markup=False)
        yield Static("", id="workspace-map", markup=False)
        yield Static("", id="workspace-legend", markup=False)

    def show_progress(self, state: ProgressState) -> None:
        """The running bisection: its stage and bracket, a warning when the estimated box
        count exceeds the budget, and the map of the boxes kept so far (redrawn at most
        every :data:`PARTIAL_MAP_EVERY_S`)."""
        super().show_progress(state)
        text = f"running {state.stage}: {state.detail}"
        if state.warning:
            text = f"warning: {state.warning}\n{text}"
        self.query_one("#result-text", Static).update(text)
        boxes = state.partial.get("boxes_cm")
        now = time.monotonic()
        if boxes is not None and len(boxes) and now - self._partial_drawn_s >= PARTIAL_MAP_EVERY_S:
            self._partial_drawn_s = now
            status = state.partial.get("status")
            if status is None:  # the 5-D stage: kept boxes, none proved inside yet
                status = np.ones(len(boxes), dtype=np.int64)
            self.draw_map(boxes, status, "(so far)")

    def draw_map(self, boxes, status, note: str = "", **overlays) -> None:
        """Draw boxes on the map area, fitted to the results area (``overlays``: the
        singular boxes and the circle, see ``render_map``)."""
        from planar_tui.workspace.map import SINGULAR_LEGEND

        area = self.query_one("#workspace-map", Static)
        results = self.query_one(".results")
        width = max(20, results.content_region.width - 1)
        legend_text = map_legend() + (f"  {note}" if note else "")
        if overlays:
            legend_text += f"  {SINGULAR_LEGEND}"
        legend_lines = -(-len(legend_text) // width)
        summary_lines = self.query_one("#result-text").size.height
        height = max(8, results.content_region.height - summary_lines - legend_lines)
        area.update("\n".join(fitted_map(boxes, status, width, height, **overlays)))
        self.query_one("#workspace-legend", Static).update(legend_text)

    def render_result(self, job: Job, result: JobResult) -> None:
        self.query_one("#result-text", Static).update(result.summary)
        outcome = result.outcome
        area = self.query_one("#workspace-map", Static)
        legend = self.query_one("#workspace-legend", Static)
        if outcome is None or len(outcome.boxes) == 0:
            area.update("(no box kept: the workspace is empty at this precision)")
            legend.update("")
            return
        from planar_tui.workspace.job import overlays

        self.draw_map(outcome.boxes, outcome.status, **overlays(result.singularity))


class FiveBarPane(WorkspacePane):
    """The five-bar's tab: the workspace pane on ``[[workspace5r]]`` jobs."""

    kind = "workspace5r"

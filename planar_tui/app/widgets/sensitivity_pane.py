"""The Sensitivity tab: indices shaped like paper A's Table 4 (fitted to the width, see
:mod:`~planar_tui.sensitivity.tables`), a percent / S1 / ST / confidence toggle,
the Fig 5/6 stacked bars (the CLI's renderer), and the arm drawn in the analysed posture
(the solved one, e.g. isotropic)."""

from __future__ import annotations

from rich.console import Group
from rich.text import Text
from textual.app import ComposeResult
from textual.containers import ScrollableContainer
from textual.widgets import Static

from planar_tui.app.widgets.panes import JobPane
from planar_tui.app.widgets.robot_drawing import SceneView, serial_scene
from planar_tui.jobkind import JobResult
from planar_tui.presets import Job
from planar_tui.sensitivity.bars import sensitivity_bars
from planar_tui.sensitivity.tables import VIEWS, fit_tables

#: Cells taken by a bar's label (``τ1 1.00 rad/s ``) and a margin.
BAR_LABEL_CELLS = 16


def posture_line(posture) -> str:
    """The solved posture: ``posture isotropic θ = [0.0, 135.0]° κ = 1.000`` (relative joint angles)."""
    import math

    if posture is None:
        return ""
    angles = ", ".join(f"{math.degrees(t):.1f}" for t in posture.theta_rad)
    name = posture.label.split("=", 1)[0] if "=" in posture.label else posture.label
    return f"posture {name} θ = [{angles}]° κ = {posture.condition_number:.3f}"


class SensitivityPane(JobPane):
    """Posture, speeds, tolerances, methods, samples, seed; the indices table and bars."""

    kind = "sensitivity"

    DEFAULT_CSS = """
    #sensitivity-results { height: 1fr; scrollbar-gutter: stable; scrollbar-size: 1 1; }
    #sensitivity-results Static { width: 100%; }
    #sensitivity-arm { height: 10; display: none; }
    #sensitivity-arm.-shown { display: block; }
    """

    view = 0

    def compose_results(self) -> ComposeResult:
        with ScrollableContainer(id="sensitivity-results"):
            yield Static("Run the analysis (F5) to see the indices.", id="result-text")
            yield Static("", id="sensitivity-posture", markup=False)
            yield SceneView(id="sensitivity-arm")
            yield Static("", id="sensitivity-table")
            yield Static("", id="sensitivity-bars")

    def available_width(self) -> int:
        """Cells the table may use: the results area minus its scrollbar gutter."""
        return max(20, self.query_one("#sensitivity-results").scrollable_content_region.width)

    def render_result(self, job: Job, result: JobResult) -> None:
        analyses = result.analyses
        width = self.available_width()
        self.query_one("#result-text", Static).update(Text(result.summary))
        self.query_one("#sensitivity-posture", Static).update(posture_line(result.posture))
        arm = self.query_one("#sensitivity-arm", SceneView)
        arm.set_class(result.posture is not None, "-shown")
        if result.posture is not None:
            import math

            theta_deg = [math.degrees(t) for t in result.posture.theta_rad]
            arm.show(serial_scene(list(job.robot.lengths_m), theta_deg, caption="posture"))
        fitted = fit_tables(analyses, VIEWS[self.view], width, job.spec.percent_of)
        table = self.query_one("#sensitivity-table", Static)
        # never shrunk: a table wider than the pane scrolls sideways
        table.styles.width = max(width, fitted.width)
        table.update(fitted.renderable)
        bar_cells = max(10, width - BAR_LABEL_CELLS)
        bars = [
            sensitivity_bars(analyses, method, bar_cells)
            for method in dict.fromkeys(a.method for a in analyses)
        ]
        self.query_one("#sensitivity-bars", Static).update(Group(*bars))

    def action_toggle_view(self) -> None:
        """Cycle the table through percent, S1, ST and confidence."""
        self.view = (self.view + 1) % len(VIEWS)
        self.rerender()

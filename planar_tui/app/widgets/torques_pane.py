"""The Torques tab: the generic result view (the job's summary and first CSV rows) beside
the serial arm drawn at the job's first state (:mod:`.robot_drawing`), so the posture the
torques are for is seen; before a run the drawing follows the form's first ``theta_deg``
row."""

from __future__ import annotations

from typing import Any

from textual.app import ComposeResult
from textual.containers import ScrollableContainer
from textual.widgets import Static

from planar_tui.app.widgets.panes import JobPane, numbers_or_zeros
from planar_tui.app.widgets.robot_drawing import Scene, SceneView, serial_scene
from planar_tui.jobkind import JobResult
from planar_tui.presets import Job


def first_state_scene(lengths_m: Any, theta_deg: Any) -> Scene | None:
    """The arm at the first row of ``theta_deg`` (relative joint angles, degrees), or
    ``None`` when the lengths are not all positive numbers or there is no row."""
    if not isinstance(lengths_m, list | tuple) or not lengths_m:
        return None
    if not all(isinstance(v, int | float) and not isinstance(v, bool) and v > 0 for v in lengths_m):
        return None
    if not isinstance(theta_deg, list | tuple) or not theta_deg:
        return None
    lengths = [float(v) for v in lengths_m]
    theta = numbers_or_zeros(list(theta_deg[0]) if isinstance(theta_deg[0], list | tuple)
                             else None, len(lengths))  # fmt: skip
    return serial_scene(lengths, theta, caption="state 1")


class TorquesPane(JobPane):
    """States (angles, rates, accelerations); the summary, the CSV's first rows and the
    arm at the first state."""

    kind = "torques"

    DEFAULT_CSS = """
    #torques-arm { height: 1fr; min-height: 6; max-height: 14; }
    """

    def compose_results(self) -> ComposeResult:
        """The generic view's summary, the arm, then the generic view's CSV rows."""
        yield Static("Run the job (F5) to see its results.", id="result-text", markup=False)
        yield SceneView("(no drawing: the lengths or theta_deg are not numbers)", id="torques-arm")
        with ScrollableContainer(classes="generic-rows"):
            yield Static("", id="result-rows", markup=False)

    def on_mount(self) -> None:
        self.draw_document_state()

    def draw_document_state(self) -> None:
        """The arm at the form's first state (the job's own robot, else the preset's)."""
        if not self.available() or self.result is not None:
            return
        table = self.bench.table(self.kind, self.index)
        robot = table.get(self.robot_kind())
        if not isinstance(robot, dict):
            robot = self.bench.table(self.robot_kind())
        scene = first_state_scene(robot.get("lengths_m"), table.get("theta_deg"))
        self.query_one("#torques-arm", SceneView).show(scene)

    async def load_document(self) -> None:
        await super().load_document()
        self.draw_document_state()

    def on_table_form_changed(self, event: Any) -> None:
        super().on_table_form_changed(event)
        self.draw_document_state()

    def render_result(self, job: Job, result: JobResult) -> None:
        super().render_result(job, result)
        theta = [list(row) for row in job.spec.theta_deg]
        scene = first_state_scene(list(job.robot.lengths_m), theta)
        self.query_one("#torques-arm", SceneView).show(scene)

"""The Torques tab: the generic result view (the job's summary and first CSV rows) beside
the serial arm drawn at one of the job's states (:mod:`.robot_drawing`), so the posture the
torques are for is seen: the first state at first, another chosen with ``←``/``→``
(``home``/``end``: the first/last) once the drawing has the focus (:class:`StateView`);
before a run the drawing follows the form's ``theta_deg`` rows."""

from __future__ import annotations

from typing import Any, ClassVar

from rich.table import Table
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import ScrollableContainer
from textual.widgets import Static

from planar_tui.app.widgets.panes import JobPane
from planar_tui.app.widgets.robot_drawing import Scene, SceneView, numbers_or_zeros, serial_scene
from planar_tui.jobkind import JobResult
from planar_tui.presets import Job


def state_scene(lengths_m: Any, theta_deg: Any, index: int = 0) -> Scene | None:
    """The arm at row ``index`` of ``theta_deg`` (relative joint angles, degrees; an index
    past the rows: the last), or ``None`` when the lengths are not all positive numbers or
    there is no row; its caption ``state k/n``."""
    if not isinstance(lengths_m, list | tuple) or not lengths_m:
        return None
    if not all(isinstance(v, int | float) and not isinstance(v, bool) and v > 0 for v in lengths_m):
        return None
    if not isinstance(theta_deg, list | tuple) or not theta_deg:
        return None
    index = min(max(index, 0), len(theta_deg) - 1)
    lengths = [float(v) for v in lengths_m]
    row = theta_deg[index]
    theta = numbers_or_zeros(list(row) if isinstance(row, list | tuple) else None, len(lengths))
    return serial_scene(lengths, theta, caption=f"state {index + 1}/{len(theta_deg)}")


#: Rows of the torques table shown (the CSV has them all).
TABLE_ROWS = 200


def torques_grid(spec: Any, tau_Nm: Any) -> Table:
    """The states as a table, the joint torques τ_i (N m, 4 significant digits) first, then
    the state the preset gave: angles θ_i (deg), rates ω_i (deg/s), accelerations α_i
    (deg/s²); one row per state (``#``), at most :data:`TABLE_ROWS`; narrow columns (one
    space between), so that a 6R's torques fit beside the form at 80 columns."""
    n = len(tau_Nm[0]) if len(tau_Nm) else 0
    table = Table(
        title="τ (N m), θ (°), ω (°/s), α (°/s²)",
        title_justify="left",
        box=None,
        padding=(0, 0, 0, 1),
        pad_edge=False,
        header_style="bold",
    )
    table.add_column("#", justify="right")
    groups = (
        ("τ", tau_Nm),
        ("θ", spec.theta_deg),
        ("ω", spec.omega_deg_s),
        ("α", spec.alpha_deg_s2),
    )
    for symbol, _ in groups:
        for i in range(1, n + 1):
            table.add_column(f"{symbol}{i}", justify="right", no_wrap=True)
    for k in range(min(len(tau_Nm), TABLE_ROWS)):
        cells = [f"{float(rows[k][i]):.4g}" for _, rows in groups for i in range(n)]
        table.add_row(str(k + 1), *cells)
    return table


class StateView(SceneView):
    """The arm at one of the job's states (``←``/``→`` the previous/next, ``home``/``end``
    the first/last, with the focus); the chosen state is kept when the states change
    (cut to the last row when there are fewer)."""

    can_focus = True
    DEFAULT_CSS = """
    StateView { border-left: blank; }
    StateView:focus { border-left: thick $accent; }
    """
    BINDINGS: ClassVar = [
        Binding("left", "state(-1)", "◀ state", show=False),
        Binding("right", "state(1)", "State ▶"),
        Binding("home", "state_at(0)", "first state", show=False),
        Binding("end", "state_at(-1)", "last state", show=False),
    ]

    def __init__(self, placeholder: str = "", **kwargs):
        super().__init__(placeholder, **kwargs)
        self.lengths_m: Any = None
        self.theta_deg: Any = None
        #: The state drawn (0-based row of ``theta_deg``).
        self.index = 0

    def count(self) -> int:
        """How many states there are to choose from."""
        return len(self.theta_deg) if isinstance(self.theta_deg, list | tuple) else 0

    def set_states(self, lengths_m: Any, theta_deg: Any) -> None:
        """Draw the arm of ``lengths_m`` at the chosen row of ``theta_deg``."""
        self.lengths_m, self.theta_deg = lengths_m, theta_deg
        self.index = min(self.index, max(self.count() - 1, 0))
        self.show(state_scene(lengths_m, theta_deg, self.index))

    def action_state(self, step: int) -> None:
        """The previous (``step`` −1) or next (+1) state, stopping at the ends."""
        self.action_state_at(min(max(self.index + step, 0), max(self.count() - 1, 0)))

    def action_state_at(self, index: int) -> None:
        """State ``index`` (−1: the last)."""
        if self.count():
            self.index = index % self.count()
            self.set_states(self.lengths_m, self.theta_deg)


class TorquesPane(JobPane):
    """States (angles, rates, accelerations); the summary, the CSV's first rows and the
    arm at a chosen state (:class:`StateView`)."""

    kind = "torques"

    DEFAULT_CSS = """
    #torques-arm { height: 1fr; min-height: 6; max-height: 14; }
    """

    def compose_results(self) -> ComposeResult:
        """The generic view's summary, the arm, then the generic view's CSV rows."""
        yield Static("Run the job (F5) to see its results.", id="result-text", markup=False)
        yield StateView("(no drawing: the lengths or theta_deg are not numbers)", id="torques-arm")
        with ScrollableContainer(classes="generic-rows"):
            yield Static("", id="result-rows", markup=False)

    def on_mount(self) -> None:
        self.draw_document_state()

    def draw_document_state(self) -> None:
        """The arm at the form's chosen state (the job's own robot, else the preset's)."""
        if not self.available() or self.result is not None:
            return
        table = self.bench.table(self.kind, self.index)
        robot = table.get(self.robot_kind())
        if not isinstance(robot, dict):
            robot = self.bench.table(self.robot_kind())
        self.query_one("#torques-arm", StateView).set_states(
            robot.get("lengths_m"), table.get("theta_deg")
        )

    async def load_document(self) -> None:
        await super().load_document()
        self.draw_document_state()

    def on_table_form_changed(self, event: Any) -> None:
        super().on_table_form_changed(event)
        self.draw_document_state()

    def render_result(self, job: Job, result: JobResult) -> None:
        super().render_result(job, result)
        tau = getattr(result, "tau_Nm", None)
        if tau is not None:  # the kind's own result: a table, the torques first
            self.query_one("#result-rows", Static).update(torques_grid(job.spec, tau))
        theta = [list(row) for row in job.spec.theta_deg]
        self.query_one("#torques-arm", StateView).set_states(list(job.robot.lengths_m), theta)

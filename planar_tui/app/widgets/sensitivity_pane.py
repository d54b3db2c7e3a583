"""The Sensitivity tab: indices shaped like paper A's Table 4 with heat colouring, a
S1 / ST / percent / confidence toggle, and the Fig 5/6 stacked bars (the CLI's renderer)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import ClassVar

from rich import box
from rich.console import Group
from rich.table import Table
from rich.text import Text
from textual.app import ComposeResult
from textual.containers import VerticalScroll
from textual.widgets import Static

from planar_tui.app.widgets.panes import JobPane
from planar_tui.jobs import JobResult
from planar_tui.presets import Job

#: Views of the table: title, row of ``Analysis.indices`` (None: ``percent``), scale of 1.
VIEWS = (
    ("percent", None, 100.0),
    ("S1", 0, 1.0),
    ("ST", 2, 1.0),
    ("confidence", 3, 1.0),
)


def heat_style(fraction: float) -> str:
    """Heat levels readable in 16 colours; the top level is also bold (for NO_COLOR)."""
    if fraction >= 0.5:
        return "bold black on red"
    if fraction >= 0.2:
        return "black on yellow"
    if fraction >= 0.05:
        return "black on green"
    return ""


def heat_table(analyses: Sequence, view: int = 0) -> Table:
    """Rows torque × posture, columns l1…ln, m1…mn, cells "Sobol' (eFAST)" of the chosen
    quantity, coloured by the first method's value (the layout of paper A's Table 4)."""
    name, row, scale = VIEWS[view]
    speed = analyses[0].speed_rad_s
    chosen = [a for a in analyses if a.speed_rad_s == speed]
    methods = list(dict.fromkeys(a.method for a in chosen))
    heading = " (".join(methods) + (")" if len(methods) > 1 else "")
    note = ", ± 95 % half-width of ST (eFAST's are unreliable, SALib #649)" if row == 3 else ""
    table = Table(
        title=f"{name}: {heading}, {speed:g} rad/s{note}",
        title_justify="left",
        box=box.SIMPLE_HEAD,
        pad_edge=False,
        show_edge=False,
    )
    table.add_column("τ")
    table.add_column("posture")
    for parameter in chosen[0].names:
        table.add_column(parameter, justify="right")
    postures = list(dict.fromkeys(a.posture for a in chosen))
    for torque in range(chosen[0].percent.shape[0]):
        for posture in postures:
            here = [a for a in chosen if a.posture == posture]
            cells = []
            for j in range(len(chosen[0].names)):
                values = [
                    float(a.percent[torque, j] if row is None else a.indices[row, torque, j])
                    for a in here
                ]
                text = " (".join(f"{v:.2f}" if row != 3 else f"±{v:.3f}" for v in values)
                text += ")" if len(values) > 1 else ""
                style = heat_style(values[0] / scale) if row != 3 else ""
                cells.append(Text(text, style=style))
            table.add_row(f"τ{torque + 1}", posture, *cells)
    return table


class SensitivityPane(JobPane):
    """Posture, speeds, tolerances, methods, samples, seed; the indices table and bars."""

    kind: ClassVar[str] = "sensitivity"

    view = 0

    def compose_results(self) -> ComposeResult:
        with VerticalScroll(id="sensitivity-results"):
            yield Static("Run the analysis (F5) to see the indices.", id="result-text")
            yield Static("", id="sensitivity-table")
            yield Static("", id="sensitivity-bars")

    def render_result(self, job: Job, result: JobResult) -> None:
        from planar_tui.sensitivity.render import sensitivity_bars

        analyses = result.data["analyses"]
        self.query_one("#result-text", Static).update(
            Text(result.summary + "   (ctrl+t: S1 / ST / percent / confidence)")
        )
        self.query_one("#sensitivity-table", Static).update(heat_table(analyses, self.view))
        width = max(10, self.query_one("#sensitivity-results").size.width - 20)
        bars = [
            sensitivity_bars(analyses, method, width)
            for method in dict.fromkeys(a.method for a in analyses)
        ]
        self.query_one("#sensitivity-bars", Static).update(Group(*bars))

    def action_toggle_view(self) -> None:
        """Cycle the table through percent, S1, ST and confidence."""
        self.view = (self.view + 1) % len(VIEWS)
        if self.result is not None and self.job is not None:
            self.render_result(self.job, self.result)

    def on_resize(self) -> None:
        if self.result is not None and self.job is not None:
            self.render_result(self.job, self.result)

"""Figure of a parallel robot's path job: each actuator's effort and power against time
(two panels). Read from the path CSV (``t_s, x_cm, y_cm, ..., tau1_Nm`` or ``force1_N``,
``power1_W`` ...)."""

from __future__ import annotations

from typing import Any

from planar_tui.csvio import CsvTable
from planar_tui.figures.canvas import colour, new_figure
from planar_tui.figures.table import column, has_columns, numbered

#: The efforts' columns by actuator kind: prefix, suffix, axis label.
EFFORTS = (("tau", "_Nm", "torque (N m)"), ("force", "_N", "force (N)"))


def matches(header: tuple[str, ...]) -> bool:
    return has_columns(header, ("t_s", "x_cm", "y_cm", "power1_W")) and any(
        f"{prefix}1{suffix}" in header for prefix, suffix, _ in EFFORTS
    )


def draw(table: CsvTable, title: str) -> Any:
    """Efforts (top) and powers (bottom) against time, one line per actuator."""
    header = table.header
    prefix, suffix, label = next(e for e in EFFORTS if f"{e[0]}1{e[1]}" in header)
    efforts = numbered(header, prefix, suffix)
    n = len(efforts)
    t = column(table, "t_s")
    fig = new_figure(7.0, 6.0)
    top, bottom = fig.subplots(2, 1, sharex=True)
    for i, name in enumerate(efforts):
        top.plot(t, column(table, name), color=colour(i, n), label=f"actuator {i + 1}")
        bottom.plot(t, column(table, f"power{i + 1}_W"), color=colour(i, n))
    top.set(ylabel=f"actuator {label}", title="actuator efforts along the path")
    bottom.set(xlabel="time (s)", ylabel="power (W)")
    for ax in (top, bottom):
        ax.axhline(0.0, color="k", lw=0.6)
        ax.grid(alpha=0.3)
    top.legend(fontsize="small")
    fig.suptitle(title)
    return fig


def from_result(job: Any, result: Any) -> Any:
    """The figure of a finished path job."""
    return draw(result.table, job.label)

"""Figure of the torques job: the joint torques at every listed state as grouped bars
(one group per state, one bar per joint) and, when the robot is known, the arm drawn at
each state (:mod:`planar_tui.figures.arm`). Read from the torques CSV
(``theta*_rad, omega*_rad_s, alpha*_rad_s2, tau*_Nm``)."""

from __future__ import annotations

from typing import Any

from planar_tui.csvio import CsvTable
from planar_tui.figures.arm import draw_arm, joint_points_m
from planar_tui.figures.canvas import colour, new_figure
from planar_tui.figures.table import column, has_columns, numbered

REQUIRED = ("theta1_rad", "omega1_rad_s", "alpha1_rad_s2", "tau1_Nm")


def matches(header: tuple[str, ...]) -> bool:
    return has_columns(header, REQUIRED)


def draw(table: CsvTable, title: str, lengths_m: Any = None) -> Any:
    """Grouped torque bars per state; ``lengths_m`` adds the arm at each state."""
    import numpy as np

    header = table.header
    taus = numbered(header, "tau", "_Nm")
    n = len(taus)
    tau = np.column_stack([column(table, name) for name in taus])
    states = tau.shape[0]
    with_arm = lengths_m is not None and len(lengths_m) == n
    fig = new_figure(11.0 if with_arm else 7.0, 4.5)
    grid = fig.add_gridspec(1, 2 if with_arm else 1, width_ratios=[3, 2] if with_arm else None)
    ax = fig.add_subplot(grid[0, 0])
    width = 0.8 / n
    x = np.arange(states)
    for i in range(n):
        ax.bar(
            x + (i - (n - 1) / 2) * width, tau[:, i], width, color=colour(i, n), label=f"τ{i + 1}"
        )
    ax.axhline(0.0, color="k", lw=0.6)
    ax.set_xticks(x, [f"state {k + 1}" for k in range(states)])
    ax.set(ylabel="joint torque (N m)", title="inverse dynamics τ = Iθ̈ + Cθ̇ − γ")
    ax.legend(fontsize="small", ncols=2 if n > 3 else 1)
    ax.grid(axis="y", alpha=0.3)
    if with_arm:
        arm = fig.add_subplot(grid[0, 1])
        theta = np.column_stack([column(table, name) for name in numbered(header, "theta", "_rad")])
        points = joint_points_m(np.asarray(lengths_m), theta)
        for k in range(states):
            draw_arm(arm, points[k], colour=colour(k, states), label=f"state {k + 1}")
        arm.set(xlabel="x (m)", ylabel="y (m)", title="the states", aspect="equal")
        arm.grid(alpha=0.3)
        arm.legend(fontsize="small")
    fig.suptitle(title)
    return fig


def from_result(job: Any, result: Any) -> Any:
    """The figure of a finished torques job (the arm drawn with the job's robot)."""
    return draw(result.table, job.label, job.robot.lengths_m)

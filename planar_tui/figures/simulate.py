"""Figure of a simulation: joint angles and rates against time, the energies, the energy
balance, and (when the robot is known) the tip's path in the plane with the arm drawn at a
few instants (:mod:`planar_tui.figures.arm`).

The energy-balance panel: with the constant joint torques ``τ`` known (a finished job's
``torques_Nm``), the work they have done is ``W(t) = Σ τ_i (θ_i(t) − θ_i(0))`` (relative
joint angles, the generalised coordinates), so the panel shows the integrator's drift
``E(t) − E(0) − W(t)``, zero for an exact solution. The simulate CSV does not hold the
torques, so a figure drawn from the file alone shows ``E(t) − E(0)`` titled as what it
is: the torques' work ``W(t)`` (plus the drift, orders of magnitude smaller), not a drift.

Read from the simulate CSV (``t_s, theta*_rad, omega*_rad_s, kinetic_J, potential_J,
energy_J``); the CSV does not hold the link lengths either, so a figure drawn from the
file alone has no tip panel.
"""

from __future__ import annotations

from typing import Any

from planar_tui.csvio import CsvTable
from planar_tui.dynamics.simulate import energy_drift_J
from planar_tui.figures.arm import draw_arm, joint_points_m
from planar_tui.figures.canvas import colour, new_figure
from planar_tui.figures.table import column, has_columns, numbered

#: Columns that make a table a simulation's.
REQUIRED = ("t_s", "theta1_rad", "omega1_rad_s", "kinetic_J", "potential_J", "energy_J")
#: Instants at which the arm is drawn on the tip's path.
ARM_POSES = 5


def matches(header: tuple[str, ...]) -> bool:
    return has_columns(header, REQUIRED)


def draw(table: CsvTable, title: str, lengths_m: Any = None, torques_Nm: Any = None) -> Any:
    """The figure of a simulate table; ``lengths_m`` adds the tip's path and the arm,
    ``torques_Nm`` (the run's constant torques) the drift ``E − E(0) − W`` (module doc)."""
    import numpy as np

    header = table.header
    t = column(table, "t_s")
    angles = numbered(header, "theta", "_rad")
    rates = numbered(header, "omega", "_rad_s")
    n = len(angles)
    with_tip = lengths_m is not None and len(lengths_m) == n
    fig = new_figure(12.0 if with_tip else 9.0, 6.5)
    grid = fig.add_gridspec(2, 3 if with_tip else 2)
    ax_theta, ax_omega = fig.add_subplot(grid[0, 0]), fig.add_subplot(grid[0, 1])
    ax_energy, ax_drift = fig.add_subplot(grid[1, 0]), fig.add_subplot(grid[1, 1])
    theta = np.column_stack([column(table, name) for name in angles])
    for i in range(n):
        c = colour(i, n)
        ax_theta.plot(t, np.degrees(theta[:, i]), color=c, label=f"θ{i + 1}", gid="series")
        rate = np.degrees(column(table, rates[i])) if i < len(rates) else None
        if rate is not None:
            ax_omega.plot(t, rate, color=c, label=f"θ̇{i + 1}", gid="series")
    ax_theta.set(xlabel="t (s)", ylabel="relative joint angle (deg)", title="joint angles")
    ax_omega.set(xlabel="t (s)", ylabel="joint rate (deg/s)", title="joint rates")
    energy = column(table, "energy_J")
    for name, label in (("kinetic_J", "kinetic"), ("potential_J", "potential")):
        ax_energy.plot(t, column(table, name), label=label, gid="series")
    ax_energy.plot(t, energy, color="k", lw=1.4, label="total E", gid="series")
    ax_energy.set(xlabel="t (s)", ylabel="energy (J)", title="energy")
    if torques_Nm is not None and len(torques_Nm) == n:
        balance, label, name = energy_drift_J(energy, theta, torques_Nm), "E − E(0) − W", "drift"
    else:
        balance, label, name = energy - energy[0], "E(t) − E(0)", "≈ torques' work W"
    ax_drift.plot(t, balance, color="k", gid="series")
    largest = float(np.max(np.abs(balance)))
    ax_drift.set(xlabel="t (s)", ylabel=f"{label} (J)", title=f"{name}, max {largest:.2e} J")
    for ax in (ax_theta, ax_omega, ax_energy):
        ax.legend(fontsize="small", ncols=2 if n > 3 else 1)
    for ax in (ax_theta, ax_omega, ax_energy, ax_drift):
        ax.grid(alpha=0.3)
    if with_tip:
        _tip_panel(fig.add_subplot(grid[:, 2]), np.asarray(lengths_m), t, theta)
    fig.suptitle(title)
    return fig


def _tip_panel(ax: Any, lengths_m: Any, t: Any, theta: Any) -> None:
    """The tip's path in the plane and the arm at :data:`ARM_POSES` evenly spaced rows."""
    import numpy as np

    points = joint_points_m(lengths_m, theta)
    ax.plot(points[:, -1, 0], points[:, -1, 1], color="k", lw=1.2, label="tip path", gid="tip")
    rows = np.unique(np.linspace(0, len(t) - 1, min(ARM_POSES, len(t))).round().astype(int))
    for k, row in enumerate(rows):
        shade = 0.3 + 0.7 * k / max(len(rows) - 1, 1)
        draw_arm(ax, points[row], colour=(0.1, 0.3, 0.8), alpha=shade, label=f"t = {t[row]:.3g} s")
    ax.set(xlabel="x (m)", ylabel="y (m)", title="tip path and arm", aspect="equal")
    ax.grid(alpha=0.3)
    ax.legend(fontsize="x-small", loc="best")


def from_result(job: Any, result: Any) -> Any:
    """The figure of a finished simulate job (the arm drawn with the job's robot, the
    energy drift net of the work of its torques)."""
    return draw(result.table, job.label, job.robot.lengths_m, job.spec.torques_Nm)

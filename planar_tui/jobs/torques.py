"""The ``[torques]`` job: inverse dynamics at listed states."""

from __future__ import annotations

from dataclasses import dataclass

from planar_tui.jobs.base import JobKind
from planar_tui.model import SerialRobot
from planar_tui.presets import TableReader


@dataclass(frozen=True)
class TorquesSpec:
    """States (rows of relative joint angles, rates, accelerations) to evaluate."""

    theta_deg: tuple[tuple[float, ...], ...]
    omega_deg_s: tuple[tuple[float, ...], ...]
    alpha_deg_s2: tuple[tuple[float, ...], ...]


def parse_torques(reader: TableReader, robot: SerialRobot) -> TorquesSpec:
    """Validate a ``[torques]`` table: every array has the same number of rows of n values."""
    n = robot.n_links
    theta = reader.number_rows("theta_deg", columns=n)
    zeros = ((0.0,) * n,) * len(theta)
    omega = reader.number_rows("omega_deg_s", zeros, columns=n)
    alpha = reader.number_rows("alpha_deg_s2", zeros, columns=n)
    for name, rows in (("omega_deg_s", omega), ("alpha_deg_s2", alpha)):
        if len(rows) != len(theta):
            raise reader.error(name, f"has {len(rows)} rows", f"{len(theta)}, as many as theta_deg")
    return TorquesSpec(theta, omega, alpha)


def dump_torques(spec: TorquesSpec) -> dict:
    """The settings as a ``[torques]`` table."""
    return {
        "theta_deg": [list(row) for row in spec.theta_deg],
        "omega_deg_s": [list(row) for row in spec.omega_deg_s],
        "alpha_deg_s2": [list(row) for row in spec.alpha_deg_s2],
    }


TORQUES = JobKind(
    name="torques",
    robot_kind="robot",
    keys=("theta_deg", "omega_deg_s", "alpha_deg_s2"),
    parse=parse_torques,
    dump=dump_torques,
    runner="planar_tui.runners.torques:run_torques",
    summary="inverse dynamics at listed states",
)

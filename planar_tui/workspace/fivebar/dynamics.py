"""The five-bar's path kinematics and inverse dynamics: the RR-leg kernel of
:mod:`planar_tui.kernels.dynamics5r` with a point platform (the end mass at ``P``, the
pose :math:`X = (x, y)`), its legs and bodies as the kernel's arrays, in SI."""

from __future__ import annotations

from typing import Any

from planar_tui.workspace.path.model import SINGULAR_RELATIVE, PathSolution


def leg_rows(robot: Any, elbow: Any) -> Any:
    """The kernel's (2, 9) leg rows: ``A_i``, ``q_i = 0`` and ``l1, l2`` in m, the elbow
    sign, the joint limit's start and width (rad)."""
    import numpy as np

    rows = []
    for (ax, ay), l1, l2, sign, (lo, hi) in zip(
        robot.base_joints_cm(),
        robot.proximal_cm,
        robot.distal_cm,
        elbow,
        robot.limits_rad,
        strict=True,
    ):
        rows.append([ax / 100.0, ay / 100.0, 0.0, 0.0, l1 / 100.0, l2 / 100.0, sign, lo, hi - lo])
    return np.array(rows)


def body_array(robot: Any) -> Any:
    """The kernel's body entries: link masses and inertias, the end mass (no inertia)."""
    import numpy as np

    return np.array(
        [
            robot.proximal_mass_kg,
            robot.proximal_inertia_kgm2,
            robot.distal_mass_kg,
            robot.distal_inertia_kgm2,
            robot.end_mass_kg,
            0.0,
            robot.gravity_m_s2,
        ]
    )


def path_arrays(robot: Any, spec: Any) -> tuple[int, Any, Any]:
    """The leg family of :func:`~planar_tui.kernels.dynamics_robots.robots_path_efforts`
    (RR_LEGS), the leg rows and the body entries of ``robot`` in the working mode of
    ``spec``: what :func:`solve_path` solves with."""
    from planar_tui.kernels.dynamics_robots import RR_LEGS

    return RR_LEGS, leg_rows(robot, spec.elbow), body_array(robot)


def solve_path(robot: Any, spec: Any, pose: Any, rate: Any, acceleration: Any) -> PathSolution:
    """The legs' angles, rates, accelerations and the torques at every end-effector state
    ``(x, y)`` (SI) in the working mode ``spec.elbow``, within the robot's joint limits."""
    from planar_tui.kernels.dynamics5r import solve_fivebar_path

    _, legs, body = path_arrays(robot, spec)
    return PathSolution(
        *solve_fivebar_path(legs, body, pose, rate, acceleration, SINGULAR_RELATIVE)
    )

"""The 3-RRR's path kinematics and inverse dynamics (:mod:`planar_tui.kernels.dynamics3rrr`,
whose docstring holds the equations): its legs and bodies as the kernel's arrays, in SI."""

from __future__ import annotations

import math
from typing import Any

from planar_tui.workspace.path.model import SINGULAR_RELATIVE, PathSolution

#: A leg without joint limits: the angle reported in [-pi, pi), any width allowed.
NO_LIMITS = (-math.pi, 4.0 * math.pi)


def leg_rows(robot: Any, elbow: Any, limits_rad: Any) -> Any:
    """The kernel's (3, 9) leg rows: ``A_i``, ``q_i`` and ``l1, l2`` in m, the elbow sign,
    the joint limit's start and width (rad; ``limits_rad`` ``None``: no limits)."""
    import numpy as np

    rows = []
    limits = limits_rad or (None,) * 3
    for (ax, ay), (qx, qy), sign, limit in zip(
        robot.base_joints_cm(), robot.platform_points_cm(), elbow, limits, strict=True
    ):
        lo, width = NO_LIMITS if limit is None else (limit[0], limit[1] - limit[0])
        lengths = (ax, ay, qx, qy, robot.proximal_cm, robot.distal_cm)
        rows.append([v / 100.0 for v in lengths] + [float(sign), lo, width])
    return np.array(rows)


def body_array(robot: Any) -> Any:
    """The kernel's body entries: link masses and inertias, platform's, gravity."""
    import numpy as np

    return np.array(
        [
            robot.proximal_mass_kg,
            robot.proximal_inertia_kgm2,
            robot.distal_mass_kg,
            robot.distal_inertia_kgm2,
            robot.platform_mass_kg,
            robot.platform_inertia_kgm2,
            robot.gravity_m_s2,
        ]
    )


def path_arrays(robot: Any, spec: Any) -> tuple[int, Any, Any]:
    """The leg family of :func:`~planar_tui.kernels.dynamics_robots.robots_path_efforts`
    (RR_LEGS), the leg rows and the body entries of ``robot`` in the working mode of
    ``spec``: what :func:`solve_path` solves with."""
    from planar_tui.kernels.dynamics_robots import RR_LEGS

    return RR_LEGS, leg_rows(robot, spec.elbow, spec.limits_rad), body_array(robot)


def solve_path(robot: Any, spec: Any, pose: Any, rate: Any, acceleration: Any) -> PathSolution:
    """The legs' angles, rates, accelerations and the torques at every platform state
    ``(x, y, phi)`` (SI) in the working mode ``spec.elbow``, within ``spec.limits_rad``."""
    from planar_tui.kernels.dynamics3rrr import solve_rr_path

    _, legs, body = path_arrays(robot, spec)
    return PathSolution(*solve_rr_path(legs, body, pose, rate, acceleration, SINGULAR_RELATIVE))

"""The 3-RPR's path kinematics and inverse dynamics (:mod:`planar_tui.kernels.dynamics3rpr`,
whose docstring holds the equations and the cylinder-and-piston body model): its legs and
bodies as the kernel's arrays, in SI."""

from __future__ import annotations

import math
from typing import Any

from planar_tui.workspace.path.model import SINGULAR_RELATIVE, PathSolution


def leg_rows(robot: Any, limits_cm: Any) -> Any:
    """The kernel's (3, 6) leg rows: ``A_i``, ``q_i`` and the stroke limits in m
    (``limits_cm`` ``None``: no limits)."""
    import numpy as np

    limits = limits_cm or ((0.0, math.inf),) * 3
    return np.array(
        [
            [v / 100.0 for v in (ax, ay, qx, qy, lo, hi)]
            for (ax, ay), (qx, qy), (lo, hi) in zip(
                robot.base_joints_cm, robot.platform_points_cm, limits, strict=True
            )
        ]
    )


def body_array(robot: Any) -> Any:
    """The kernel's body entries: cylinder and piston (mass, inertia, centre of mass in m),
    platform (mass, inertia), gravity."""
    import numpy as np

    return np.array(
        [
            robot.cylinder_mass_kg,
            robot.cylinder_inertia_kgm2,
            robot.cylinder_com_cm / 100.0,
            robot.piston_mass_kg,
            robot.piston_inertia_kgm2,
            robot.piston_com_cm / 100.0,
            robot.platform_mass_kg,
            robot.platform_inertia_kgm2,
            robot.gravity_m_s2,
        ]
    )


def path_arrays(robot: Any, spec: Any) -> tuple[int, Any, Any]:
    """The leg family of :func:`~planar_tui.kernels.dynamics_robots.robots_path_efforts`
    (RPR_LEGS), the leg rows and the body entries of ``robot`` in the working mode of
    ``spec``: what :func:`solve_path` solves with."""
    from planar_tui.kernels.dynamics_robots import RPR_LEGS

    return RPR_LEGS, leg_rows(robot, spec.leg_limits_cm), body_array(robot)


def solve_path(robot: Any, spec: Any, pose: Any, rate: Any, acceleration: Any) -> PathSolution:
    """The leg lengths, their rates and accelerations and the leg forces at every platform
    state ``(x, y, phi)`` (SI), within ``spec.leg_limits_cm``."""
    from planar_tui.kernels.dynamics3rpr import rpr_path_dynamics
    from planar_tui.kernels.dynamics3rrr import solve_legs

    _, legs, body = path_arrays(robot, spec)
    return PathSolution(
        *solve_legs(
            rpr_path_dynamics,
            legs,
            body,
            pose,
            rate,
            acceleration,
            SINGULAR_RELATIVE,
        )
    )

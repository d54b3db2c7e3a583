"""The 3-PRR's path kinematics and inverse dynamics (:mod:`planar_tui.kernels.dynamics3prr`,
whose docstring holds the equations and the slider-and-link body model): its legs and
bodies as the kernel's arrays, in SI. Its actuated coordinate is each slider's stroke
:math:`s_i` along its rail (the path CSV's ``rho1_cm`` ...)."""

from __future__ import annotations

import math
from typing import Any

from planar_tui.workspace.path.model import SINGULAR_RELATIVE, PathSolution


def leg_rows(robot: Any, modes: Any) -> Any:
    """The kernel's (3, 10) leg rows: the rail's point ``B_i`` and direction ``u_i``, ``q_i``
    and the link length in m, the working mode's sign, the stroke limits in m."""
    import numpy as np

    rows = []
    for (bx, by), angle, (qx, qy), length, sign, (lo, hi) in zip(
        robot.slider_points_cm,
        robot.slider_angles_deg,
        robot.platform_points_cm,
        robot.distal_cm,
        modes,
        robot.strokes_cm,
        strict=True,
    ):
        u = (math.cos(math.radians(angle)), math.sin(math.radians(angle)))
        rows.append(
            [bx / 100, by / 100, *u, qx / 100, qy / 100, length / 100, sign, lo / 100, hi / 100]
        )
    return np.array(rows)


def body_array(robot: Any) -> Any:
    """The kernel's body entries: slider mass, link mass and inertia, platform's, gravity."""
    import numpy as np

    return np.array(
        [
            robot.slider_mass_kg,
            robot.link_mass_kg,
            robot.link_inertia_kgm2,
            robot.platform_mass_kg,
            robot.platform_inertia_kgm2,
            robot.gravity_m_s2,
        ]
    )


def path_arrays(robot: Any, spec: Any) -> tuple[int, Any, Any]:
    """The leg family of :func:`~planar_tui.kernels.dynamics_robots.robots_path_efforts`
    (PRR_LEGS), the leg rows and the body entries of ``robot`` in the working mode of
    ``spec``: what :func:`solve_path` solves with."""
    from planar_tui.kernels.dynamics_robots import PRR_LEGS

    return PRR_LEGS, leg_rows(robot, spec.slider_modes), body_array(robot)


def solve_path(robot: Any, spec: Any, pose: Any, rate: Any, acceleration: Any) -> PathSolution:
    """The strokes, their rates and accelerations and the slider forces at every platform
    state ``(x, y, phi)`` (SI) in the working mode ``spec.slider_modes``, within the
    robot's strokes."""
    from planar_tui.kernels.dynamics3prr import prr_path_dynamics
    from planar_tui.kernels.dynamics3rrr import solve_legs

    _, legs, body = path_arrays(robot, spec)
    return PathSolution(
        *solve_legs(
            prr_path_dynamics,
            legs,
            body,
            pose,
            rate,
            acceleration,
            SINGULAR_RELATIVE,
        )
    )

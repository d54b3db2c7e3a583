"""Orientation ranges of the 3-RPR: ``orientation_deg = [lo, hi]`` with ``orientation_mode``
(``maximal``: positions reachable with some φ of the range, ``total``: with every one), as
for the 3-RRR (:mod:`planar_tui.workspace.paving.orientation`, whose keys, checks and paving this
reuses through :func:`planar_tui.workspace.paving.runner.compute_range`).

Each (x, y) box is classified by
:func:`planar_tui.kernels.workspace_orientation.classify_box_range` with the 3-RPR's piece
test (:func:`planar_tui.kernels.workspace_parallel_orientation.parallel_piece_status`: the leg
distance over the box and the piece :math:`[m - h, m + h]` lies in :math:`[D_{lo} -
\\delta_i, D_{hi} + \\delta_i]`, :math:`[D_{lo}, D_{hi}]` the exact distance range from
:math:`c_i(m) = A_i - R(m) q_i` over the box and :math:`\\delta_i = 2|q_i|\\sin(h/2)`), so
the bracket ``area_inside <= exact <= area_kept`` is certified. With a range the job has no
exact reference (``geometric_reference`` and ``form = "geometric"`` are refused), no
tolerance and no singularities.
"""

from __future__ import annotations

from typing import Any

from planar_tui.workspace.paving import runner as planar
from planar_tui.workspace.rpr.robot import Robot3RPR


def compute_range(robot: Robot3RPR, spec: Any, budget: Any) -> Any:
    """The maximal or total orientation workspace of a 3-RPR spec with ``orientation_deg =
    (lo, hi)`` (:class:`~planar_tui.workspace.paving.levels.WorkspaceOutcome`); ``g`` holds the
    platform points and base joints, ``limits`` the (3, 2) leg limits."""
    import numpy as np

    from planar_tui.kernels.workspace_orientation import RPR

    g = planar.platform_and_base_vector(robot.platform_points_cm, robot.base_joints_cm)
    limits = np.ascontiguousarray(spec.leg_limits_cm, dtype=np.float64)
    return planar.compute_range(robot, spec, budget, g, limits, RPR)

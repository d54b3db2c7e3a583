"""Orientation ranges of the 3-RPR: ``orientation_deg = [lo, hi]`` with ``orientation_mode``
(``maximal``: positions reachable with some φ of the range, ``total``: with every one), as
for the 3-RRR (:mod:`planar_tui.workspace.orientation`, whose keys, checks and paving this
reuses).

Each (x, y) box is classified by
:func:`planar_tui.kernels.workspace_orientation.classify_box_range` with the 3-RPR's piece
test (:func:`planar_tui.kernels.workspace3rpr_orientation.rpr_piece_status`: the leg
distance over the box and the piece :math:`[m - h, m + h]` lies in :math:`[D_{lo} -
\\delta_i, D_{hi} + \\delta_i]`, :math:`[D_{lo}, D_{hi}]` the exact distance range from
:math:`c_i(m) = A_i - R(m) q_i` over the box and :math:`\\delta_i = 2|q_i|\\sin(h/2)`), so
the bracket ``area_inside <= exact <= area_kept`` is certified. With a range the job has no
exact reference (``geometric_reference`` and ``form = "geometric"`` are refused), no
tolerance and no singularities.
"""

from __future__ import annotations

import time
from typing import Any

from planar_tui.workspace.rpr import Robot3RPR


def geometry_vector(robot: Robot3RPR) -> Any:
    """``[0, 0, q1, q2, q3, A1, A2, A3]`` flattened (cm): the 3-RRR's layout of the kernels'
    ``g`` (:mod:`planar_tui.kernels.workspace3rpr_orientation`)."""
    import numpy as np

    values = [0.0, 0.0]
    for point in (*robot.platform_points_cm, *robot.base_joints_cm):
        values += [float(point[0]), float(point[1])]
    return np.array(values)


def compute_range(robot: Robot3RPR, spec: Any, budget: Any) -> Any:
    """The maximal or total orientation workspace of a 3-RPR spec with ``orientation_deg =
    (lo, hi)`` (:class:`~planar_tui.workspace.compute.WorkspaceOutcome`)."""
    import numpy as np

    from planar_tui.kernels.workspace_orientation import RPR
    from planar_tui.workspace.compute import square_about
    from planar_tui.workspace.orientation import paved_range, range_stage
    from planar_tui.workspace.rpr import reach_box

    started = time.perf_counter()
    box = spec.search_box_cm or square_about(reach_box(robot, spec), spec.precision_cm)
    extent = (box[0][0], box[0][1], box[1][0], box[1][1])
    g = geometry_vector(robot)
    limits = np.ascontiguousarray(spec.leg_limits_cm, dtype=np.float64)
    points = robot.platform_points_cm

    def stage(seeds, precision, inside_cm2):
        return range_stage(g, limits, RPR, points, spec, seeds, precision, budget, inside_cm2)

    return paved_range(stage, spec, budget, extent, None, started, disjoint=True)

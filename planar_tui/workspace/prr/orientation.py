"""Orientation ranges of the 3-PRR: ``orientation_deg = [lo, hi]`` with ``orientation_mode``
(``maximal`` or ``total``), as for the 3-RRR and the 3-RPR
(:mod:`planar_tui.workspace.rpr.orientation`; the shared paving is
:func:`planar_tui.workspace.paving.runner.compute_range`).

Each (x, y) box is classified by
:func:`planar_tui.kernels.workspace_orientation.classify_box_range` with the 3-PRR's piece
test (:func:`planar_tui.kernels.workspace_parallel_orientation.parallel_piece_status`: the distance
to the stroke and to its far end are 1-Lipschitz in the platform point, which moves by at
most :math:`\\delta_i = 2|q_i|\\sin(h/2)` over the piece :math:`[m - h, m + h]`, so the
one-orientation test at :math:`m` with the distal length shifted by :math:`\\pm\\delta_i` is
certified over the piece). No exact reference, tolerance or singularities over a range.
"""

from __future__ import annotations

import math
from typing import Any

from planar_tui.workspace.paving import runner as planar
from planar_tui.workspace.prr.robot import Robot3PRR


def compute_range(robot: Robot3PRR, spec: Any, budget: Any) -> Any:
    """The maximal or total orientation workspace of a 3-PRR spec with ``orientation_deg =
    (lo, hi)``; ``g`` holds the platform points and slider line points, ``limits`` per leg
    ``ux, uy, s_lo, s_hi, l`` (:mod:`planar_tui.kernels.workspace_parallel_orientation`)."""
    import numpy as np

    from planar_tui.kernels.workspace_orientation import PRR

    g = planar.platform_and_base_vector(robot.platform_points_cm, robot.slider_points_cm)
    rows = [
        (math.cos(math.radians(angle)), math.sin(math.radians(angle)), lo, hi, length)
        for angle, (lo, hi), length in zip(
            robot.slider_angles_deg, robot.strokes_cm, robot.distal_cm, strict=True
        )
    ]
    limits = np.ascontiguousarray(rows, dtype=np.float64)
    return planar.compute_range(robot, spec, budget, g, limits, PRR)

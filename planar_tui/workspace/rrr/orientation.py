"""The 3-RRR's orientation workspaces (``orientation_deg = [lo, hi]``): its reach over the
range, its arrays for the range kernel, and the paving with its sampled reference; the
range paving itself is the core's (:mod:`planar_tui.workspace.paving.orientation`)."""

from __future__ import annotations

import math
import time

from planar_tui.workspace.paving.orientation import (
    paved_range,
    range_reach_box,
    range_stage,
)
from planar_tui.workspace.rrr.robot import Robot3RRR


def default_form(robot, values) -> str:
    """The form's default: ``arc-distance`` over a range of orientations, else
    ``mean-value``."""
    return "arc-distance" if isinstance(values.get("orientation_deg"), tuple) else "mean-value"


def reach_box_for(robot: Robot3RRR, orientation_deg) -> tuple[float, float, float, float]:
    """Bounding box of the legs' reach at one orientation, or of the union of the reaches
    over a range (:func:`range_reach_box` with every leg's reach :math:`l_1 + l_2`)."""
    if not isinstance(orientation_deg, tuple):
        return robot.reach_box_cm(math.radians(orientation_deg))
    reach = robot.proximal_cm + robot.distal_cm
    return range_reach_box(
        robot.base_joints_cm(), robot.platform_points_cm(), (reach,) * 3, orientation_deg
    )


def search_box(robot: Robot3RRR, spec) -> tuple[tuple[float, float], tuple[float, float]]:
    """The job's ``search_box_cm`` or a square about the reach box whose side is
    ``precision_cm * 2**n`` (smallest n)."""
    if spec.search_box_cm is not None:
        return spec.search_box_cm
    xlo, xhi, ylo, yhi = reach_box_for(robot, spec.orientation_deg)
    if xlo > xhi or ylo > yhi:
        xlo = xhi = ylo = yhi = 0.0
    side = spec.precision_cm
    while side < max(xhi - xlo, yhi - ylo):
        side *= 2.0
    cx, cy = 0.5 * (xlo + xhi), 0.5 * (ylo + yhi)
    return ((cx - 0.5 * side, cx + 0.5 * side), (cy - 0.5 * side, cy + 0.5 * side))


def geometry_vector(robot: Robot3RRR):
    """``[l1, l2, q1, q2, q3, A1, A2, A3]`` flattened (cm), the kernels' ``g``."""
    import numpy as np

    values = [robot.proximal_cm, robot.distal_cm]
    for point in (*robot.platform_points_cm(), *robot.base_joints_cm()):
        values += [float(point[0]), float(point[1])]
    return np.array(values)


def _range_stage(robot, spec, seeds, precision, budget, inside_cm2=0.0):
    """:func:`range_stage` of a 3-RRR."""
    from planar_tui.kernels.workspace_arc import limits_array
    from planar_tui.kernels.workspace_orientation import RRR

    g, limits = geometry_vector(robot), limits_array(spec.limits_rad)
    points = robot.platform_points_cm()
    return range_stage(g, limits, RRR, points, spec, seeds, precision, budget, inside_cm2)


def compute_orientation_workspace(robot: Robot3RRR, spec, budget):
    """The maximal or total orientation workspace of ``spec`` (``orientation_deg`` a range)
    as a :class:`~planar_tui.workspace.paving.levels.WorkspaceOutcome`: the bisection down to
    ``precision_cm``, then the boundary boxes again down to ``refine_precision_cm``."""
    from planar_tui.workspace.rrr.orientation_reference import reference_area

    started = time.perf_counter()
    box = search_box(robot, spec)
    extent = (box[0][0], box[0][1], box[1][0], box[1][1])
    geometric = None
    if spec.geometric_reference:
        budget.progress.start(1.0, "sampled reference")
        geometric = budget.progress.wait_for(
            reference_area, robot, spec.limits_rad, spec.orientation_deg, spec.orientation_mode
        )

    def stage(seeds, precision, inside_cm2):
        return _range_stage(robot, spec, seeds, precision, budget, inside_cm2)

    return paved_range(stage, spec, budget, extent, geometric, started)

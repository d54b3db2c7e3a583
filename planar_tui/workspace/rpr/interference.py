"""The 3-RPR's clearance evaluator (:meth:`~planar_tui.workspace.paving.mechanism.Mechanism.
interference`): :func:`kernels.interference_prismatic.rpr_interference` with the job's base
joints, annuli centres, platform offsets, leg limits and ``leg_width_cm``: each leg one
link :math:`A_i C_i`, the platform the triangle :math:`C_1 C_2 C_3`. Its legs have one
branch: no working mode."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from planar_tui.workspace.rpr.singularity import offsets_cm


def evaluator(robot: Any, spec: Any) -> Callable[[Any], tuple[Any, Any]]:
    """Boxes (k, 4) to ``(verdict, gap)``."""
    import numpy as np

    bases = np.array(robot.base_joints_cm, dtype=float)
    centres = np.array(robot.centres_cm(spec.orientation_rad), dtype=float)
    offsets = offsets_cm(robot, spec.orientation_rad)
    limits = np.array(spec.leg_limits_cm, dtype=float)
    width = float(spec.leg_width_cm)

    def evaluate(boxes: Any) -> tuple[Any, Any]:
        from planar_tui.kernels.interference_prismatic import rpr_interference  # numba

        verdict = np.empty(len(boxes), dtype=np.int64)
        gap = np.empty((len(boxes), 2))
        boxes = np.ascontiguousarray(boxes)
        rpr_interference(boxes, bases, centres, offsets, limits, width, verdict, gap)
        return verdict, gap

    return evaluate

"""The 3-RRR's pose error evaluator (:meth:`~planar_tui.workspace.paving.mechanism.Mechanism.
accuracy`): :func:`kernels.accuracy_rr.rr_accuracy` with the job's geometry, working mode
(resolved by :func:`~planar_tui.workspace.rrr.singularity.resolve_circle`, or the given
``elbow`` over an orientation range) and errors: the active angles :math:`\\theta_i` within
``actuator_deg``; the base joints :math:`A_i`, the platform joints :math:`c_i` (each
coordinate, the platform's in its own frame) and each leg's proximal and distal lengths
within ``tolerance_cm``."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from planar_tui.workspace.paving.accuracy import AccuracySpec, at_orientation
from planar_tui.workspace.rrr.orientation import geometry_vector
from planar_tui.workspace.rrr.singularity import Circle


def pose_evaluator(robot: Any, spec: Any, elbow: Any) -> Callable[[Any], tuple[Any, Any]]:
    """Pose boxes (k, 6) ``x_lo, x_hi, y_lo, y_hi, phi_lo, phi_hi`` to ``(verdict, bound)``
    in the working mode ``elbow``."""
    import numpy as np

    from planar_tui.kernels.workspace_arc import limits_array

    rows = np.tile(geometry_vector(robot), (3, 1))  # one geometry row per leg
    q = np.array(robot.platform_points_cm(), dtype=np.float64)
    signs = np.array(elbow, dtype=np.float64)
    limits = limits_array(spec.limits_rad)
    errors = np.array(AccuracySpec.of(spec.accuracy, "deg").kernel_errors())

    def evaluate(boxes: Any) -> tuple[Any, Any]:
        from planar_tui.kernels.accuracy_rr import rr_accuracy  # numba

        verdict = np.empty(len(boxes), dtype=np.int64)
        bound = np.empty((len(boxes), 3))
        rr_accuracy(np.ascontiguousarray(boxes), rows, q, signs, limits, errors, verdict, bound)
        return verdict, bound

    return evaluate


def evaluator(robot: Any, spec: Any, circle: Circle) -> Callable[[Any], tuple[Any, Any]]:
    """Boxes (k, 4) to ``(verdict, bound)`` at the spec's orientation in the working mode
    ``circle.elbow``."""
    return at_orientation(pose_evaluator(robot, spec, circle.elbow), spec.orientation_rad)

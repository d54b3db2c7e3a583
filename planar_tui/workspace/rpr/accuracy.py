"""The 3-RPR's pose error evaluator (:meth:`~planar_tui.workspace.paving.mechanism.Mechanism.
accuracy`): :func:`kernels.accuracy_prismatic.rpr_accuracy` with the job's base joints,
platform points, leg limits and errors: the legs' lengths within ``actuator_cm``; the base
joints :math:`A_i` and the platform joints :math:`c_i` (each coordinate, the platform's in
its own frame) within ``tolerance_cm``. Its legs have one branch: no working mode."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from planar_tui.workspace.paving.accuracy import AccuracySpec, at_orientation


def pose_evaluator(robot: Any, spec: Any) -> Callable[[Any], tuple[Any, Any]]:
    """Pose boxes (k, 6) ``x_lo, x_hi, y_lo, y_hi, phi_lo, phi_hi`` to ``(verdict,
    bound)``."""
    import numpy as np

    bases = np.array(robot.base_joints_cm, dtype=np.float64)
    q = np.array(robot.platform_points_cm, dtype=np.float64)
    limits = np.array(spec.leg_limits_cm, dtype=np.float64)
    errors = np.array(AccuracySpec.of(spec.accuracy, "cm").kernel_errors())

    def evaluate(boxes: Any) -> tuple[Any, Any]:
        from planar_tui.kernels.accuracy_prismatic import rpr_accuracy  # numba

        verdict = np.empty(len(boxes), dtype=np.int64)
        bound = np.empty((len(boxes), 3))
        rpr_accuracy(np.ascontiguousarray(boxes), bases, q, limits, errors, verdict, bound)
        return verdict, bound

    return evaluate


def evaluator(robot: Any, spec: Any) -> Callable[[Any], tuple[Any, Any]]:
    """Boxes (k, 4) to ``(verdict, bound)`` at the spec's orientation."""
    return at_orientation(pose_evaluator(robot, spec), spec.orientation_rad)

"""The five-bar's pose error evaluator (:meth:`~planar_tui.workspace.paving.mechanism.
Mechanism.accuracy`): :func:`kernels.accuracy_rr.rr_accuracy` with its two legs in the
robot's ``working_mode`` and the errors: the active angles :math:`\\theta_i` within
``actuator_deg``; the base joints :math:`A_i` (each coordinate) and each leg's proximal and
distal lengths within ``tolerance_cm``. Its tip is the distal links' common joint: bounds
of :math:`|\\Delta x|, |\\Delta y|` only."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from planar_tui.workspace.fivebar.singularity import kernel_inputs
from planar_tui.workspace.paving.accuracy import AccuracySpec, at_orientation


def evaluator(robot: Any, spec: Any) -> Callable[[Any], tuple[Any, Any]]:
    """Boxes (k, 4) to ``(verdict, bound)`` (bound (k, 2), cm) in the robot's working mode
    (not ``any``)."""
    import numpy as np

    g, q, _, limits, _ = kernel_inputs(robot)  # q: the point platform's zero offsets
    elbow = np.array(robot.elbows, dtype=float)
    errors = np.array(AccuracySpec.of(spec.accuracy, "deg").kernel_errors(platform=False))

    def evaluate(boxes: Any) -> tuple[Any, Any]:
        from planar_tui.kernels.accuracy_rr import rr_accuracy  # numba

        verdict = np.empty(len(boxes), dtype=np.int64)
        bound = np.empty((len(boxes), 2))
        rr_accuracy(np.ascontiguousarray(boxes), g, q, elbow, limits, errors, verdict, bound)
        return verdict, bound

    return at_orientation(evaluate, 0.0)

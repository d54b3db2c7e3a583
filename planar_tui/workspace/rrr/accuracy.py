"""The 3-RRR's pose error evaluator (:meth:`~planar_tui.workspace.paving.mechanism.Mechanism.
accuracy`): :func:`kernels.accuracy_rr.rr_accuracy` with the job's geometry, working mode
(resolved by :func:`~planar_tui.workspace.rrr.singularity.resolve_circle`) and errors: the
active angles :math:`\\theta_i` within ``actuator_deg``; the base joints :math:`A_i`, the
platform joints :math:`c_i` (each coordinate, the platform's in its own frame) and each
leg's proximal and distal lengths within ``tolerance_cm``."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from planar_tui.workspace.paving.accuracy import AccuracySpec
from planar_tui.workspace.rrr.singularity import Circle, kernel_inputs


def evaluator(robot: Any, spec: Any, circle: Circle) -> Callable[[Any], tuple[Any, Any]]:
    """Boxes (k, 4) to ``(verdict, bound)`` in the working mode ``circle.elbow``."""
    import numpy as np

    g, r, elbow, limits = kernel_inputs(robot, spec, circle)
    rows = np.tile(g, (3, 1))  # one geometry row per leg
    errors = np.array(AccuracySpec.of(spec.accuracy, "deg").kernel_errors(spec.orientation_rad))

    def evaluate(boxes: Any) -> tuple[Any, Any]:
        from planar_tui.kernels.accuracy_rr import rr_accuracy  # numba

        verdict = np.empty(len(boxes), dtype=np.int64)
        bound = np.empty((len(boxes), 3))
        rr_accuracy(np.ascontiguousarray(boxes), rows, r, elbow, limits, errors, verdict, bound)
        return verdict, bound

    return evaluate

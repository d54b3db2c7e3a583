"""The 3-RPR's pose error evaluator (:meth:`~planar_tui.workspace.paving.mechanism.Mechanism.
accuracy`): :func:`kernels.accuracy_prismatic.rpr_accuracy` with the job's annuli centres,
platform offsets, leg limits and errors: the legs' lengths within ``actuator_cm``; the base
joints :math:`A_i` and the platform joints :math:`c_i` (each coordinate, the platform's in
its own frame) within ``tolerance_cm``. Its legs have one branch: no working mode."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from planar_tui.workspace.paving.accuracy import AccuracySpec
from planar_tui.workspace.rpr.singularity import offsets_cm


def evaluator(robot: Any, spec: Any) -> Callable[[Any], tuple[Any, Any]]:
    """Boxes (k, 4) to ``(verdict, bound)``."""
    import numpy as np

    phi = spec.orientation_rad
    centres = np.array(robot.centres_cm(phi), dtype=float)
    offsets = offsets_cm(robot, phi)
    limits = np.array(spec.leg_limits_cm, dtype=float)
    errors = np.array(AccuracySpec.of(spec.accuracy, "cm").kernel_errors(phi))

    def evaluate(boxes: Any) -> tuple[Any, Any]:
        from planar_tui.kernels.accuracy_prismatic import rpr_accuracy  # numba

        verdict = np.empty(len(boxes), dtype=np.int64)
        bound = np.empty((len(boxes), 3))
        rpr_accuracy(np.ascontiguousarray(boxes), centres, offsets, limits, errors, verdict, bound)
        return verdict, bound

    return evaluate

"""The 3-PRR's pose error evaluator (:meth:`~planar_tui.workspace.paving.mechanism.Mechanism.
accuracy`): :func:`kernels.accuracy_prismatic.prr_accuracy` with the job's slider lines,
strokes, links, working mode (``slider_modes``, resolved as for ``kappa_max``, or given
over an orientation range) and errors: the sliders' positions within ``actuator_cm``; each
slider line's point (each coordinate; its direction exact), the platform joints
:math:`c_i` (each coordinate, in the platform's frame) and each distal length within
``tolerance_cm``."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from planar_tui.workspace.paving.accuracy import AccuracySpec, at_orientation
from planar_tui.workspace.prr.singularity import slider_rows


def pose_evaluator(job: Any, modes: tuple[int, int, int]) -> Callable[[Any], tuple[Any, Any]]:
    """Pose boxes (k, 6) ``x_lo, x_hi, y_lo, y_hi, phi_lo, phi_hi`` to ``(verdict,
    bound)`` in the slider ``modes``."""
    import numpy as np

    spec = job.spec
    g = slider_rows(job.robot)
    q = np.array(job.robot.platform_points_cm, dtype=np.float64)
    sigma = np.array(modes, dtype=np.float64)
    errors = np.array(AccuracySpec.of(spec.accuracy, "cm").kernel_errors())

    def evaluate(boxes: Any) -> tuple[Any, Any]:
        from planar_tui.kernels.accuracy_prismatic import prr_accuracy  # numba

        verdict = np.empty(len(boxes), dtype=np.int64)
        bound = np.empty((len(boxes), 3))
        prr_accuracy(np.ascontiguousarray(boxes), g, sigma, q, errors, verdict, bound)
        return verdict, bound

    return evaluate


def evaluator(job: Any, modes: tuple[int, int, int]) -> Callable[[Any], tuple[Any, Any]]:
    """Boxes (k, 4) to ``(verdict, bound)`` at the spec's orientation in the slider
    ``modes``."""
    return at_orientation(pose_evaluator(job, modes), job.spec.orientation_rad)

"""The 3-RRR's clearance evaluator (:meth:`~planar_tui.workspace.paving.mechanism.Mechanism.
interference`): :func:`kernels.interference_rr.rr_interference` with the job's geometry,
``leg_width_cm`` and working mode (resolved by
:func:`~planar_tui.workspace.rrr.singularity.resolve_circle`): per leg the proximal link
:math:`A_i B_i` and the distal link :math:`B_i C_i`, the platform the triangle
:math:`C_1 C_2 C_3`."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from planar_tui.workspace.rrr.singularity import Circle, kernel_inputs


def evaluator(robot: Any, spec: Any, circle: Circle) -> Callable[[Any], tuple[Any, Any]]:
    """Boxes (k, 4) to ``(verdict, gap)`` in the working mode ``circle.elbow``."""
    import numpy as np

    g, r, elbow, limits = kernel_inputs(robot, spec, circle)
    rows = np.tile(g, (3, 1))  # one geometry row per leg
    width = float(spec.leg_width_cm)

    def evaluate(boxes: Any) -> tuple[Any, Any]:
        from planar_tui.kernels.interference_rr import rr_interference  # numba

        verdict = np.empty(len(boxes), dtype=np.int64)
        gap = np.empty((len(boxes), 2))
        rr_interference(np.ascontiguousarray(boxes), rows, r, elbow, limits, width, verdict, gap)
        return verdict, gap

    return evaluate

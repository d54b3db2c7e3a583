"""The five-bar's clearance evaluator (:meth:`~planar_tui.workspace.paving.mechanism.
Mechanism.interference`): :func:`kernels.interference_rr.rr_interference` with its two legs
in the robot's ``working_mode``: per leg the proximal link :math:`A_i B_i` and the distal
link :math:`B_i P` to the end point :math:`P` (the two distal links share that joint and
are not checked against each other; no platform polygon)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from planar_tui.workspace.fivebar.singularity import kernel_inputs


def evaluator(robot: Any, spec: Any) -> Callable[[Any], tuple[Any, Any]]:
    """Boxes (k, 4) to ``(verdict, gap)`` in the robot's working mode (not ``any``)."""
    import numpy as np

    g, r, _, limits, _ = kernel_inputs(robot)
    elbow = np.array(robot.elbows, dtype=float)
    width = float(spec.leg_width_cm)

    def evaluate(boxes: Any) -> tuple[Any, Any]:
        from planar_tui.kernels.interference_rr import rr_interference  # numba

        verdict = np.empty(len(boxes), dtype=np.int64)
        gap = np.empty((len(boxes), 2))
        rr_interference(np.ascontiguousarray(boxes), g, r, elbow, limits, width, verdict, gap)
        return verdict, gap

    return evaluate

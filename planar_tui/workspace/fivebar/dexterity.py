"""The five-bar's κ evaluator (:meth:`~planar_tui.workspace.paving.mechanism.Mechanism.
dexterity`): :func:`kernels.dexterity_rr.rr_dexterity` with its two legs in the robot's
``working_mode`` (:math:`J` maps :math:`(\\dot\\theta_1, \\dot\\theta_2)` to
:math:`(\\dot x, \\dot y)`: no characteristic length)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from planar_tui.workspace.fivebar.singularity import kernel_inputs


def evaluator(robot: Any) -> Callable[[Any], tuple[Any, Any]]:
    """Boxes (k, 4) to ``(verdict, kappa)`` in the robot's working mode (not ``any``)."""
    import numpy as np

    g, r, _, limits, _ = kernel_inputs(robot)
    elbow = np.array(robot.elbows, dtype=float)

    def evaluate(boxes: Any) -> tuple[Any, Any]:
        from planar_tui.kernels.dexterity_rr import rr_dexterity  # numba: after prepare_kernels

        verdict = np.empty(len(boxes), dtype=np.int64)
        kappa = np.empty((len(boxes), 2))
        rr_dexterity(boxes, g, r, elbow, limits, 0.0, verdict, kappa)
        return verdict, kappa

    return evaluate

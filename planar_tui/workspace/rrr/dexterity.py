"""The 3-RRR's κ evaluator (:meth:`~planar_tui.workspace.paving.mechanism.Mechanism.
dexterity`): :func:`kernels.dexterity_rr.rr_dexterity` with the job's geometry, working
mode (resolved by :func:`~planar_tui.workspace.rrr.singularity.resolve_circle`) and
:math:`L` (``characteristic_length_cm``, default the platform's circumradius)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from planar_tui.workspace.paving.dexterity import circumradius_cm
from planar_tui.workspace.rrr.singularity import Circle, kernel_inputs


def length_cm(robot: Any, spec: Any) -> float:
    """:math:`L`: the job's ``characteristic_length_cm`` or the platform's circumradius."""
    if spec.characteristic_length_cm is not None:
        return float(spec.characteristic_length_cm)
    return circumradius_cm(robot.platform_points_cm())


def evaluator(robot: Any, spec: Any, circle: Circle) -> Callable[[Any], tuple[Any, Any]]:
    """Boxes (k, 4) to ``(verdict, kappa)`` in the working mode ``circle.elbow``."""
    import numpy as np

    g, r, elbow, limits = kernel_inputs(robot, spec, circle)
    rows = np.tile(g, (3, 1))  # one geometry row per leg
    length = length_cm(robot, spec)

    def evaluate(boxes: Any) -> tuple[Any, Any]:
        from planar_tui.kernels.dexterity_rr import rr_dexterity  # numba: after prepare_kernels

        verdict = np.empty(len(boxes), dtype=np.int64)
        kappa = np.empty((len(boxes), 2))
        rr_dexterity(boxes, rows, r, elbow, limits, length, verdict, kappa)
        return verdict, kappa

    return evaluate

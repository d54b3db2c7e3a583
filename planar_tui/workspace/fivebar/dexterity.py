"""The five-bar's κ evaluator (:meth:`~planar_tui.workspace.paving.mechanism.Mechanism.
dexterity`): :func:`kernels.dexterity_rr.rr_dexterity` with its two legs in the robot's
``working_mode`` (:math:`J` maps :math:`(\\dot\\theta_1, \\dot\\theta_2)` to
:math:`(\\dot x, \\dot y)`: no characteristic length).

With a tolerance (:mod:`planar_tui.workspace.paving.tolerance_dexterity`) the kernel also
runs over every robot within it: the base joints' tolerance :math:`t_A` moves
:math:`v_i = P - A_i` as the position does (the box grown by :math:`t_A`), the link lengths
are intervals (:func:`spread_rows`); beside it the nominal robot and two vertices (every
link length at its upper or its lower tolerance)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from planar_tui.workspace.fivebar.singularity import kernel_inputs
from planar_tui.workspace.paving.tolerance import tolerance_of
from planar_tui.workspace.paving.tolerance_dexterity import kappa_of, tolerant_rows

#: The link lengths' columns in a geometry row and in a spread row (:func:`spread_rows`).
LENGTHS = ((0, 2), (1, 3))


def spread_rows(spec: Any) -> Any:
    """One :func:`kernels.singularity3rrr.leg_spread` row per leg, ``(t_A, 0, t_1,
    t_2)`` (zeros without a tolerance)."""
    import numpy as np

    tolerance = tolerance_of(spec)
    if tolerance is None:
        return np.zeros((2, 4))
    t = tolerance.of
    row = [t("base_joints_cm"), 0.0, t("proximal_cm"), t("distal_cm")]
    return np.tile(np.array(row, dtype=np.float64), (2, 1))


def evaluator(robot: Any, spec: Any) -> Callable[[Any], tuple[Any, Any]]:
    """Boxes (k, 4) to ``(verdict, kappa)`` in the robot's working mode (not ``any``; with
    a tolerance, in its mode: module docstring)."""
    import numpy as np

    g, r, _, limits, _ = kernel_inputs(robot)
    elbow = np.array(robot.elbows, dtype=float)

    def make(geometry: Any, spread: Any) -> Callable[[Any], tuple[Any, Any]]:
        def evaluate(boxes: Any) -> tuple[Any, Any]:
            from planar_tui.kernels.dexterity_rr import rr_dexterity  # numba: after prepare

            return kappa_of(rr_dexterity, boxes, geometry, r, elbow, limits, 0.0, spread)

        return evaluate

    return tolerant_rows(make, g, spread_rows(spec), LENGTHS, spec)

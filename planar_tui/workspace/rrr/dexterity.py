"""The 3-RRR's κ evaluator (:meth:`~planar_tui.workspace.paving.mechanism.Mechanism.
dexterity`): :func:`kernels.dexterity_rr.rr_dexterity` with the job's geometry, working
mode (resolved by :func:`~planar_tui.workspace.rrr.singularity.resolve_circle`) and
:math:`L` (``characteristic_length_cm``, default the platform's circumradius).

With a tolerance (:mod:`planar_tui.workspace.paving.tolerance_dexterity`) the kernel also
runs over every robot within it (:func:`spread_rows`: the base joints' and platform
points' tolerances widen :math:`v_i` and :math:`r_i = R(\\varphi) q_i`, the link lengths
become intervals), beside the nominal robot and two vertices (every link length at its
upper or its lower tolerance)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from planar_tui.workspace.paving.dexterity import circumradius_cm
from planar_tui.workspace.paving.tolerance import tolerance_of
from planar_tui.workspace.paving.tolerance_dexterity import (
    kappa_of,
    platform_spread_cm,
    tolerant_rows,
)
from planar_tui.workspace.rrr.singularity import Circle, kernel_inputs

#: The link lengths' columns in a geometry row and in a spread row (:func:`spread_rows`).
LENGTHS = ((0, 2), (1, 3))


def length_cm(robot: Any, spec: Any) -> float:
    """:math:`L`: the job's ``characteristic_length_cm`` or the platform's circumradius."""
    if spec.characteristic_length_cm is not None:
        return float(spec.characteristic_length_cm)
    return circumradius_cm(robot.platform_points_cm())


def spread_rows(spec: Any) -> Any:
    """One :func:`kernels.singularity3rrr.leg_spread` row per leg, ``(t_A + t_q(|\\cos
    \\varphi| + |\\sin\\varphi|), t_q(|\\cos\\varphi| + |\\sin\\varphi|), t_1, t_2)``: zeros
    without a tolerance."""
    import numpy as np

    tolerance = tolerance_of(spec)
    if tolerance is None:
        return np.zeros((3, 4))
    t = tolerance.of
    offset = platform_spread_cm(tolerance, spec.orientation_rad)
    row = [t("base_joints_cm") + offset, offset, t("proximal_cm"), t("distal_cm")]
    return np.tile(np.array(row, dtype=np.float64), (3, 1))


def evaluator(robot: Any, spec: Any, circle: Circle) -> Callable[[Any], tuple[Any, Any]]:
    """Boxes (k, 4) to ``(verdict, kappa)`` in the working mode ``circle.elbow`` (with a
    tolerance, in its mode: module docstring)."""
    import numpy as np

    g, r, elbow, limits = kernel_inputs(robot, spec, circle)
    rows = np.tile(g, (3, 1))  # one geometry row per leg
    length = length_cm(robot, spec)

    def make(geometry: Any, spread: Any) -> Callable[[Any], tuple[Any, Any]]:
        def evaluate(boxes: Any) -> tuple[Any, Any]:
            from planar_tui.kernels.dexterity_rr import rr_dexterity  # numba: after prepare

            return kappa_of(rr_dexterity, boxes, geometry, r, elbow, limits, length, spread)

        return evaluate

    return tolerant_rows(make, rows, spread_rows(spec), LENGTHS, spec)

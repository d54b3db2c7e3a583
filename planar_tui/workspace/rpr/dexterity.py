"""The 3-RPR's κ evaluator (:meth:`~planar_tui.workspace.paving.mechanism.Mechanism.
dexterity`): :func:`kernels.dexterity_prismatic.rpr_dexterity` with the job's annuli centres,
platform offsets, leg limits and :math:`L` (``characteristic_length_cm``, default the
platform's circumradius). Its legs have one branch: no working mode.

With a tolerance (:mod:`planar_tui.workspace.paving.tolerance_dexterity`) the kernel also
runs over every robot within it (:func:`spread_rows`: the base joints' and platform points'
tolerances move the annuli centres as the position does, and widen :math:`r_i`), beside
the nominal robot (the 3-RPR tolerances no link length)."""

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
from planar_tui.workspace.rpr.singularity import offsets_cm


def spread_rows(spec: Any) -> Any:
    """One :func:`kernels.dexterity_prismatic.rpr_leg` spread row per leg, ``(t_A +
    t_q(|\\cos\\varphi| + |\\sin\\varphi|), t_q(|\\cos\\varphi| + |\\sin\\varphi|))``: zeros
    without a tolerance."""
    import numpy as np

    tolerance = tolerance_of(spec)
    if tolerance is None:
        return np.zeros((3, 2))
    offset = platform_spread_cm(tolerance, spec.orientation_rad)
    row = [tolerance.of("base_joints_cm") + offset, offset]
    return np.tile(np.array(row, dtype=np.float64), (3, 1))


def evaluator(robot: Any, spec: Any) -> Callable[[Any], tuple[Any, Any]]:
    """Boxes (k, 4) to ``(verdict, kappa)`` (with a tolerance, in its mode: module
    docstring)."""
    import numpy as np

    centres = np.array(robot.centres_cm(spec.orientation_rad), dtype=float)
    offsets = offsets_cm(robot, spec.orientation_rad)
    limits = np.array(spec.leg_limits_cm, dtype=float)
    length = spec.characteristic_length_cm or circumradius_cm(robot.platform_points_cm)

    def make(geometry: Any, spread: Any) -> Callable[[Any], tuple[Any, Any]]:
        def evaluate(boxes: Any) -> tuple[Any, Any]:
            from planar_tui.kernels.dexterity_prismatic import rpr_dexterity  # numba

            return kappa_of(rpr_dexterity, boxes, geometry, offsets, limits, length, spread)

        return evaluate

    return tolerant_rows(make, centres, spread_rows(spec), (), spec)

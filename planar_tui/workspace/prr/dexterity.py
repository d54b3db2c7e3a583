"""The 3-PRR's κ evaluator (:meth:`~planar_tui.workspace.paving.mechanism.Mechanism.
dexterity`): :func:`kernels.dexterity_prismatic.prr_dexterity` with the job's slider lines,
strokes, links, its working mode (``slider_modes``, resolved as with ``singularities =
true``) and :math:`L` (``characteristic_length_cm``, default the platform's circumradius).

With a tolerance (:mod:`planar_tui.workspace.paving.tolerance_dexterity`) the kernel also
runs over every robot within it (:func:`spread_rows`: the slider points' and platform
points' tolerances move the leg as the position does and widen :math:`r_i`, the distal is
an interval), beside the nominal robot and the two with every distal at its upper or its
lower tolerance."""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from typing import Any

from planar_tui.workspace.paving.dexterity import circumradius_cm
from planar_tui.workspace.paving.tolerance import tolerance_of
from planar_tui.workspace.paving.tolerance_dexterity import (
    kappa_of,
    platform_spread_cm,
    tolerant_rows,
)
from planar_tui.workspace.prr.singularity import kernel_inputs, resolve_circle

#: The distal's column in a geometry row and in a spread row (:func:`spread_rows`).
LENGTHS = ((6, 2),)


def working_modes(job: Any, prepared: Any) -> tuple[int, int, int]:
    """The job's slider modes: the singularity circle's (``prepared``), else resolved the
    same way at the circle's centre (:func:`resolve_circle`; refusals exit with code 2)."""
    if prepared is not None:
        return prepared[1]
    forced = dataclasses.replace(job, spec=dataclasses.replace(job.spec, singularities=True))
    circle = resolve_circle(forced)
    assert circle is not None
    return circle[1]


def spread_rows(spec: Any) -> Any:
    """One :func:`kernels.dexterity_prismatic.prr_leg` spread row per leg, ``(t_B +
    t_q(|\\cos\\varphi| + |\\sin\\varphi|), t_q(|\\cos\\varphi| + |\\sin\\varphi|), t_l)``:
    zeros without a tolerance."""
    import numpy as np

    tolerance = tolerance_of(spec)
    if tolerance is None:
        return np.zeros((3, 3))
    t = tolerance.of
    offset = platform_spread_cm(tolerance, spec.orientation_rad)
    row = [t("slider_points_cm") + offset, offset, t("distal_cm")]
    return np.tile(np.array(row, dtype=np.float64), (3, 1))


def evaluator(job: Any, modes: tuple[int, int, int]) -> Callable[[Any], tuple[Any, Any]]:
    """Boxes (k, 4) to ``(verdict, kappa)`` in the slider ``modes`` (with a tolerance, in
    its mode: module docstring)."""
    import numpy as np

    robot, spec = job.robot, job.spec
    g, offsets = kernel_inputs(robot, spec)
    sigma = np.array(modes, dtype=float)
    length = spec.characteristic_length_cm or circumradius_cm(robot.platform_points_cm)

    def make(geometry: Any, spread: Any) -> Callable[[Any], tuple[Any, Any]]:
        def evaluate(boxes: Any) -> tuple[Any, Any]:
            from planar_tui.kernels.dexterity_prismatic import prr_dexterity  # numba

            return kappa_of(prr_dexterity, boxes, geometry, sigma, offsets, length, spread)

        return evaluate

    return tolerant_rows(make, g, spread_rows(spec), LENGTHS, spec)

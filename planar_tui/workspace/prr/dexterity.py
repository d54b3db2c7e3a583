"""The 3-PRR's κ evaluator (:meth:`~planar_tui.workspace.paving.mechanism.Mechanism.
dexterity`): :func:`kernels.dexterity_prismatic.prr_dexterity` with the job's slider lines,
strokes, links, its working mode (``slider_modes``, resolved as with ``singularities =
true``) and :math:`L` (``characteristic_length_cm``, default the platform's circumradius)."""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from typing import Any

from planar_tui.workspace.paving.dexterity import circumradius_cm
from planar_tui.workspace.prr.singularity import kernel_inputs, resolve_circle


def working_modes(job: Any, prepared: Any) -> tuple[int, int, int]:
    """The job's slider modes: the singularity circle's (``prepared``), else resolved the
    same way at the circle's centre (:func:`resolve_circle`; refusals exit with code 2)."""
    if prepared is not None:
        return prepared[1]
    forced = dataclasses.replace(job, spec=dataclasses.replace(job.spec, singularities=True))
    circle = resolve_circle(forced)
    assert circle is not None
    return circle[1]


def evaluator(job: Any, modes: tuple[int, int, int]) -> Callable[[Any], tuple[Any, Any]]:
    """Boxes (k, 4) to ``(verdict, kappa)`` in the slider ``modes``."""
    import numpy as np

    robot, spec = job.robot, job.spec
    g, offsets = kernel_inputs(robot, spec)
    sigma = np.array(modes, dtype=float)
    length = spec.characteristic_length_cm or circumradius_cm(robot.platform_points_cm)

    def evaluate(boxes: Any) -> tuple[Any, Any]:
        from planar_tui.kernels.dexterity_prismatic import (
            prr_dexterity,
        )  # numba: after prepare_kernels

        verdict = np.empty(len(boxes), dtype=np.int64)
        kappa = np.empty((len(boxes), 2))
        prr_dexterity(boxes, g, sigma, offsets, length, verdict, kappa)
        return verdict, kappa

    return evaluate

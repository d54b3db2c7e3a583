"""The 3-RPR's κ evaluator (:meth:`~planar_tui.workspace.paving.mechanism.Mechanism.
dexterity`): :func:`kernels.dexterity_prismatic.rpr_dexterity` with the job's annuli centres,
platform offsets, leg limits and :math:`L` (``characteristic_length_cm``, default the
platform's circumradius). Its legs have one branch: no working mode."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from planar_tui.workspace.paving.dexterity import circumradius_cm
from planar_tui.workspace.rpr.singularity import offsets_cm


def evaluator(robot: Any, spec: Any) -> Callable[[Any], tuple[Any, Any]]:
    """Boxes (k, 4) to ``(verdict, kappa)``."""
    import numpy as np

    centres = np.array(robot.centres_cm(spec.orientation_rad), dtype=float)
    offsets = offsets_cm(robot, spec.orientation_rad)
    limits = np.array(spec.leg_limits_cm, dtype=float)
    length = spec.characteristic_length_cm or circumradius_cm(robot.platform_points_cm)

    def evaluate(boxes: Any) -> tuple[Any, Any]:
        from planar_tui.kernels.dexterity_prismatic import (
            rpr_dexterity,
        )  # numba: after prepare_kernels

        verdict = np.empty(len(boxes), dtype=np.int64)
        kappa = np.empty((len(boxes), 2))
        rpr_dexterity(boxes, centres, offsets, limits, length, verdict, kappa)
        return verdict, kappa

    return evaluate

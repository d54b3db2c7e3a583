"""The 3-PRR's clearance evaluator (:meth:`~planar_tui.workspace.paving.mechanism.Mechanism.
interference`): :func:`kernels.interference_prismatic.prr_interference` with the job's
slider lines, strokes, links, ``leg_width_cm`` and working mode (``slider_modes``, resolved
as for ``kappa_max``): each leg's moving link from its slider to its platform joint, the
platform the triangle :math:`C_1 C_2 C_3` (the slider lines are fixed and not checked)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from planar_tui.workspace.prr.singularity import kernel_inputs


def evaluator(job: Any, modes: tuple[int, int, int]) -> Callable[[Any], tuple[Any, Any]]:
    """Boxes (k, 4) to ``(verdict, gap)`` in the slider ``modes``."""
    import numpy as np

    g, offsets = kernel_inputs(job.robot, job.spec)
    sigma = np.array(modes, dtype=float)
    width = float(job.spec.leg_width_cm)

    def evaluate(boxes: Any) -> tuple[Any, Any]:
        from planar_tui.kernels.interference_prismatic import prr_interference  # numba

        verdict = np.empty(len(boxes), dtype=np.int64)
        gap = np.empty((len(boxes), 2))
        boxes = np.ascontiguousarray(boxes)
        prr_interference(boxes, g, sigma, offsets, width, verdict, gap)
        return verdict, gap

    return evaluate

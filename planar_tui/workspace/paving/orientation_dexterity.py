r"""The dexterous region over a range of orientations, ``orientation_deg = [lo, hi]`` with
``kappa_max``, in the total-workspace sense: a point :math:`(x, y)` is dexterous when, for
*every* :math:`\varphi \in [lo, hi]`, the working mode closes every leg within its limits and
:math:`\kappa(x, y, \varphi) \le` ``kappa_max``. Its κ is therefore
:math:`g(x, y) = \max_{\varphi} \kappa(x, y, \varphi)`.

The evaluator (:func:`range_evaluator`) has the signature
:func:`~planar_tui.workspace.paving.dexterity.compute_dexterity` takes, so the paving, the
bracket, the disc, the κ map and the boxes CSV are the one-orientation ones. It is built on
the robot's certified pose-box test (its mechanism's ``path_box_test``: per box
:math:`X \times Y \times \Phi` a verdict and an enclosure of κ over the box's poses where
the legs close). Per workspace box :math:`B`, the range is cut into ``SLICES`` slices
:math:`\Phi_s`, each tested on :math:`B \times \Phi_s`:

- a slice *holds* when its verdict is ``IN`` with :math:`\kappa_{hi} \le` ``kappa_max``;
- a slice *fails* when its verdict is ``OUT`` (some leg closes at no pose: every point of
  :math:`B` misses some φ) or :math:`\kappa_{lo} >` ``kappa_max`` (every point where the
  legs close has :math:`\kappa > \kappa_{max}` at every φ of the slice);
- an undecided slice is halved while the rotation it spans, :math:`L \cdot |\Phi_s|`
  (:math:`L` the characteristic length), is wider than the box, and at most
  ``MAX_HALVINGS`` times (the κ enclosure of a pose box grows with its rotation: a slice
  much wider than its box leaves κ unbounded).

The box's verdict is ``OUT`` when some slice fails, ``IN`` when every final slice is
``IN``, else unsure; its κ enclosure is :math:`[\max_s \kappa_{lo,s}, \max_s
\kappa_{hi,s}]` over the tested slices (lower ends) and the final slices (upper ends): every
:math:`\kappa_{lo,s}` bounds :math:`g` from below on :math:`B` and the final slices cover
the range, so the enclosure holds :math:`g` over :math:`B`'s points whose legs close at
every φ. A box whose slices all hold is therefore proved dexterous, and one with a failing
slice proved outside.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from planar_tui.workspace.paving.dexterity import IN, OUT, UNSURE, Evaluator

#: The range is first cut into SLICES equal slices.
SLICES = 4
#: An undecided slice is halved at most MAX_HALVINGS times.
MAX_HALVINGS = 7


def range_evaluator(
    make_test: Callable[[], Any],
    phi_rad: tuple[float, float],
    kappa_max: float,
    length_cm: float,
) -> Evaluator:
    """Boxes (k, 4) to ``(verdict, kappa)`` over every orientation of ``phi_rad``
    (module docstring), by the test ``make_test()`` builds at the first call (pose boxes
    (k, 6) to ``(verdict, reason, kappa)``; its kernels import after ``prepare_kernels``);
    undecided slices are halved while :math:`L \\cdot |\\Phi_s|` (``length_cm``) is wider
    than their box."""
    import numpy as np

    lo, hi = phi_rad
    finest = (hi - lo) / SLICES / 2**MAX_HALVINGS
    tests: list[Any] = []

    def evaluate(boxes: Any) -> tuple[Any, Any]:
        if not tests:
            tests.append(make_test())
        test = tests[0]
        boxes = np.asarray(boxes, dtype=np.float64)
        k = len(boxes)
        widths = np.maximum(boxes[:, 1] - boxes[:, 0], boxes[:, 3] - boxes[:, 2])
        floor = np.maximum(widths / length_cm, finest)
        failed = np.zeros(k, dtype=bool)
        all_in = np.ones(k, dtype=bool)
        kappa = np.ones((k, 2))  # κ >= 1: the neutral lower ends
        edges = np.linspace(lo, hi, SLICES + 1)
        owner = np.repeat(np.arange(k), SLICES)
        s_lo, s_hi = np.tile(edges[:-1], k), np.tile(edges[1:], k)
        while len(owner):
            rows = np.column_stack([boxes[owner], s_lo, s_hi])
            verdict, _, enclosure = test(np.ascontiguousarray(rows))
            holds = (verdict == IN) & (enclosure[:, 1] <= kappa_max)
            fails = (verdict == OUT) | (enclosure[:, 0] > kappa_max)
            failed[owner[fails]] = True
            np.maximum.at(kappa[:, 0], owner[~fails], enclosure[~fails, 0])
            split = ~holds & ~fails & (s_hi - s_lo > floor[owner]) & ~failed[owner]
            final = ~fails & ~split
            np.maximum.at(kappa[:, 1], owner[final], enclosure[final, 1])
            all_in[owner[final & (verdict != IN)]] = False
            mid = 0.5 * (s_lo[split] + s_hi[split])
            owner = np.repeat(owner[split], 2)
            s_lo = np.column_stack([s_lo[split], mid]).ravel()
            s_hi = np.column_stack([mid, s_hi[split]]).ravel()
        result = np.where(failed, OUT, np.where(all_in, IN, UNSURE))
        kappa[failed, 1] = math.inf
        return result, kappa

    return evaluate


def range_dexterity(mechanism: Any, job: Any, length_cm: float) -> Evaluator:
    """The evaluator of a job with ``kappa_max`` and ``orientation_deg = [lo, hi]``: its
    ``mechanism``'s pose-box test (``path_box_test``, without ``leg_width_cm``, built at the
    first call: its kernels import after ``prepare_kernels``) over the range, slices halved
    while :math:`L \\cdot |\\Phi_s|` is wider than their box."""
    import dataclasses

    spec = job.spec
    plain = dataclasses.replace(spec, leg_width_cm=None)  # κ and the legs alone
    lo_deg, hi_deg = spec.orientation_deg
    phi = (math.radians(lo_deg), math.radians(hi_deg))
    return range_evaluator(
        lambda: mechanism.path_box_test(job.robot, plain),
        phi,
        spec.kappa_max,
        length_cm,
    )

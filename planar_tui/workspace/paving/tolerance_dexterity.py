r"""The dexterous region of a workspace job with tolerances (``kappa_max`` with
``tolerance_cm`` / ``tolerances_cm``), in the quantifiers of
:mod:`planar_tui.workspace.paving.tolerance`: for an (x, y) box :math:`B` and the box
:math:`\Pi` of robots within the tolerances, a point :math:`p` is dexterous for a robot
:math:`\pi` when :math:`\pi`'s working mode closes every leg at :math:`p` within its limits
with :math:`\kappa(p, \pi) \le` ``kappa_max``.

* ``all`` (robust): :math:`p` is dexterous iff it is for *every* :math:`\pi \in \Pi`; its
  κ is :math:`g(p) = \max_\pi \kappa(p, \pi)`.
* ``some``: :math:`p` is dexterous iff it is for *some* :math:`\pi`; its κ is
  :math:`h(p) = \min_\pi \kappa(p, \pi)` over the robots closing at :math:`p`.

The evaluator (:func:`tolerant_evaluator`) has the signature
:func:`~planar_tui.workspace.paving.dexterity.compute_dexterity` takes, so the paving, the
bracket, the disc, the κ map and the boxes CSV are the nominal ones. It combines

- the robot's evaluator over :math:`B \times \Pi` (``every``: the geometry as intervals;
  verdict ``IN`` when every robot closes every leg at every point, ``OUT`` when no robot
  closes some leg at any point, and an enclosure of every robot's κ at the points where it
  closes), and
- the evaluators of a few single robots of :math:`\Pi` (``robots``: the nominal one and
  vertices), each exact for its robot.

``all``: verdict ``IN`` when ``every`` says ``IN`` (with its :math:`\kappa_{hi}`, so the box
is proved dexterous when :math:`\kappa_{hi} \le` ``kappa_max``); ``OUT`` when ``every``
says ``OUT`` or one robot is proved outside on the whole box (``OUT`` or :math:`\kappa_{lo}
>` ``kappa_max``: every point then fails for that robot). κ: :math:`[\max(\kappa_{lo}^{every},
\kappa_{lo}^{\pi}), \kappa_{hi}^{every}]`, an enclosure of :math:`g`.

``some``: verdict ``IN`` when one robot is ``IN``, its :math:`\kappa_{hi}` the least of
those robots' (the box is proved dexterous when it is :math:`\le` ``kappa_max``: that robot
is dexterous at every point); ``OUT`` when ``every`` says ``OUT`` (its
:math:`\kappa_{lo} >` ``kappa_max`` proves the box outside too: no robot is dexterous at
any point). κ: :math:`[\kappa_{lo}^{every}, \cdot]`, an enclosure of :math:`h`.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

from planar_tui.workspace.paving.dexterity import IN, OUT, UNSURE, Evaluator, proved_outside
from planar_tui.workspace.paving.tolerance import Tolerance, tolerance_of

#: The vertex robots use ``(1 - 1e-6)`` of each tolerance (their float lengths stay inside).
VERTEX_SHRINK = 1.0 - 1e-6


def tolerant_evaluator(
    every: Evaluator, robots: Sequence[Evaluator], mode: str, kappa_max: float
) -> Evaluator:
    """Boxes (k, 4) to ``(verdict, kappa)`` of the tolerance ``mode`` (``"all"`` or
    ``"some"``, module docstring) from ``every`` (over :math:`B \\times \\Pi`) and
    ``robots`` (single robots of :math:`\\Pi`)."""
    import numpy as np

    def evaluate(boxes: Any) -> tuple[Any, Any]:
        verdict, kappa = every(boxes)
        kappa = np.array(kappa, dtype=np.float64)
        if mode == "all":
            refuted = verdict == OUT
            for robot in robots:
                v, k = robot(boxes)
                refuted |= proved_outside(v, k, kappa_max)
                np.maximum(kappa[:, 0], np.where(v == OUT, 1.0, k[:, 0]), out=kappa[:, 0])
            return np.where(refuted, OUT, verdict), kappa
        best = np.full(len(boxes), np.inf)
        exhibited = np.zeros(len(boxes), dtype=bool)
        for robot in robots:
            v, k = robot(boxes)
            exhibited |= v == IN
            best = np.where(v == IN, np.minimum(best, k[:, 1]), best)
        kappa[:, 1] = np.where(exhibited, best, kappa[:, 1])
        return np.where(verdict == OUT, OUT, np.where(exhibited, IN, UNSURE)), kappa

    return evaluate


def kappa_of(kernel: Callable[..., None], boxes: Any, *inputs: Any) -> tuple[Any, Any]:
    """``kernel(boxes, *inputs, verdict, kappa)`` on fresh outputs: the verdicts (k,) and
    the κ enclosures (k, 2) of the boxes (k, 4)."""
    import numpy as np

    verdict = np.empty(len(boxes), dtype=np.int64)
    kappa = np.empty((len(boxes), 2))
    kernel(boxes, *inputs, verdict, kappa)
    return verdict, kappa


def platform_spread_cm(tolerance: Tolerance, orientation_rad: float) -> float:
    """How far a platform point's tolerance moves it along x or y in the base frame:
    :math:`t_q(|\\cos\\varphi| + |\\sin\\varphi|)`."""
    turn = abs(math.cos(orientation_rad)) + abs(math.sin(orientation_rad))
    return tolerance.of("platform_points_cm") * turn


def tolerant_rows(
    make: Callable[[Any, Any], Evaluator],
    rows: Any,
    spread: Any,
    lengths: Sequence[tuple[int, int]],
    spec: Any,
) -> Evaluator:
    """The job's evaluator of a kernel taking one geometry row and one spread row per leg
    (``make(rows, spread)``, a zero spread: the robot of ``rows``). Without a tolerance
    (``spread`` zeros) ``make(rows, spread)``; with one, :func:`tolerant_evaluator` in its
    mode: ``every`` with ``spread``, the robots the nominal one and (with ``lengths``) the
    two vertices with every link length (``lengths``: its column in ``rows`` and its
    half-width's in ``spread``) at its upper or its lower tolerance (times
    ``VERTEX_SHRINK``)."""
    import numpy as np

    tolerance = tolerance_of(spec)
    if tolerance is None:
        return make(rows, spread)
    assert spec.kappa_max is not None
    zero = np.zeros_like(spread)
    robots = [make(rows, zero)]
    for sign in (1.0, -1.0) if lengths else ():
        vertex = np.array(rows, dtype=np.float64)
        for column, half_width in lengths:
            vertex[:, column] += sign * VERTEX_SHRINK * spread[:, half_width]
        robots.append(make(vertex, zero))
    return tolerant_evaluator(make(rows, spread), robots, tolerance.mode, spec.kappa_max)

r"""Certified regions over a range of orientations, ``orientation_deg = [lo, hi]``, in the
total-workspace sense: a point :math:`(x, y)` belongs when, for *every* :math:`\varphi \in
[lo, hi]`, the working mode closes every leg within its limits and the stage's quantity
holds: κ ≤ ``kappa_max`` (the dexterous region, :func:`range_dexterity`), a clearance gap
:math:`\ge 0` (``leg_width_cm``, :func:`~planar_tui.workspace.paving.interference.
range_interference`) or a certified pose error (``accuracy``,
:func:`~planar_tui.workspace.paving.accuracy.range_accuracy`). The dexterous region's κ is
therefore :math:`g(x, y) = \max_{\varphi} \kappa(x, y, \varphi)`.

The evaluators have the signature of their one-orientation stages, so the pavings, the
brackets, the maps and the boxes CSV are the one-orientation ones. They are built on a
robot's certified test of pose boxes :math:`X \times Y \times \Phi` (rows ``x_lo, x_hi,
y_lo, y_hi, phi_lo, phi_hi``: a verdict and enclosures ``lo, hi`` of the quantity over the
box's poses where the legs close; the κ test is its mechanism's ``path_box_test``). Per
workspace box :math:`B`, :func:`sliced` cuts the range into ``SLICES`` slices
:math:`\Phi_s`, each tested on :math:`B \times \Phi_s`:

- a slice *holds* when its verdict is ``IN`` and its upper end satisfies the bound;
- a slice *fails* when its verdict is ``OUT`` (some leg closes at no pose: every point of
  :math:`B` misses some φ) or its lower end violates the bound (every point where the legs
  close does so at every φ of the slice);
- an undecided slice is halved while the rotation it spans, :math:`L \cdot |\Phi_s|`
  (:math:`L` the characteristic length), is wider than the box, and at most
  ``MAX_HALVINGS`` times (a pose box's enclosures grow with its rotation: a slice much
  wider than its box leaves them unbounded).

The box's verdict is ``OUT`` when some slice fails, ``IN`` when every final slice is
``IN``, else unsure; its enclosure of the worst value over the range is :math:`[\max_s
lo_s, \max_s hi_s]` over the tested slices (lower ends) and the final slices (upper ends):
every :math:`lo_s` bounds the worst value from below on :math:`B` and the final slices
cover the range, so the enclosure holds it over :math:`B`'s points whose legs close at
every φ. A box whose slices all hold is therefore proved inside, and one with a failing
slice proved outside.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from planar_tui.workspace.paving.dexterity import IN, OUT, UNSURE, Evaluator

if TYPE_CHECKING:
    import numpy as np

#: The range is first cut into SLICES equal slices.
SLICES = 4
#: An undecided slice is halved at most MAX_HALVINGS times.
MAX_HALVINGS = 7

#: A pose-box test: rows (k, 6) to ``(verdict, lo, hi)``, enclosures (k, m).
PoseTest = Callable[["np.ndarray"], tuple["np.ndarray", "np.ndarray", "np.ndarray"]]
#: A slice's property from ``(verdict, lo, hi)``: a boolean per row.
Judge = Callable[["np.ndarray", "np.ndarray", "np.ndarray"], "np.ndarray"]
#: Boxes (k, 4) to ``(verdict, lower, upper)``, the worst value's enclosure (k, m).
SlicedEvaluator = Callable[["np.ndarray"], tuple["np.ndarray", "np.ndarray", "np.ndarray"]]


def sliced(
    make_test: Callable[[], PoseTest],
    phi_rad: tuple[float, float],
    length_cm: float,
    columns: int,
    holds: Judge,
    fails: Judge,
) -> SlicedEvaluator:
    """Boxes (k, 4) to ``(verdict, lower, upper)`` over every orientation of ``phi_rad``
    (module docstring), by the test ``make_test()`` builds at the first call (pose boxes
    (k, 6) to ``(verdict, lo, hi)`` with ``columns`` columns each; its kernels import after
    ``prepare_kernels``); a slice holds or fails as ``holds`` and ``fails`` say, undecided
    ones are halved while :math:`L \\cdot |\\Phi_s|` (``length_cm``) is wider than their
    box. ``lower`` is ``-inf`` where no slice was bounded, ``upper`` ``inf`` on a failed
    box."""
    import numpy as np

    lo, hi = phi_rad
    finest = (hi - lo) / SLICES / 2**MAX_HALVINGS
    tests: list[Any] = []

    def evaluate(boxes: Any) -> tuple[Any, Any, Any]:
        if not tests:
            tests.append(make_test())
        test = tests[0]
        boxes = np.asarray(boxes, dtype=np.float64).reshape(-1, 4)
        k = len(boxes)
        widths = np.maximum(boxes[:, 1] - boxes[:, 0], boxes[:, 3] - boxes[:, 2])
        floor = np.maximum(widths / length_cm, finest)
        failed = np.zeros(k, dtype=bool)
        all_in = np.ones(k, dtype=bool)
        lower = np.full((k, columns), -math.inf)
        upper = np.full((k, columns), -math.inf)
        edges = np.linspace(lo, hi, SLICES + 1)
        owner = np.repeat(np.arange(k), SLICES)
        s_lo, s_hi = np.tile(edges[:-1], k), np.tile(edges[1:], k)
        while len(owner):
            rows = np.column_stack([boxes[owner], s_lo, s_hi])
            verdict, low, high = test(np.ascontiguousarray(rows))
            held, fail = holds(verdict, low, high), fails(verdict, low, high)
            failed[owner[fail]] = True
            np.maximum.at(lower, owner[~fail], low[~fail])
            split = ~held & ~fail & (s_hi - s_lo > floor[owner]) & ~failed[owner]
            final = ~fail & ~split
            np.maximum.at(upper, owner[final], high[final])
            all_in[owner[final & (verdict != IN)]] = False
            mid = 0.5 * (s_lo[split] + s_hi[split])
            owner = np.repeat(owner[split], 2)
            s_lo = np.column_stack([s_lo[split], mid]).ravel()
            s_hi = np.column_stack([mid, s_hi[split]]).ravel()
        result = np.where(failed, OUT, np.where(all_in, IN, UNSURE))
        upper[failed] = math.inf
        return result, lower, upper

    return evaluate


def range_phi_rad(spec: Any) -> tuple[float, float]:
    """The spec's range ``orientation_deg = [lo, hi]`` in radians."""
    lo_deg, hi_deg = spec.orientation_deg
    return math.radians(lo_deg), math.radians(hi_deg)


def range_evaluator(
    make_test: Callable[[], Any],
    phi_rad: tuple[float, float],
    kappa_max: float,
    length_cm: float,
) -> Evaluator:
    """Boxes (k, 4) to ``(verdict, kappa)`` over every orientation of ``phi_rad``
    (:func:`sliced`) by the κ test ``make_test()`` builds (pose boxes (k, 6) to
    ``(verdict, reason, kappa)``): a slice holds when ``IN`` with :math:`\\kappa_{hi} \\le`
    ``kappa_max``, fails when ``OUT`` or :math:`\\kappa_{lo} >` ``kappa_max``."""
    import numpy as np

    def make_kappa_test() -> PoseTest:
        test = make_test()

        def kappa_test(rows: Any) -> tuple[Any, Any, Any]:
            verdict, _, kappa = test(rows)
            return verdict, kappa[:, :1], kappa[:, 1:]

        return kappa_test

    evaluate = sliced(
        make_kappa_test,
        phi_rad,
        length_cm,
        1,
        lambda verdict, lo, hi: (verdict == IN) & (hi[:, 0] <= kappa_max),
        lambda verdict, lo, hi: (verdict == OUT) | (lo[:, 0] > kappa_max),
    )

    def evaluate_kappa(boxes: Any) -> tuple[Any, Any]:
        verdict, lower, upper = evaluate(boxes)
        return verdict, np.column_stack([np.maximum(lower[:, 0], 1.0), upper[:, 0]])

    return evaluate_kappa


def range_dexterity(mechanism: Any, job: Any, length_cm: float) -> Evaluator:
    """The evaluator of a job with ``kappa_max`` and ``orientation_deg = [lo, hi]``: its
    ``mechanism``'s pose-box test (``path_box_test``, without ``leg_width_cm``, built at the
    first call: its kernels import after ``prepare_kernels``) over the range, slices halved
    while :math:`L \\cdot |\\Phi_s|` is wider than their box."""
    import dataclasses

    spec = job.spec
    plain = dataclasses.replace(spec, leg_width_cm=None)  # κ and the legs alone
    return range_evaluator(
        lambda: mechanism.path_box_test(job.robot, plain),
        range_phi_rad(spec),
        spec.kappa_max,
        length_cm,
    )

"""Exact leg test of a 3-RPR at a fixed orientation and its level-wise 2-D paving.

Leg ``i`` (base joint :math:`A_i`, platform point :math:`q_i` in the platform frame, actuated
prismatic length in :math:`[\\rho_i, \\overline\\rho_i]`) closes at the platform position
:math:`p = (x, y)` and orientation :math:`\\varphi` iff

.. math:: \\rho_i^2 \\le f_i(x, y) = (x - c_{x,i})^2 + (y - c_{y,i})^2 \\le \\overline\\rho_i^2,
          \\qquad c_i = A_i - R(\\varphi) q_i,

an annulus about :math:`c_i`. Over a box :math:`X \\times Y` the natural interval extension
:math:`(X - c_x)^2 + (Y - c_y)^2` (with :func:`~kernels.interval.isqr`, not ``X * X``) is
the *exact* range of :math:`f_i` up to outward rounding: the two squares depend on
different variables, and each square's enclosure is its exact range. So a box is

* ``OUTSIDE`` if some leg's range misses :math:`[\\rho_i^2, \\overline\\rho_i^2]`,
* ``INSIDE`` if every leg's range lies within it,
* ``BOUNDARY`` otherwise: then every leg has a point of the box where it closes and one
  where it does not (the range is an interval straddling a bound).

The squared limits are enclosed as intervals too (``down``/``up`` of the float product), so
the labels are certified. The centred (mean-value, slope) forms could only be wider than an
exact range, so the 3-RPR has the natural form alone.

The paving is the arc-distance form's (:func:`kernels.workspace_arc.settle_xy_box`): each
box of a frontier slice is decided in parallel, boxes go to ``LANES`` interleaved lanes, and
each outcome depends on its box alone, so the result does not depend on the thread count.

The parameter array ``p`` is (3, 8): per leg ``c_x, c_y, rho_lo, rho_hi`` (cm), then the
distance thresholds the labels use, ``out_lo, out_hi, in_lo, in_hi`` (cm, each ``>= 0``): a
box is ``OUTSIDE`` if some leg's distance range :math:`[d_{lo}, d_{hi}]` has
:math:`d_{hi} < out_{lo}` or :math:`d_{lo} > out_{hi}`, ``INSIDE`` if every leg's lies in
:math:`[in_{lo}, in_{hi}]`. For the nominal robot all four are ``rho_lo, rho_hi`` (the test
above); a tolerance-certified job moves them
(:func:`planar_tui.workspace.rpr.tolerance.leg_thresholds`); the comparisons are on the
squared distances, the squared thresholds rounded outward.
"""

import numba

from ._jit import kernel
from .interval import down, iadd, iadd_scalar, isqr, up
from .workspace_arc import BOUNDARY, INSIDE, LANES, OUTSIDE, settle_xy_box


@kernel
def squared_distance_range(xlo, xhi, ylo, yhi, cx, cy):
    """Enclosure of :math:`(x - c_x)^2 + (y - c_y)^2` over the box (its exact range,
    rounded outward)."""
    ulo, uhi = iadd_scalar(xlo, xhi, -cx)
    vlo, vhi = iadd_scalar(ylo, yhi, -cy)
    u2lo, u2hi = isqr(ulo, uhi)
    v2lo, v2hi = isqr(vlo, vhi)
    return iadd(u2lo, u2hi, v2lo, v2hi)


@kernel
def leg_label(slo, shi, out_lo, out_hi, in_lo, in_hi):
    """``OUTSIDE`` if the squared distance range ``[slo, shi]`` has ``shi < out_lo²`` or
    ``slo > out_hi²``, ``INSIDE`` if it lies in ``[in_lo², in_hi²]`` (thresholds ``>= 0``,
    their squares rounded outward), else ``BOUNDARY``."""
    if shi < down(out_lo * out_lo) or slo > up(out_hi * out_hi):
        return OUTSIDE
    if slo < up(in_lo * in_lo) or shi > down(in_hi * in_hi):
        return BOUNDARY
    return INSIDE


@kernel
def classify_rpr_box(xlo, xhi, ylo, yhi, p):
    """``OUTSIDE``, ``BOUNDARY`` or ``INSIDE`` for the (x, y) box (module docstring)."""
    inside = True
    for leg in range(3):
        slo, shi = squared_distance_range(xlo, xhi, ylo, yhi, p[leg, 0], p[leg, 1])
        label = leg_label(slo, shi, p[leg, 4], p[leg, 5], p[leg, 6], p[leg, 7])
        if label == OUTSIDE:
            return OUTSIDE
        inside = inside and label == INSIDE
    return INSIDE if inside else BOUNDARY


@kernel(parallel=True)
def rpr_level(p, precision, rows, start, stop, children, outcome):
    """Decide rows ``start .. stop - 1`` of a frontier of (x, y) boxes in parallel: label
    (:func:`classify_rpr_box`), then :func:`~kernels.workspace_arc.settle_xy_box`; row
    ``start + i`` writes ``children[2 i]``, ``children[2 i + 1]`` and ``outcome[i]``."""
    n = stop - start
    lanes = min(LANES, n)
    for lane in numba.prange(lanes):
        for i in range(lane, n, lanes):
            r = start + i
            label = classify_rpr_box(rows[r, 0], rows[r, 1], rows[r, 2], rows[r, 3], p)
            outcome[i] = settle_xy_box(label, rows, r, children, 2 * i, precision)

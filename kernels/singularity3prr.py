"""Parallel (type II) singularities of a 3-PRR in one working mode, by interval analysis.

Leg ``i``: the slider's line through :math:`B_i` with unit direction :math:`u_i` and normal
:math:`n_i = (-u_{y,i}, u_{x,i})`, the platform joint :math:`C_i = p + r_i`
(:math:`r_i = R(\\varphi) q_i`). With :math:`w = C_i - B_i`, :math:`a = w \\cdot u_i` and
:math:`h = w \\cdot n_i` (both linear in :math:`p`), the slider positions that close the leg
are :math:`s = a + \\sigma_i \\sqrt{l_i^2 - h^2}` (working mode :math:`\\sigma_i = \\pm 1`:
the slider behind or ahead of the foot of the perpendicular), and the distal link is

.. math:: d_i = C_i - B_i - s\\,u_i = h\\,n_i - \\sigma_i \\sqrt{l_i^2 - h^2}\\; u_i .

:math:`W_\\sigma` is the set of positions where every leg closes in its mode with
:math:`s \\in [\\underline s_i, \\overline s_i]`. The parallel Jacobian has rows
:math:`[d_i^T,\\ d_i \\times r_i]` (the 3-RRR's, with this distal link), singular iff its
determinant vanishes: the three distal lines concurrent or parallel.

**Box test** (:func:`prr_box_status`): :math:`a, h` are enclosed exactly (linear), then
:math:`l^2 - h^2`, the square root, :math:`s`, :math:`d_i` and the determinant with the
rigorous arithmetic of :mod:`kernels.interval`. A leg is *out* if :math:`l^2 - h^2 < 0` or
:math:`s` misses the stroke over the whole box, *in* if :math:`l^2 - h^2 \\ge 0` and
:math:`s` lies in the stroke; the determinant's enclosure holds :math:`\\det A(p)` for every
:math:`p \\in W_\\sigma` of the box (:math:`s` intersected with the stroke does not matter:
:math:`d_i` does not depend on the stroke).

**Paving** (:func:`prr_singular_level`, a level of
:func:`planar_tui.workspace.paving.levels.pave_in_levels`): a box with every leg *in* and a
determinant excluding 0 is *good* (no bad point: dropped, ``OUTSIDE``); a box with some leg
*out* is all *bad* (kept unsplit, labelled ``INSIDE`` here); any other box is halved down to
``precision`` and kept (``BOUNDARY``: may hold a singular pose, or the edge of
:math:`W_\\sigma`).

``g`` is (3, 7): per leg ``B'x, B'y, ux, uy, s_lo, s_hi, l`` with :math:`B' = B_i - r_i`
(so :math:`w = p - B'`); ``modes`` the three signs :math:`\\sigma_i`; ``offsets`` the (3, 2)
:math:`r_i`.
"""

import math

import numba

from ._jit import kernel
from .interval import iadd, iadd_scalar, imul, iscale, isqr, isqrt, isub
from .workspace_arc import BOUNDARY, INSIDE, LANES, OUTSIDE, settle_xy_box

LEG_OUT = 0
LEG_UNSURE = 1
LEG_IN = 2


@kernel
def leg_link(xlo, xhi, ylo, yhi, g, modes, leg):
    """``(verdict, dx_lo, dx_hi, dy_lo, dy_hi)``: the leg's verdict over the box and the
    enclosure of its distal link :math:`d_i` (module docstring)."""
    ux = g[leg, 2]
    uy = g[leg, 3]
    wx_lo, wx_hi = iadd_scalar(xlo, xhi, -g[leg, 0])
    wy_lo, wy_hi = iadd_scalar(ylo, yhi, -g[leg, 1])
    a_lo, a_hi = iadd(*iscale(wx_lo, wx_hi, ux), *iscale(wy_lo, wy_hi, uy))
    h_lo, h_hi = iadd(*iscale(wx_lo, wx_hi, -uy), *iscale(wy_lo, wy_hi, ux))
    length = g[leg, 6]
    q_lo, q_hi = isub(*isqr(length, length), *isqr(h_lo, h_hi))
    if q_hi < 0.0:
        return LEG_OUT, 0.0, 0.0, 0.0, 0.0
    root_lo, root_hi = isqrt(q_lo, q_hi)
    sigma = modes[leg]
    s_lo, s_hi = iadd(a_lo, a_hi, *iscale(root_lo, root_hi, sigma))
    if s_hi < g[leg, 4] or s_lo > g[leg, 5]:
        return LEG_OUT, 0.0, 0.0, 0.0, 0.0
    verdict = LEG_IN if (q_lo >= 0.0 and g[leg, 4] <= s_lo and s_hi <= g[leg, 5]) else LEG_UNSURE
    # d = h n - sigma sqrt(q) u, n = (-uy, ux)
    dx_lo, dx_hi = isub(*iscale(h_lo, h_hi, -uy), *iscale(root_lo, root_hi, sigma * ux))
    dy_lo, dy_hi = isub(*iscale(h_lo, h_hi, ux), *iscale(root_lo, root_hi, sigma * uy))
    return verdict, dx_lo, dx_hi, dy_lo, dy_hi


@kernel
def prr_box_status(xlo, xhi, ylo, yhi, g, modes, offsets):
    """``(in_w, out_w, det_lo, det_hi)`` of the box: every leg *in*, some leg *out*, and an
    enclosure of :math:`\\det A` over the box's points in :math:`W_\\sigma`."""
    v0, ax0, bx0, ay0, by0 = leg_link(xlo, xhi, ylo, yhi, g, modes, 0)
    v1, ax1, bx1, ay1, by1 = leg_link(xlo, xhi, ylo, yhi, g, modes, 1)
    v2, ax2, bx2, ay2, by2 = leg_link(xlo, xhi, ylo, yhi, g, modes, 2)
    if v0 == LEG_OUT or v1 == LEG_OUT or v2 == LEG_OUT:
        return False, True, -math.inf, math.inf
    in_w = v0 == LEG_IN and v1 == LEG_IN and v2 == LEG_IN
    am0, bm0 = isub(*iscale(ax0, bx0, offsets[0, 1]), *iscale(ay0, by0, offsets[0, 0]))
    am1, bm1 = isub(*iscale(ax1, bx1, offsets[1, 1]), *iscale(ay1, by1, offsets[1, 0]))
    am2, bm2 = isub(*iscale(ax2, bx2, offsets[2, 1]), *iscale(ay2, by2, offsets[2, 0]))
    # det = d1x (d2y m3 - m2 d3y) - d1y (d2x m3 - m2 d3x) + m1 (d2x d3y - d2y d3x)
    c1_lo, c1_hi = isub(*imul(ay1, by1, am2, bm2), *imul(am1, bm1, ay2, by2))
    c2_lo, c2_hi = isub(*imul(ax1, bx1, am2, bm2), *imul(am1, bm1, ax2, bx2))
    c3_lo, c3_hi = isub(*imul(ax1, bx1, ay2, by2), *imul(ay1, by1, ax2, bx2))
    t1_lo, t1_hi = imul(ax0, bx0, c1_lo, c1_hi)
    t2_lo, t2_hi = imul(ay0, by0, c2_lo, c2_hi)
    t3_lo, t3_hi = imul(am0, bm0, c3_lo, c3_hi)
    d_lo, d_hi = iadd(*isub(t1_lo, t1_hi, t2_lo, t2_hi), t3_lo, t3_hi)
    return in_w, False, d_lo, d_hi


@kernel
def boxes_status(boxes, g, modes, offsets, out):
    """:func:`prr_box_status` of each row ``x_lo, x_hi, y_lo, y_hi`` (a point: ``lo = hi``):
    ``out[k] = (in_w, out_w, det_lo, det_hi)`` (booleans as 1.0 / 0.0)."""
    for k in range(boxes.shape[0]):
        in_w, out_w, d_lo, d_hi = prr_box_status(
            boxes[k, 0], boxes[k, 1], boxes[k, 2], boxes[k, 3], g, modes, offsets
        )
        out[k, 0] = 1.0 if in_w else 0.0
        out[k, 1] = 1.0 if out_w else 0.0
        out[k, 2] = d_lo
        out[k, 3] = d_hi


@kernel(parallel=True)
def prr_singular_level(g, modes, offsets, precision, rows, start, stop, children, outcome):
    """Decide rows ``start .. stop - 1`` of a frontier in parallel (module docstring):
    good boxes dropped, all-bad boxes kept whole (``INSIDE``), the rest halved down to
    ``precision`` and kept (``BOUNDARY``)."""
    n = stop - start
    lanes = min(LANES, n)
    for lane in numba.prange(lanes):
        for i in range(lane, n, lanes):
            row = start + i
            in_w, out_w, d_lo, d_hi = prr_box_status(
                rows[row, 0], rows[row, 1], rows[row, 2], rows[row, 3], g, modes, offsets
            )
            label = BOUNDARY
            if out_w:
                label = INSIDE
            elif in_w and (d_lo > 0.0 or d_hi < 0.0):
                label = OUTSIDE
            outcome[i] = settle_xy_box(label, rows, row, children, 2 * i, precision)

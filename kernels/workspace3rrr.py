"""Interval enclosures of the 3-RRR leg constraints and the paper's bisection (paper B, Alg. 1).

Leg ``i`` of a 3-RRR with base joint :math:`A_i`, proximal length :math:`l_1`, distal length
:math:`l_2` and platform point :math:`C_i = (x, y) + o_i` (:math:`o_i` the platform offset at the
fixed orientation :math:`\\varphi`) closes iff

.. math:: f_i(x, y, \\theta_i) = (x + d_{x,i} - l_1\\cos\\theta_i)^2
          + (y + d_{y,i} - l_1\\sin\\theta_i)^2 - l_2^2 = 0,
          \\qquad d_i = o_i - A_i

(eqs. 17-21 in compact form; eq. 21 prints :math:`s_2` where :math:`s_1` is meant). Each
:math:`f_i` depends on :math:`(x, y, \\theta_i)` only. Over a box it is enclosed by

* the natural extension of the compact form (``NATURAL``) or of the paper's expanded
  eqs. (22)-(23) (``NATURAL_EXPANDED``; leg 1 stays compact);
* the mean-value form (eq. 14) :math:`f(m) + \\sum_j D_jF(X)(X_j - m_j)` with
  :math:`\\partial_x f = 2U`, :math:`\\partial_y f = 2V`,
  :math:`\\partial_\\theta f = 2 l_1((x+d_x)\\sin\\theta - (y+d_y)\\cos\\theta)`;
* the slope form :math:`f(m) + \\sum_j S_j (X_j - m_j)` with the exact slopes taken
  variable by variable,
  :math:`S_x = X + m_x + 2d_x - 2l_1\\cos\\Theta`,
  :math:`S_y = Y + m_y + 2d_y - 2l_1\\sin\\Theta`,
  :math:`S_\\theta = -2l_1(u_y\\cos M - u_x\\sin M)\\,\\mathrm{sinc}(H)`, where
  :math:`u = m_{xy} + d`, :math:`M = (\\Theta + m_\\theta)/2` and
  :math:`H = (\\Theta - m_\\theta)/2` (from
  :math:`\\cos\\theta - \\cos m = -2\\sin\\frac{\\theta+m}{2}\\sin\\frac{\\theta-m}{2}`).

The parameter vector ``p`` is ``[l1, l2, dx0, dy0, dx1, dy1, dx2, dy2, a, b, cos phi, sin phi]``
(cm); ``a, b, cos phi, sin phi`` are used by the expanded form only.
"""

import math

import numpy as np
from numba import prange

from ._jit import kernel
from .interval import (
    down,
    iadd,
    iadd_scalar,
    imul,
    iscale,
    isincos,
    isincos_ends,
    isqr,
    isub,
    psincos,
    up,
)

NATURAL = 0
MEAN_VALUE = 1
SLOPE = 2
NATURAL_EXPANDED = 3

# Stack and kept-box layouts: one row per box.
# stack row: x_lo, x_hi, y_lo, y_hi, t1_lo, t1_hi, t2_lo, t2_hi, t3_lo, t3_hi, split,
# then per leg i the libm values at its angle's ends, sin(lo), sin(hi), cos(lo), cos(hi)
# (columns ENDS + 4 i .. ENDS + 4 i + 3; split: index 0-4 of the variable whose
# bisection made the box, -1 for the root)
ENDS = 11
STACK_COLUMNS = ENDS + 12
# kept row:  x_lo, x_hi, y_lo, y_hi
DONE = 0
CHUNK_LIMIT = 1
KEPT_FULL = 2
STACK_FULL = 3


@kernel
def chunk_halt(processed, max_boxes, n_kept, kept_capacity, n_stack, stack_capacity):
    """Why a bisection chunk must return before popping the next box: ``CHUNK_LIMIT``
    (``max_boxes`` processed), ``KEPT_FULL``, ``STACK_FULL`` (a split pushes two boxes),
    or ``DONE`` when it may go on."""
    if processed >= max_boxes:
        return CHUNK_LIMIT
    if n_kept >= kept_capacity:
        return KEPT_FULL
    if n_stack + 1 >= stack_capacity:
        return STACK_FULL
    return DONE


@kernel
def keep_xy_box(kept, status, n_kept, xlo, xhi, ylo, yhi, label):
    """Write the (x, y) box ``[xlo, xhi] × [ylo, yhi]`` with ``label`` as row ``n_kept``
    of ``kept`` (columns ``x_lo, x_hi, y_lo, y_hi``) and ``status``; returns
    ``n_kept + 1``. The keep step of the 2-D pavings (arc-distance, orientation,
    singularity)."""
    kept[n_kept, 0] = xlo
    kept[n_kept, 1] = xhi
    kept[n_kept, 2] = ylo
    kept[n_kept, 3] = yhi
    status[n_kept] = label
    return n_kept + 1


@kernel
def split_xy_widest(boxes, row, child, columns):
    """Halve the (x, y) box of ``boxes[row]`` (columns ``x_lo, x_hi, y_lo, y_hi``) across its
    wider side (x on a tie): ``boxes[child]`` becomes a copy of the first ``columns``
    columns of the row, then the row keeps the lower half and the child the upper. The
    split step of the 2-D pavings (arc-distance, orientation, singularity, leg-wise)."""
    for j in range(columns):
        boxes[child, j] = boxes[row, j]
    xlo = boxes[row, 0]
    xhi = boxes[row, 1]
    ylo = boxes[row, 2]
    yhi = boxes[row, 3]
    if xhi - xlo >= yhi - ylo:
        mid = 0.5 * (xlo + xhi)
        boxes[row, 1] = mid
        boxes[child, 0] = mid
    else:
        mid = 0.5 * (ylo + yhi)
        boxes[row, 3] = mid
        boxes[child, 2] = mid


@kernel
def _l2_squared(l2):
    """:math:`l_2^2` as an interval (the float product may round)."""
    s = l2 * l2
    return down(s), up(s)


@kernel
def _compact(xlo, xhi, ylo, yhi, slo, shi, clo, chi, dx, dy, l1, l2):
    """The natural extension of the compact form (``NATURAL``),
    :math:`(X + d_x - l_1 C)^2 + (Y + d_y - l_1 S)^2 - l_2^2`, given the enclosures
    :math:`S \\supseteq \\sin\\Theta` and :math:`C \\supseteq \\cos\\Theta`."""
    alo, ahi = iadd_scalar(xlo, xhi, dx)
    blo, bhi = iscale(clo, chi, l1)
    ulo, uhi = isub(alo, ahi, blo, bhi)
    alo, ahi = iadd_scalar(ylo, yhi, dy)
    blo, bhi = iscale(slo, shi, l1)
    vlo, vhi = isub(alo, ahi, blo, bhi)
    u2lo, u2hi = isqr(ulo, uhi)
    v2lo, v2hi = isqr(vlo, vhi)
    slo, shi = iadd(u2lo, u2hi, v2lo, v2hi)
    klo, khi = _l2_squared(l2)
    return isub(slo, shi, klo, khi)


@kernel
def point_value(x, y, t, dx, dy, l1, l2):
    """Enclosure of :math:`f` at one point (the :math:`f(m)` of the centred forms)."""
    slo, shi, clo, chi = psincos(t)
    return _compact(x, x, y, y, slo, shi, clo, chi, dx, dy, l1, l2)


@kernel
def _times_centered(glo, ghi, xlo, xhi, m):
    """:math:`G\\,(X - m)` for ``m`` in X: :math:`X - m \\subseteq [-r, r]`, so the product is
    :math:`[-|G| r, |G| r]` with :math:`|G| = \\max(|\\underline g|, |\\overline g|)`."""
    r = max(up(xhi - m), up(m - xlo))
    v = up(max(abs(glo), abs(ghi)) * r)
    return -v, v


@kernel
def mean_value(xlo, xhi, ylo, yhi, tlo, thi, dx, dy, l1, l2):
    """Mean-value form (paper eq. 14) of one leg constraint."""
    slo, shi, clo, chi = isincos(tlo, thi)
    return mean_value_sc(xlo, xhi, ylo, yhi, tlo, thi, slo, shi, clo, chi, dx, dy, l1, l2)


@kernel
def mean_value_sc(xlo, xhi, ylo, yhi, tlo, thi, slo, shi, clo, chi, dx, dy, l1, l2):
    """:func:`mean_value` given :math:`\\sin\\Theta \\subseteq [s_{lo}, s_{hi}]` and
    :math:`\\cos\\Theta \\subseteq [c_{lo}, c_{hi}]` (:func:`isincos`)."""
    mx = 0.5 * (xlo + xhi)
    my = 0.5 * (ylo + yhi)
    mt = 0.5 * (tlo + thi)
    flo, fhi = point_value(mx, my, mt, dx, dy, l1, l2)
    pxlo, pxhi = iadd_scalar(xlo, xhi, dx)
    pylo, pyhi = iadd_scalar(ylo, yhi, dy)
    # D_x F = 2 U, D_y F = 2 V
    blo, bhi = iscale(clo, chi, l1)
    ulo, uhi = isub(pxlo, pxhi, blo, bhi)
    blo, bhi = iscale(slo, shi, l1)
    vlo, vhi = isub(pylo, pyhi, blo, bhi)
    glo, ghi = _times_centered(2.0 * ulo, 2.0 * uhi, xlo, xhi, mx)
    flo, fhi = iadd(flo, fhi, glo, ghi)
    glo, ghi = _times_centered(2.0 * vlo, 2.0 * vhi, ylo, yhi, my)
    flo, fhi = iadd(flo, fhi, glo, ghi)
    # D_theta F = 2 l1 ((x + dx) sin(theta) - (y + dy) cos(theta))
    alo, ahi = imul(pxlo, pxhi, slo, shi)
    blo, bhi = imul(pylo, pyhi, clo, chi)
    dlo, dhi = isub(alo, ahi, blo, bhi)
    dlo, dhi = iscale(dlo, dhi, 2.0 * l1)
    glo, ghi = _times_centered(dlo, dhi, tlo, thi, mt)
    return iadd(flo, fhi, glo, ghi)


@kernel
def sinc_lower(h):
    """A lower bound of :math:`\\sin(t)/t` over :math:`|t| \\le h` (``h >= 0``, in radians)."""
    if h == 0.0:
        return 1.0
    if h >= math.pi:
        return -0.2173  # global minimum of sinc is -0.21723...
    return down(down(down(math.sin(h))) / up(h))


@kernel
def slope(xlo, xhi, ylo, yhi, tlo, thi, dx, dy, l1, l2):
    """Slope form of one leg constraint about the box midpoint (see module docstring)."""
    slo, shi, clo, chi = isincos(tlo, thi)
    return slope_sc(xlo, xhi, ylo, yhi, tlo, thi, slo, shi, clo, chi, dx, dy, l1, l2)


@kernel
def slope_sc(xlo, xhi, ylo, yhi, tlo, thi, slo, shi, clo, chi, dx, dy, l1, l2):
    """:func:`slope` given the enclosures of :math:`\\sin\\Theta` and :math:`\\cos\\Theta`."""
    mx = 0.5 * (xlo + xhi)
    my = 0.5 * (ylo + yhi)
    mt = 0.5 * (tlo + thi)
    flo, fhi = point_value(mx, my, mt, dx, dy, l1, l2)
    # S_x = X + m_x + 2 dx - 2 l1 cos(Theta)
    alo, ahi = iadd_scalar(xlo, xhi, mx)
    alo, ahi = iadd_scalar(alo, ahi, 2.0 * dx)
    blo, bhi = iscale(clo, chi, 2.0 * l1)
    alo, ahi = isub(alo, ahi, blo, bhi)
    glo, ghi = _times_centered(alo, ahi, xlo, xhi, mx)
    flo, fhi = iadd(flo, fhi, glo, ghi)
    # S_y = Y + m_y + 2 dy - 2 l1 sin(Theta)
    alo, ahi = iadd_scalar(ylo, yhi, my)
    alo, ahi = iadd_scalar(alo, ahi, 2.0 * dy)
    blo, bhi = iscale(slo, shi, 2.0 * l1)
    alo, ahi = isub(alo, ahi, blo, bhi)
    glo, ghi = _times_centered(alo, ahi, ylo, yhi, my)
    flo, fhi = iadd(flo, fhi, glo, ghi)
    # S_theta = -2 l1 (u_y cos M - u_x sin M) sinc(H)
    uxlo, uxhi = iadd_scalar(mx, mx, dx)
    uylo, uyhi = iadd_scalar(my, my, dy)
    mlo, mhi = iadd_scalar(tlo, thi, mt)
    mlo, mhi = iscale(mlo, mhi, 0.5)
    smlo, smhi, cmlo, cmhi = isincos(mlo, mhi)
    alo, ahi = imul(uylo, uyhi, cmlo, cmhi)
    blo, bhi = imul(uxlo, uxhi, smlo, smhi)
    alo, ahi = isub(alo, ahi, blo, bhi)
    alo, ahi = iscale(alo, ahi, -2.0 * l1)
    half = up(0.5 * max(up(thi - mt), up(mt - tlo)))
    alo, ahi = imul(alo, ahi, sinc_lower(half), 1.0)
    glo, ghi = _times_centered(alo, ahi, tlo, thi, mt)
    return iadd(flo, fhi, glo, ghi)


@kernel
def _sum3(alo, ahi, blo, bhi, clo, chi):
    slo, shi = iadd(alo, ahi, blo, bhi)
    return iadd(slo, shi, clo, chi)


@kernel
def natural_expanded(leg, xlo, xhi, ylo, yhi, tlo, thi, p):
    """Natural extension of the paper's expanded eqs. (22) (leg 2) and (23) (leg 3).

    Leg 1 uses eq. (21) with the :math:`s_2 \\to s_1` typo fixed (it is already compact).
    The terms are evaluated in the order printed, with the paper's layout
    :math:`A_1 = (0,0), A_2 = (a,0), A_3 = (a/2, a\\sqrt3/2)`.
    """
    slo, shi, clo, chi = isincos(tlo, thi)
    return natural_expanded_sc(leg, xlo, xhi, ylo, yhi, slo, shi, clo, chi, p[0], p[1], p[2],
                               p[3], p[8], p[9], p[10], p[11])  # fmt: skip


@kernel
def natural_expanded_sc(leg, xlo, xhi, ylo, yhi, slo, shi, clo, chi, l1, l2, dx0, dy0, a, b,
                        cf, sf):  # fmt: skip
    """:func:`natural_expanded` given the enclosures of :math:`\\sin\\Theta` and
    :math:`\\cos\\Theta`, with ``p``'s entries as floats (no array crosses the call)."""
    if leg == 0:
        return _compact(xlo, xhi, ylo, yhi, slo, shi, clo, chi, dx0, dy0, l1, l2)
    x2lo, x2hi = isqr(xlo, xhi)
    y2lo, y2hi = isqr(ylo, yhi)
    lclo, lchi = iscale(clo, chi, l1)
    lslo, lshi = iscale(slo, shi, l1)
    if leg == 1:
        # x^2 + y^2 + l1^2 - l2^2 + a^2 + b^2 + 2 b y s_phi - 2 a x - 2 (a - x) b c_phi
        #   + 2 (a - x - b c_phi) l1 c2 - 2 (b s_phi + y) l1 s2
        k = l1 * l1 - l2 * l2 + a * a + b * b
        flo, fhi = iadd_scalar(x2lo, x2hi, k)
        flo, fhi = _sum3(flo, fhi, y2lo, y2hi, *iscale(ylo, yhi, 2.0 * b * sf))
        flo, fhi = iadd(flo, fhi, *iscale(xlo, xhi, -2.0 * a))
        amx = iscale(*iadd_scalar(xlo, xhi, -a), -1.0)
        flo, fhi = iadd(flo, fhi, *iscale(amx[0], amx[1], -2.0 * b * cf))
        t = iadd_scalar(amx[0], amx[1], -b * cf)
        flo, fhi = iadd(flo, fhi, *iscale(*imul(t[0], t[1], lclo, lchi), 2.0))
        t = iadd_scalar(ylo, yhi, b * sf)
        return iadd(flo, fhi, *iscale(*imul(t[0], t[1], lslo, lshi), -2.0))
    # eq. (23):
    # x^2 + y^2 + l1^2 - l2^2 + a^2 - a x + 1.25 b^2 - 2 y l1 s3 + (a - 2x) l1 c3
    #   - (l1 c3 + 2 l1 s3 + 0.5 a - x - 2 y) b c_phi
    #   + (2 l1 c3 - l1 s3 + a - 2 x + y) b s_phi
    #   - (b c_phi + 0.5 b s_phi - l1 s3 + y) sqrt(3) a
    k = l1 * l1 - l2 * l2 + a * a + 1.25 * b * b
    flo, fhi = iadd_scalar(x2lo, x2hi, k)
    flo, fhi = _sum3(flo, fhi, y2lo, y2hi, *iscale(xlo, xhi, -a))
    flo, fhi = iadd(flo, fhi, *iscale(*imul(ylo, yhi, lslo, lshi), -2.0))
    amx2 = iadd_scalar(*iscale(xlo, xhi, -2.0), a)
    flo, fhi = iadd(flo, fhi, *imul(amx2[0], amx2[1], lclo, lchi))
    t = iadd(lclo, lchi, *iscale(lslo, lshi, 2.0))
    t = iadd_scalar(t[0], t[1], 0.5 * a)
    t = isub(t[0], t[1], xlo, xhi)
    t = isub(t[0], t[1], *iscale(ylo, yhi, 2.0))
    flo, fhi = iadd(flo, fhi, *iscale(t[0], t[1], -b * cf))
    t = isub(*iscale(lclo, lchi, 2.0), lslo, lshi)
    t = iadd_scalar(t[0], t[1], a)
    t = isub(t[0], t[1], *iscale(xlo, xhi, 2.0))
    t = iadd(t[0], t[1], ylo, yhi)
    flo, fhi = iadd(flo, fhi, *iscale(t[0], t[1], b * sf))
    t = iadd_scalar(*iscale(lslo, lshi, -1.0), b * cf + 0.5 * b * sf)
    t = iadd(t[0], t[1], ylo, yhi)
    return iadd(flo, fhi, *iscale(t[0], t[1], -math.sqrt(3.0) * a))


@kernel
def leg_enclosure(form, leg, xlo, xhi, ylo, yhi, tlo, thi, p):
    """Enclosure of :math:`f_{leg}` over the box by the chosen ``form`` (module constants)."""
    slo, shi, clo, chi = isincos(tlo, thi)
    return leg_enclosure_sc(form, leg, xlo, xhi, ylo, yhi, tlo, thi, slo, shi, clo, chi, p)


@kernel(inline=True)
def leg_enclosure_sc(form, leg, xlo, xhi, ylo, yhi, tlo, thi, slo, shi, clo, chi, p):
    """:func:`leg_enclosure` given the enclosures of :math:`\\sin\\Theta` and
    :math:`\\cos\\Theta` (:func:`~kernels.interval.isincos`): the same result. Inlined
    into its callers, so that ``p`` crosses no call (a reference count taken and dropped
    per call: 5 % of the bisection's time)."""
    dx = p[2 + 2 * leg]
    dy = p[3 + 2 * leg]
    if form == MEAN_VALUE:
        return mean_value_sc(xlo, xhi, ylo, yhi, tlo, thi, slo, shi, clo, chi, dx, dy,
                             p[0], p[1])  # fmt: skip
    if form == SLOPE:
        return slope_sc(xlo, xhi, ylo, yhi, tlo, thi, slo, shi, clo, chi, dx, dy, p[0], p[1])
    if form == NATURAL_EXPANDED:
        return natural_expanded_sc(leg, xlo, xhi, ylo, yhi, slo, shi, clo, chi, p[0], p[1],
                                   p[2], p[3], p[8], p[9], p[10], p[11])  # fmt: skip
    return _compact(xlo, xhi, ylo, yhi, slo, shi, clo, chi, dx, dy, p[0], p[1])


#: Slots of a bisection's verdict memo per leg (a power of two): 4 096 slots (three legs,
#: 688 kB a thread) kept 83 % of Table 3's leg verdicts, 1 024 kept 75 % and 65 536 90 %
#: (92.7 % repeat), and ran fastest.
MEMO_SLOTS = 4096
#: A memo row: the leg's box ``x_lo, x_hi, y_lo, y_hi, t_lo, t_hi`` and its verdict (1.0
#: when the leg's enclosure excludes 0, else 0.0); a row of NaN matches no box.
MEMO_COLUMNS = 7


@kernel
def memo_slot(xlo, xhi, ylo, yhi, tlo, thi, slots):
    """The memo slot (``0 .. slots - 1``, ``slots`` a power of two) of a leg's
    ``(x, y, θ)`` box: the fractional part of a mix of its bounds times the golden ratio's
    inverse (Knuth's multiplicative hashing). Any slot is correct, since a row is used
    only when all six bounds match; the mix only spreads the boxes."""
    mix = (xlo * 0.7548776662466927 + xhi * 0.5698402909980532 + ylo * 0.3247179572447460
           + yhi * 0.8191725133961645 + tlo * 97.41935483870968 + thi * 61.80339887498949)  # fmt: skip
    f = mix * 0.6180339887498949
    return int((f - math.floor(f)) * slots) & (slots - 1)


@kernel(inline=True)
def leg_excludes_zero(form, leg, stack, row, p, memo):
    """:math:`0 \\notin F_{leg}` over the box ``stack[row]`` (its (x, y) box and the leg's
    angle, with the angle's end values), by ``form``; remembered in ``memo`` (shape
    ``(3, slots, MEMO_COLUMNS)``, ``slots`` a power of two, or 0 for no memo).

    A leg's verdict depends on its own ``(x, y, θ_leg)`` box alone, and Algorithm 1 meets
    the same such box again and again under other angles of the other legs (92.7 % of
    Table 3's expanded-form evaluations repeat one). A memo row is used only when all six
    bounds are equal to the box's, so the verdict is the one computed afresh, bit for
    bit; a slot holds the latest box that fell into it. Inlined into the bisection
    (passing the arrays to a call cost a third of its time).
    """
    xlo = stack[row, 0]
    xhi = stack[row, 1]
    ylo = stack[row, 2]
    yhi = stack[row, 3]
    tlo = stack[row, 4 + 2 * leg]
    thi = stack[row, 5 + 2 * leg]
    slots = memo.shape[1]
    slot = 0
    if slots > 0:
        slot = memo_slot(xlo, xhi, ylo, yhi, tlo, thi, slots)
        if (memo[leg, slot, 0] == xlo and memo[leg, slot, 1] == xhi
                and memo[leg, slot, 2] == ylo and memo[leg, slot, 3] == yhi
                and memo[leg, slot, 4] == tlo and memo[leg, slot, 5] == thi):  # fmt: skip
            return memo[leg, slot, 6] != 0.0
    e = ENDS + 4 * leg  # the ends' libm values: no sin or cos computed here
    slo, shi, clo, chi = isincos_ends(
        tlo, thi, stack[row, e], stack[row, e + 1], stack[row, e + 2], stack[row, e + 3]
    )
    flo, fhi = leg_enclosure_sc(form, leg, xlo, xhi, ylo, yhi, tlo, thi, slo, shi, clo, chi, p)
    excluded = flo > 0.0 or fhi < 0.0
    if slots > 0:
        memo[leg, slot, 0] = xlo
        memo[leg, slot, 1] = xhi
        memo[leg, slot, 2] = ylo
        memo[leg, slot, 3] = yhi
        memo[leg, slot, 4] = tlo
        memo[leg, slot, 5] = thi
        memo[leg, slot, 6] = 1.0 if excluded else 0.0
    return excluded


@kernel
def bisect_chunk(form, p, precision, angle_scale, stack, n_stack, kept, n_kept, max_boxes,
                 memo):  # fmt: skip
    """Run at most ``max_boxes`` steps of Algorithm 1 on an explicit stack (no recursion).

    Pop a box; if :math:`0 \\notin F_i` for some leg, discard it (only the leg whose angle
    was just bisected is re-evaluated: the others' enclosures are unchanged; a leg's
    verdict met before is taken from ``memo``, :func:`leg_excludes_zero`); else if its x
    and y widths are both :math:`\\le \\varepsilon`, append its (x, y) projection to
    ``kept``; else bisect the widest of :math:`x, y, k\\theta_1, k\\theta_2, k\\theta_3`
    and push both halves.

    Returns ``(n_stack, n_kept, processed, status)``; ``status`` is ``DONE`` (stack empty),
    ``CHUNK_LIMIT``, ``KEPT_FULL`` or ``STACK_FULL`` (grow the array and call again).
    """
    processed = 0
    refuter = 0  # the leg that last excluded a box: tried first (neighbours often agree)
    while n_stack > 0:
        halt = chunk_halt(processed, max_boxes, n_kept, kept.shape[0], n_stack, stack.shape[0])
        if halt != DONE:
            return n_stack, n_kept, processed, halt
        n_stack -= 1
        row = n_stack
        processed += 1
        # A theta_j bisection leaves F_i (i != j) as the parent's, which contained 0.
        split = int(stack[row, 10])
        first_leg, n_legs = (split - 2, 1) if split >= 2 else (refuter, 3)
        feasible = True
        for k in range(n_legs):
            leg = (first_leg + k) % 3
            if leg_excludes_zero(form, leg, stack, row, p, memo):
                feasible = False
                refuter = leg
                break
        if not feasible:
            continue
        wx = stack[row, 1] - stack[row, 0]
        wy = stack[row, 3] - stack[row, 2]
        if wx <= precision and wy <= precision:
            for j in range(4):
                kept[n_kept, j] = stack[row, j]
            n_kept += 1
            continue
        widest = 0
        wmax = wx
        if wy > wmax:
            widest = 1
            wmax = wy
        for leg in range(3):
            w = angle_scale * (stack[row, 5 + 2 * leg] - stack[row, 4 + 2 * leg])
            if w > wmax:
                widest = 2 + leg
                wmax = w
        lo = stack[row, 2 * widest]
        hi = stack[row, 2 * widest + 1]
        mid = 0.5 * (lo + hi)
        child = n_stack + 1
        for j in range(STACK_COLUMNS):
            stack[child, j] = stack[row, j]
        stack[row, 2 * widest + 1] = mid
        stack[child, 2 * widest] = mid
        stack[row, 10] = widest
        stack[child, 10] = widest
        if widest >= 2:  # the new end's sin and cos, once for both halves
            e = ENDS + 4 * (widest - 2)
            s = math.sin(mid)
            c = math.cos(mid)
            stack[row, e + 1] = s
            stack[row, e + 3] = c
            stack[child, e] = s
            stack[child, e + 2] = c
        n_stack += 2
    return n_stack, n_kept, processed, DONE


@kernel
def root_row(row, xlo, xhi, ylo, yhi, limits):
    """Fill ``row`` (a stack row) with the root box ``[xlo, xhi] × [ylo, yhi] × limits``
    (``limits[i] = (lo, hi)`` of leg i's angle, rad) and its angles' end values."""
    row[0] = xlo
    row[1] = xhi
    row[2] = ylo
    row[3] = yhi
    for leg in range(3):
        lo = limits[leg, 0]
        hi = limits[leg, 1]
        row[4 + 2 * leg] = lo
        row[5 + 2 * leg] = hi
        e = ENDS + 4 * leg
        row[e] = math.sin(lo)
        row[e + 1] = math.sin(hi)
        row[e + 2] = math.cos(lo)
        row[e + 3] = math.cos(hi)
    row[10] = -1.0


#: Boxes a block of :func:`bisect_blocks` bisects between two looks at the other blocks.
SHARE_QUOTA = 512


@kernel
def share_work(stacks, n_stack):
    """Give every block with an empty stack the bottom half of the fullest stack (rows
    ``0 .. k-1``, pushed first: the shallowest boxes, the largest pieces of work left), in
    place; a stack of one box is not split."""
    for block in range(stacks.shape[0]):
        if n_stack[block] != 0:
            continue
        donor = np.argmax(n_stack)
        count = n_stack[donor]
        if count < 2:
            return
        moved = count // 2
        for i in range(moved):
            for j in range(stacks.shape[2]):
                stacks[block, i, j] = stacks[donor, i, j]
        for i in range(count - moved):  # down the stack: row moved + i is read before written
            for j in range(stacks.shape[2]):
                stacks[donor, i, j] = stacks[donor, moved + i, j]
        n_stack[block] = moved
        n_stack[donor] = count - moved


@kernel(parallel=True)
def bisect_round(form, p, precision, angle_scale, stacks, n_stack, kept, n_kept, max_boxes,
                 processed, codes, memos):  # fmt: skip
    """One round of :func:`bisect_blocks`: :func:`bisect_chunk` on every block ``b`` at
    once (``prange``), each on its own stack ``stacks[b, :n_stack[b]]`` and kept rows
    ``kept[b, n_kept[b]:]``, until it has processed ``max_boxes`` boxes in all
    (``processed[b]`` counts them), in steps of :data:`SHARE_QUOTA`: a block whose stack
    runs empty raises a shared flag and the others return after their current step.
    Block ``b`` keeps its leg verdicts in ``memos[b]``; its halt code goes to
    ``codes[b]``."""
    hungry = np.zeros(1, dtype=np.int64)  # set by a block whose stack ran empty
    for b in prange(stacks.shape[0]):
        ns = n_stack[b]
        nk = n_kept[b]
        done = processed[b]
        code = DONE
        while done < max_boxes:
            ns, nk, step, code = bisect_chunk(
                form, p, precision, angle_scale, stacks[b], ns, kept[b], nk,
                min(SHARE_QUOTA, max_boxes - done), memos[b],
            )  # fmt: skip
            done += step
            if code != CHUNK_LIMIT or hungry[0] != 0:
                break
        if done >= max_boxes and code == DONE and ns > 0:
            code = CHUNK_LIMIT
        if ns == 0:
            hungry[0] = 1
        n_stack[b] = ns
        n_kept[b] = nk
        processed[b] = done
        codes[b] = code


@kernel
def bisect_blocks(form, p, precision, angle_scale, stacks, n_stack, kept, n_kept, max_boxes,
                  processed, codes, memos):  # fmt: skip
    """Algorithm 1 on every block at once for at most ``max_boxes`` boxes a block: rounds
    of :func:`bisect_round`, the work shared out (:func:`share_work`) before each, until
    every stack is empty, a block has processed ``max_boxes`` boxes, or a block's kept
    rows or stack are full (``KEPT_FULL``, ``STACK_FULL``: the caller grows them and
    calls again). Writes back ``n_stack[b]``, ``n_kept[b]`` (rows ``kept[b, :n_kept[b]]``,
    appended to what was there), ``processed[b]`` (this call's boxes) and the halt code
    ``codes[b]``. Every box is decided from itself alone, so the kept boxes of the whole
    paving are the same multiset however the boxes are shared among blocks. The rounds
    stay in compiled code: a block whose stack runs empty costs a share of the work, not
    a return to Python (2 threads ended 346 rounds in Table 3's expanded paving, 144 of
    them full)."""
    for b in range(stacks.shape[0]):
        processed[b] = 0
        codes[b] = DONE
    while True:
        share_work(stacks, n_stack)
        bisect_round(form, p, precision, angle_scale, stacks, n_stack, kept, n_kept,
                     max_boxes, processed, codes, memos)  # fmt: skip
        if n_stack.sum() == 0:
            return
        for b in range(stacks.shape[0]):
            if codes[b] == KEPT_FULL or codes[b] == STACK_FULL or processed[b] >= max_boxes:
                return


@kernel
def enclose_legs(form, boxes, p, out):
    """Enclosures of all three legs over every row of ``boxes`` (layout of the stack)."""
    for r in range(boxes.shape[0]):
        for leg in range(3):
            lo, hi = leg_enclosure(
                form,
                leg,
                boxes[r, 0],
                boxes[r, 1],
                boxes[r, 2],
                boxes[r, 3],
                boxes[r, 4 + 2 * leg],
                boxes[r, 5 + 2 * leg],
                p,
            )
            out[r, leg, 0] = lo
            out[r, leg, 1] = hi


def parameter_vector(l1_cm, l2_cm, offsets_cm, a_cm=0.0, b_cm=0.0, phi_rad=0.0):
    """Pack ``p`` for the kernels; ``offsets_cm[i] = o_i - A_i`` (shape (3, 2))."""
    p = np.zeros(12)
    p[0] = l1_cm
    p[1] = l2_cm
    p[2:8] = np.asarray(offsets_cm, dtype=np.float64).reshape(6)
    p[8] = a_cm
    p[9] = b_cm
    p[10] = math.cos(phi_rad)
    p[11] = math.sin(phi_rad)
    return p

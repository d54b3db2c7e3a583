"""Interval enclosures of the 3-RRR leg constraints (paper B); its Algorithm 1 is
:mod:`kernels.bisection3rrr`.

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

from ._jit import kernel
from .interval import (
    down,
    iadd,
    iadd_scalar,
    imul,
    iscale,
    isincos,
    isqr,
    isub,
    psincos,
    up,
)

NATURAL = 0
MEAN_VALUE = 1
SLOPE = 2
NATURAL_EXPANDED = 3

# Halt codes of the bisections' chunks (:func:`chunk_halt`); a kept row is
# x_lo, x_hi, y_lo, y_hi.
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


@kernel(inline=True)
def pop_row(processed, max_boxes, n_kept, kept, n_stack, stack):
    """The chunked bisections' pop: ``(halt, n_stack)`` with ``halt`` from
    :func:`chunk_halt`; when it is ``DONE`` the top row is popped (the ``n_stack``
    returned is one less, the popped row's index), else nothing changes."""
    halt = chunk_halt(processed, max_boxes, n_kept, kept.shape[0], n_stack, stack.shape[0])
    if halt != DONE:
        return halt, n_stack
    return DONE, n_stack - 1


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
def mean_value_sc(xlo, xhi, ylo, yhi, tlo, thi, slo, shi, clo, chi, dx, dy, l1, l2):
    """Mean-value form (paper eq. 14) of one leg constraint, given
    :math:`\\sin\\Theta \\subseteq [s_{lo}, s_{hi}]` and
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
def slope_sc(xlo, xhi, ylo, yhi, tlo, thi, slo, shi, clo, chi, dx, dy, l1, l2):
    """Slope form of one leg constraint about the box midpoint (see module docstring), given
    the enclosures of :math:`\\sin\\Theta` and :math:`\\cos\\Theta`."""
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
    return natural_expanded_sc(
        leg,
        xlo,
        xhi,
        ylo,
        yhi,
        slo,
        shi,
        clo,
        chi,
        p[0],
        p[1],
        p[2],
        p[3],
        p[8],
        p[9],
        p[10],
        p[11],
    )


@kernel
def natural_expanded_sc(
    leg, xlo, xhi, ylo, yhi, slo, shi, clo, chi, l1, l2, dx0, dy0, a, b, cf, sf
):
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
        return mean_value_sc(xlo, xhi, ylo, yhi, tlo, thi, slo, shi, clo, chi, dx, dy, p[0], p[1])
    if form == SLOPE:
        return slope_sc(xlo, xhi, ylo, yhi, tlo, thi, slo, shi, clo, chi, dx, dy, p[0], p[1])
    if form == NATURAL_EXPANDED:
        return natural_expanded_sc(
            leg,
            xlo,
            xhi,
            ylo,
            yhi,
            slo,
            shi,
            clo,
            chi,
            p[0],
            p[1],
            p[2],
            p[3],
            p[8],
            p[9],
            p[10],
            p[11],
        )
    return _compact(xlo, xhi, ylo, yhi, slo, shi, clo, chi, dx, dy, p[0], p[1])


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

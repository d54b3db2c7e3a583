"""Parallel (type II) singularities of a 3-RRR in one working mode, by interval analysis.

At a fixed orientation :math:`\\varphi`, leg ``i``'s platform point is :math:`C_i = p +
r_i`, :math:`r_i = R(\\varphi) q_i`, and relative to its base joint :math:`v_i = C_i - A_i
= \\rho_i(\\cos\\alpha_i, \\sin\\alpha_i)`. In the working mode ``s_i = ±1`` (the elbow sign)
the active angle is

.. math:: \\theta_i = \\alpha_i + s_i \\beta_i, \\qquad
          \\cos\\beta_i = \\frac{\\rho_i^2 + l_1^2 - l_2^2}{2 l_1 \\rho_i},
          \\quad \\beta_i \\in [0, \\pi],

the elbow is :math:`B_i = A_i + l_1(\\cos\\theta_i, \\sin\\theta_i)`, the distal link
:math:`u_i = C_i - B_i = v_i - l_1(\\cos\\theta_i, \\sin\\theta_i)`. The platform Jacobian
has rows :math:`[u_i^T,\\ u_i \\times r_i]` (:math:`a \\times b = a_x b_y - a_y b_x`;
:math:`r_i = C_i - P`) and the pose is type II singular iff :math:`\\det A = 0`: the three
distal lines are concurrent or parallel. :math:`W_s` is the set of positions where every leg
closes in its mode with :math:`\\theta_i` in its joint limits.

**Box test** (:func:`box_status`): every quantity above is enclosed over an (x, y) box with
the rigorous interval arithmetic of :mod:`kernels.interval`; :math:`\\alpha_i` by the
angles of the box's corners (a box not holding the origin subtends less than :math:`\\pi`
and its extreme directions are corners), :math:`\\arccos` by monotonicity. Per leg: the
box is *out* if the :math:`\\cos\\beta` enclosure misses :math:`[-1, 1]` or the
:math:`\\theta` enclosure misses the limits (mod :math:`2\\pi`): no point of the box is in
:math:`W_s`; *in* if it lies in :math:`[-1, 1]` and in the limits. The determinant is
enclosed with :math:`\\theta` intersected with the limits, so its enclosure holds
:math:`\\det A(p)` for every :math:`p \\in W_s` in the box. Platform offsets carry a
tolerance ``TOLERANCE_CM`` for their float round-off.

**Bisection** (:func:`singular_bisect_chunk`): a box is ``GOOD`` (all legs *in*, det
enclosure excluding 0: no singular point, every point in :math:`W_s`), ``OUT`` (some leg
*out*), else split down to ``precision``; a leaf is looked at on a grid of sub-boxes
(:func:`leaf_verdict`) and kept as ``SINGULAR`` (some sub-box's det enclosure holds 0: it
may hold a singular point) or ``EDGE`` (no singular point, but not proved in :math:`W_s`).
Every singular point of :math:`W_s` lies in a ``SINGULAR`` leaf. A box that may hold a base
joint (``ρ_i = 0``, where :math:`\\alpha_i` is undefined) is never proved anything.

**Singularity-free circle** about a centre :math:`c \\in W_s` with :math:`\\det A(c) \\ne 0`:
:math:`r^* = \\sup\\{r : \\bar D(c, r) \\subseteq W_s,\\ \\det A \\ne 0 \\text{ on it}\\}`,
the distance from :math:`c` to the *bad* set (outside :math:`W_s`, or singular). Every bad
point lies in an ``OUT`` box or a leaf's sub-box not proved ``GOOD`` (``GOOD`` boxes hold
none), so :math:`r_{in} = \\min` of their distances to :math:`c` is :math:`\\le r^*`. Upper
bound :math:`r_{out}`: an ``OUT`` box is all bad, so :math:`r^* \\le \\mathrm{dist}(c,
box)`; a sub-box centre :math:`q` proved outside :math:`W_s`, or in it with
:math:`\\operatorname{sign}\\det A(q) \\ne \\operatorname{sign}\\det A(c)`, gives
:math:`r^* \\le |q - c|` (on the segment :math:`[c, q]`, either some point leaves
:math:`W_s`, or det, continuous on :math:`W_s`, vanishes). The search box must contain
:math:`W_s` (its outside is bad: it bounds both too).

Geometry vector ``g`` as in :mod:`kernels.workspace_orientation`; ``r`` the (3, 2) float
offsets :math:`R(\\varphi) q_i`; ``elbow`` the three signs; ``limits`` (3, 2) radians.
"""

import math

import numpy as np

from ._jit import kernel
from .interval import down, iadd, iadd_scalar, imul, isincos, isqr, isqrt, isub, up, widen
from .workspace3rrr import DONE, keep_xy_box, pop_row, split_xy_widest

GOOD = 3
SINGULAR = 2
EDGE = 1
OUT = 0

TOLERANCE_CM = 1e-10
_TWO_PI = 2.0 * math.pi


@kernel
def idiv_positive(alo, ahi, blo, bhi):
    """:math:`X / Y` for :math:`Y \\subset (0, \\infty)` (``blo > 0``)."""
    q1 = alo / blo
    q2 = alo / bhi
    q3 = ahi / blo
    q4 = ahi / bhi
    return down(min(min(q1, q2), min(q3, q4))), up(max(max(q1, q2), max(q3, q4)))


@kernel
def iatan2_box(xlo, xhi, ylo, yhi):
    """Enclosure of :math:`\\operatorname{atan2}(y, x)` over a box not holding the origin
    (``ok = False`` when it may): the corners' angles, unwrapped about the centre's."""
    if xlo <= 0.0 <= xhi and ylo <= 0.0 <= yhi:
        return -math.pi, math.pi, False
    centre = math.atan2(0.5 * (ylo + yhi), 0.5 * (xlo + xhi))
    lo = math.inf
    hi = -math.inf
    for k in range(4):
        x = xlo if k < 2 else xhi
        y = ylo if k % 2 == 0 else yhi
        a = math.atan2(y, x) - centre
        if a > math.pi:
            a -= _TWO_PI
        elif a < -math.pi:
            a += _TWO_PI
        lo = min(lo, a)
        hi = max(hi, a)
    return down(down(down(centre + lo))), up(up(up(centre + hi))), True


@kernel
def iacos(alo, ahi):
    """:math:`\\arccos(X \\cap [-1, 1])` (decreasing: ``[acos(hi), acos(lo)]``), in
    :math:`[0, \\pi]`."""
    lo = max(0.0, down(down(math.acos(min(1.0, ahi)))))
    hi = min(math.pi, up(up(math.acos(max(-1.0, alo)))))
    return lo, hi


#: Per-leg verdicts of :func:`leg_status`.
LEG_OUT = 0
LEG_UNSURE = 1
LEG_IN = 2
LEG_UNDEFINED = 3
#: Absolute slack on angles reduced modulo 2 pi (the float 2 pi and its multiples round).
ANGLE_SLACK = 1e-12


@kernel
def leg_status(xlo, xhi, ylo, yhi, leg, g, r, elbow, limits):
    """``(verdict, ux_lo, ux_hi, uy_lo, uy_hi, m_lo, m_hi)`` of one leg over the box: the
    verdict (``LEG_OUT``, ``LEG_UNSURE``, ``LEG_IN``, ``LEG_UNDEFINED`` when the box may
    hold the base joint's direction singularity) and enclosures of :math:`u_i` and
    :math:`u_i \\times r_i` over the box's points in :math:`W_s` (module docstring)."""
    return leg_spread(xlo, xhi, ylo, yhi, leg, g, r, elbow, limits, 0.0, 0.0, 0.0)


@kernel
def leg_spread(xlo, xhi, ylo, yhi, leg, g, r, elbow, limits, offset_cm, t1_cm, t2_cm):
    """:func:`leg_status` over every robot within tolerances: :math:`r_i` widened by
    ``offset_cm`` per axis in :math:`u_i \\times r_i`, :math:`l_1 \\pm t_1` and
    :math:`l_2 \\pm t_2` intervals. The base joint's and the platform point's tolerances
    move :math:`v_i = p + r_i - A_i` as the position does, by at most :math:`t_A +
    t_q(|\\cos\\varphi| + |\\sin\\varphi|)` per axis: the caller grows the box by it
    (:func:`kernels.interval.grown_box`), so the leg over the grown box holds every such
    robot. ``LEG_IN``: every robot closes at every point; ``LEG_OUT``: none closes at any;
    the enclosures hold every robot's :math:`u_i` and :math:`u_i \\times r_i` at the box's
    points in its :math:`W_s`."""
    l1_lo, l1_hi = widen(g[0], t1_cm)
    l2_lo, l2_hi = widen(g[1], t2_cm)
    k_lo, k_hi = isub(*isqr(l1_lo, l1_hi), *isqr(l2_lo, l2_hi))
    rx = r[leg, 0]
    ry = r[leg, 1]
    vx_lo, vx_hi = iadd_scalar(xlo, xhi, rx - g[8 + 2 * leg])
    vy_lo, vy_hi = iadd_scalar(ylo, yhi, ry - g[9 + 2 * leg])
    vx_lo -= TOLERANCE_CM
    vx_hi += TOLERANCE_CM
    vy_lo -= TOLERANCE_CM
    vy_hi += TOLERANCE_CM
    a_lo, a_hi, ok = iatan2_box(vx_lo, vx_hi, vy_lo, vy_hi)
    if not ok:
        return LEG_UNDEFINED, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    sq_lo, sq_hi = iadd(*isqr(vx_lo, vx_hi), *isqr(vy_lo, vy_hi))
    rho_lo, rho_hi = isqrt(sq_lo, sq_hi)
    num_lo, num_hi = iadd(sq_lo, sq_hi, k_lo, k_hi)
    den_lo, den_hi = imul(rho_lo, rho_hi, 2.0 * l1_lo, 2.0 * l1_hi)
    c_lo, c_hi = idiv_positive(num_lo, num_hi, den_lo, den_hi)
    if c_lo > 1.0 or c_hi < -1.0:
        return LEG_OUT, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    verdict = LEG_IN if (c_lo >= -1.0 and c_hi <= 1.0) else LEG_UNSURE
    b_lo, b_hi = iacos(c_lo, c_hi)
    if elbow[leg] > 0.0:
        t_lo = down(a_lo + b_lo)
        t_hi = up(a_hi + b_hi)
    else:
        t_lo = down(a_lo - b_hi)
        t_hi = up(a_hi - b_lo)
    lim_lo = limits[leg, 0]
    lim_hi = limits[leg, 1]
    turns = math.floor((t_lo - lim_lo) / _TWO_PI)
    t_lo = down(t_lo - turns * _TWO_PI) - ANGLE_SLACK
    t_hi = up(t_hi - turns * _TWO_PI) + ANGLE_SLACK
    if t_lo > lim_hi and t_hi < lim_lo + _TWO_PI:
        return LEG_OUT, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    if not (t_lo >= lim_lo and t_hi <= lim_hi):
        verdict = LEG_UNSURE
    if t_lo >= lim_lo and t_hi < lim_lo + _TWO_PI:
        t_hi = min(t_hi, lim_hi)
    s_lo, s_hi, co_lo, co_hi = isincos(t_lo, t_hi)
    ux_lo, ux_hi = isub(vx_lo, vx_hi, *imul(co_lo, co_hi, l1_lo, l1_hi))
    uy_lo, uy_hi = isub(vy_lo, vy_hi, *imul(s_lo, s_hi, l1_lo, l1_hi))
    offset = TOLERANCE_CM + offset_cm
    p_lo, p_hi = imul(ux_lo, ux_hi, ry - offset, ry + offset)
    q_lo, q_hi = imul(uy_lo, uy_hi, rx - offset, rx + offset)
    m_lo, m_hi = isub(p_lo, p_hi, q_lo, q_hi)
    return verdict, ux_lo, ux_hi, uy_lo, uy_hi, m_lo, m_hi


@kernel
def box_status(xlo, xhi, ylo, yhi, g, r, elbow, limits):
    """``(in_w, out_w, det_lo, det_hi)`` of the box (module docstring): every leg *in*,
    some leg *out*, and an enclosure of :math:`\\det A` over the box's points in
    :math:`W_s` (unbounded when some leg is undefined)."""
    # np.int64: a literal leg (Literal[int](0)) made numba compile leg_status once per leg
    v0, ax0, bx0, ay0, by0, am0, bm0 = leg_status(
        xlo, xhi, ylo, yhi, np.int64(0), g, r, elbow, limits
    )
    v1, ax1, bx1, ay1, by1, am1, bm1 = leg_status(
        xlo, xhi, ylo, yhi, np.int64(1), g, r, elbow, limits
    )
    v2, ax2, bx2, ay2, by2, am2, bm2 = leg_status(
        xlo, xhi, ylo, yhi, np.int64(2), g, r, elbow, limits
    )
    if v0 == LEG_OUT or v1 == LEG_OUT or v2 == LEG_OUT:
        return False, True, -math.inf, math.inf
    in_w = v0 == LEG_IN and v1 == LEG_IN and v2 == LEG_IN
    if v0 == LEG_UNDEFINED or v1 == LEG_UNDEFINED or v2 == LEG_UNDEFINED:
        return False, False, -math.inf, math.inf
    # det = u1x (u2y m3 - m2 u3y) - u1y (u2x m3 - m2 u3x) + m1 (u2x u3y - u2y u3x)
    c1_lo, c1_hi = isub(*imul(ay1, by1, am2, bm2), *imul(am1, bm1, ay2, by2))
    c2_lo, c2_hi = isub(*imul(ax1, bx1, am2, bm2), *imul(am1, bm1, ax2, bx2))
    c3_lo, c3_hi = isub(*imul(ax1, bx1, ay2, by2), *imul(ay1, by1, ax2, bx2))
    t1_lo, t1_hi = imul(ax0, bx0, c1_lo, c1_hi)
    t2_lo, t2_hi = imul(ay0, by0, c2_lo, c2_hi)
    t3_lo, t3_hi = imul(am0, bm0, c3_lo, c3_hi)
    d_lo, d_hi = iadd(*isub(t1_lo, t1_hi, t2_lo, t2_hi), t3_lo, t3_hi)
    return in_w, False, d_lo, d_hi


@kernel
def box_distance(xlo, xhi, ylo, yhi, cx, cy):
    """Distance from ``(cx, cy)`` to the box (0 inside), rounded down."""
    dx = max(xlo - cx, 0.0, cx - xhi)
    dy = max(ylo - cy, 0.0, cy - yhi)
    return max(0.0, down(math.hypot(dx, dy)))


@kernel
def leaf_verdict(xlo, xhi, ylo, yhi, g, r, elbow, limits, cx, cy, sign, n):
    """A leaf looked at on an ``n`` x ``n`` grid of sub-boxes: ``(singular, bad, witness)``.

    ``singular``: some sub-box neither *out* nor with a det enclosure excluding 0 (the leaf
    may hold a singular pose; else it holds none). ``bad``: the least distance from
    ``(cx, cy)`` to a sub-box not proved ``GOOD`` (a lower bound of the distance to the bad
    points in the leaf). ``witness``: the least distance to a sub-box proved *out*, or to a
    sub-box centre proved outside :math:`W_s` or with det of the sign opposite to ``sign``
    (an upper bound of :math:`r^*`; ``inf`` without one).
    """
    singular = False
    bad = math.inf
    witness = math.inf
    hx = (xhi - xlo) / n
    hy = (yhi - ylo) / n
    for i in range(n):
        x0 = xlo + i * hx
        x1 = xhi if i == n - 1 else xlo + (i + 1) * hx
        for j in range(n):
            y0 = ylo + j * hy
            y1 = yhi if j == n - 1 else ylo + (j + 1) * hy
            in_w, out_w, d_lo, d_hi = box_status(x0, x1, y0, y1, g, r, elbow, limits)
            distance = box_distance(x0, x1, y0, y1, cx, cy)
            if out_w:
                bad = min(bad, distance)
                witness = min(witness, distance)
                continue
            nonsingular = d_lo > 0.0 or d_hi < 0.0
            if in_w and nonsingular:
                continue
            bad = min(bad, distance)
            if not nonsingular:
                singular = True
            qx = 0.5 * (x0 + x1)
            qy = 0.5 * (y0 + y1)
            q_in, q_out, q_lo, q_hi = box_status(qx, qx, qy, qy, g, r, elbow, limits)
            flips = (sign > 0.0 and q_hi < 0.0) or (sign < 0.0 and q_lo > 0.0)
            if q_out or (q_in and flips):
                witness = min(witness, up(math.hypot(qx - cx, qy - cy)))
    return singular, bad, witness


@kernel
def singular_bisect_chunk(
    g,
    r,
    elbow,
    limits,
    precision,
    leaf_grid,
    cx,
    cy,
    sign,
    stack,
    n_stack,
    kept,
    status,
    n_kept,
    max_work,
    bounds,
):
    """Steps of the bisection of the module docstring until ``max_work`` box tests were
    made (a box costs 1, a leaf's sub-grid ``2 leaf_grid²`` more).

    ``bounds`` ``[r_in, r_out]`` is updated in place (start it at the distances from
    ``(cx, cy)`` to the search box's edges); ``sign`` is that of :math:`\\det A(c)`
    (0: no circle). Returns ``(n_stack, n_kept, processed, code)`` like
    :func:`kernels.bisection3rrr.bisect_chunk` (``code`` from
    :func:`~kernels.workspace3rrr.chunk_halt`, by :func:`~kernels.workspace3rrr.pop_row`); kept
    leaves carry ``SINGULAR`` or ``EDGE``.
    """
    processed = 0
    work = 0
    while n_stack > 0:
        halt, row = pop_row(work, max_work, n_kept, kept, n_stack, stack)
        if halt != DONE:
            return n_stack, n_kept, processed, halt
        n_stack = row
        processed += 1
        work += 1
        xlo = stack[row, 0]
        xhi = stack[row, 1]
        ylo = stack[row, 2]
        yhi = stack[row, 3]
        in_w, out_w, d_lo, d_hi = box_status(xlo, xhi, ylo, yhi, g, r, elbow, limits)
        if out_w:
            distance = box_distance(xlo, xhi, ylo, yhi, cx, cy)
            bounds[0] = min(bounds[0], distance)
            bounds[1] = min(bounds[1], distance)
            continue
        nonsingular = d_lo > 0.0 or d_hi < 0.0
        if in_w and nonsingular:
            continue
        wx = xhi - xlo
        wy = yhi - ylo
        if wx <= precision and wy <= precision:
            singular, bad, witness = leaf_verdict(
                xlo, xhi, ylo, yhi, g, r, elbow, limits, cx, cy, sign, leaf_grid
            )
            work += 2 * leaf_grid * leaf_grid
            label = SINGULAR if singular else EDGE
            n_kept = keep_xy_box(kept, status, n_kept, xlo, xhi, ylo, yhi, label)
            bounds[0] = min(bounds[0], bad)
            bounds[1] = min(bounds[1], witness)
            continue
        split_xy_widest(stack, row, n_stack + 1, np.int64(4))
        n_stack += 2
    return n_stack, n_kept, processed, DONE

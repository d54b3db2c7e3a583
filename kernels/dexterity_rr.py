"""κ enclosures over (x, y) boxes of the robots with RR legs: the 3-RRR and the five-bar.

Leg ``i`` (the model of :mod:`kernels.singularity3rrr`): :math:`v_i = C_i - A_i`, the elbow
:math:`B_i = A_i + l_1 e_i`, the distal link :math:`u_i = C_i - B_i`. Differentiating
:math:`|u_i|^2 = l_2^2` with :math:`\\dot C_i = \\dot p + \\dot\\varphi\\, E r_i` and
:math:`\\dot B_i = \\dot\\theta_i\\, E (B_i - A_i)` (:math:`E` the quarter turn) gives

.. math:: u_{ix} \\dot x + u_{iy} \\dot y - (u_i \\times r_i)\\,\\dot\\varphi
          = \\big((B_i - A_i) \\times u_i\\big)\\,\\dot\\theta_i
          = (v_i \\times u_i)\\,\\dot\\theta_i,

so with the twist :math:`(\\dot x, \\dot y, L\\dot\\varphi)` the row of :math:`M = J^{-1}` is
:math:`(u_{ix}, u_{iy}, -(u_i \\times r_i)/L) / (v_i \\times u_i)`; the sign of a column
leaves the singular values unchanged. The five-bar's platform is a point: rows
:math:`(u_{ix}, u_{iy}) / (v_i \\times u_i)`, a 2 x 2 :math:`M`.
:func:`kernels.singularity3rrr.leg_status` encloses :math:`u_i` and :math:`u_i \\times r_i`
over the box's points in the mode's workspace; :math:`v_i` is the box shifted.
"""

import math

import numba
import numpy as np

from ._jit import kernel
from .dexterity import (
    IN,
    OUT,
    UNSURE,
    combine,
    idiv,
    kappa_bounds,
    mean_value,
    set_norm,
    set_row,
    slope_term,
)
from .interval import grown_box, iadd, iadd_scalar, imul, iscale, isqr, isub, up, widen
from .singularity3rrr import (
    LEG_IN,
    LEG_OUT,
    LEG_UNDEFINED,
    TOLERANCE_CM,
    idiv_positive,
    leg_spread,
)

#: Joint limits that cut nothing (two turns either way): the enclosures over a whole box.
FREE = np.array([[-4.0 * math.pi, 4.0 * math.pi]] * 3)


@kernel
def rr_point(x, y, leg, g, r, elbow, limits, length_cm, offset_cm):
    """``(ok, ux, uy, t, b)`` enclosures (lo, hi pairs) at the point ``(x, y)``: :math:`u_i`,
    :math:`(u_i \\times r_i)/L` and :math:`b_i = v_i \\times u_i`, :math:`r_i` widened by
    ``offset_cm`` (:func:`kernels.singularity3rrr.leg_spread`; ``ok`` false unless the leg is
    proved to close within its limits there)."""
    verdict, ux_lo, ux_hi, uy_lo, uy_hi, mm_lo, mm_hi = leg_spread(
        x, x, y, y, leg, g, r, elbow, limits, offset_cm, 0.0, 0.0
    )
    vx_lo = x + r[leg, 0] - g[8 + 2 * leg] - 2.0 * TOLERANCE_CM
    vy_lo = y + r[leg, 1] - g[9 + 2 * leg] - 2.0 * TOLERANCE_CM
    vx_hi = vx_lo + 4.0 * TOLERANCE_CM
    vy_hi = vy_lo + 4.0 * TOLERANCE_CM
    b_lo, b_hi = isub(*imul(vx_lo, vx_hi, uy_lo, uy_hi), *imul(vy_lo, vy_hi, ux_lo, ux_hi))
    t_lo, t_hi = iscale(mm_lo, mm_hi, 1.0 / length_cm) if length_cm > 0.0 else (0.0, 0.0)
    return verdict == LEG_IN, ux_lo, ux_hi, uy_lo, uy_hi, t_lo, t_hi, b_lo, b_hi


@kernel
def rr_leg(xlo, xhi, ylo, yhi, leg, g, r, elbow, limits, m_lo, m_hi, norms, row, length_cm, spread):
    """Leg ``leg``'s verdict (``OUT``, ``UNSURE``, ``IN``) over the box, writing its row
    ``row`` of :math:`M` (module docstring; the third entry only when ``length_cm > 0``),
    over every robot within ``spread`` (:func:`kernels.singularity3rrr.leg_spread`: the
    box grown by ``spread[0]``, the lengths' and offset's intervals in every enclosure
    below).
    Returns ``(verdict, defined)``: ``defined`` is false when the box may hold the base
    joint's direction singularity.

    A box the limits may cut is enclosed without them (``FREE``: every point of the box, a
    superset of its points in the mode's workspace). The natural enclosure of each entry is
    met with its mean-value form where the leg is proved to reach every point of the box
    (its inverse kinematics, limits aside, is smooth there): with
    :math:`\\theta_x = M_{i0}`, :math:`\\theta_y = M_{i1}` and :math:`e^\\perp = (-e_y,
    e_x)`, :math:`e = (v - u) / l_1`, the derivatives are :math:`\\partial_x u = (1, 0) -
    l_1 \\theta_x e^\\perp`, :math:`\\partial_y u = (0, 1) - l_1 \\theta_y e^\\perp`,
    :math:`\\partial (u \\times r) = \\partial u \\times r` and :math:`\\partial b =
    \\partial v \\times u + v \\times \\partial u`."""
    xlo, xhi, ylo, yhi = grown_box(xlo, xhi, ylo, yhi, spread[0])
    verdict, ux_lo, ux_hi, uy_lo, uy_hi, mm_lo, mm_hi = leg_spread(
        xlo, xhi, ylo, yhi, leg, g, r, elbow, limits, spread[1], spread[2], spread[3]
    )
    if verdict == LEG_UNDEFINED:
        return UNSURE, False
    if verdict == LEG_OUT:
        return OUT, True
    closes = verdict == LEG_IN  # else: over every point of the box, limits or not
    reaches = closes
    if not closes:
        reach, ux_lo, ux_hi, uy_lo, uy_hi, mm_lo, mm_hi = leg_spread(
            xlo, xhi, ylo, yhi, leg, g, r, elbow, FREE, spread[1], spread[2], spread[3]
        )
        reaches = reach == LEG_IN
    vx_lo, vx_hi = iadd_scalar(xlo, xhi, r[leg, 0] - g[8 + 2 * leg])
    vy_lo, vy_hi = iadd_scalar(ylo, yhi, r[leg, 1] - g[9 + 2 * leg])
    vx_lo -= TOLERANCE_CM
    vx_hi += TOLERANCE_CM
    vy_lo -= TOLERANCE_CM
    vy_hi += TOLERANCE_CM
    b_lo, b_hi = isub(*imul(vx_lo, vx_hi, uy_lo, uy_hi), *imul(vy_lo, vy_hi, ux_lo, ux_hi))
    t_lo, t_hi = iscale(mm_lo, mm_hi, 1.0 / length_cm) if length_cm > 0.0 else (0.0, 0.0)
    sq_lo, sq_hi = iadd(*isqr(ux_lo, ux_hi), *isqr(uy_lo, uy_hi))
    sq_lo, sq_hi = iadd(sq_lo, sq_hi, *isqr(t_lo, t_hi))
    set_norm(norms, row, sq_lo, sq_hi, b_lo, b_hi)
    set_row(m_lo, m_hi, row, 0, ux_lo, ux_hi, b_lo, b_hi)
    set_row(m_lo, m_hi, row, 1, uy_lo, uy_hi, b_lo, b_hi)
    if length_cm > 0.0:
        set_row(m_lo, m_hi, row, 2, t_lo, t_hi, b_lo, b_hi)
    result = IN if closes else UNSURE
    if not reaches or b_lo <= 0.0 <= b_hi:
        return result, True
    cx = 0.5 * (xlo + xhi)
    cy = 0.5 * (ylo + yhi)
    ok, cux_lo, cux_hi, cuy_lo, cuy_hi, ct_lo, ct_hi, cb_lo, cb_hi = rr_point(
        cx, cy, leg, g, r, elbow, FREE, length_cm, spread[1]
    )
    if not ok or cb_lo <= 0.0 <= cb_hi:
        return result, True
    l1 = g[0]
    l1_lo, l1_hi = widen(l1, spread[2])
    if spread[2] == 0.0:
        ex_lo, ex_hi = iscale(*isub(vx_lo, vx_hi, ux_lo, ux_hi), 1.0 / l1)
        ey_lo, ey_hi = iscale(*isub(vy_lo, vy_hi, uy_lo, uy_hi), 1.0 / l1)
        ex_lo, ex_hi = iadd(ex_lo, ex_hi, -1e-15, 1e-15)  # 1 / l1 rounded
        ey_lo, ey_hi = iadd(ey_lo, ey_hi, -1e-15, 1e-15)
    else:
        ex_lo, ex_hi = idiv_positive(*isub(vx_lo, vx_hi, ux_lo, ux_hi), l1_lo, l1_hi)
        ey_lo, ey_hi = idiv_positive(*isub(vy_lo, vy_hi, uy_lo, uy_hi), l1_lo, l1_hi)
    dx = up(max(cx - xlo, xhi - cx))
    dy = up(max(cy - ylo, yhi - cy))
    ux_x = iadd_scalar(*imul(*imul(ey_lo, ey_hi, m_lo[row, 0], m_hi[row, 0]), l1_lo, l1_hi), 1.0)
    uy_x = imul(*imul(ex_lo, ex_hi, m_lo[row, 0], m_hi[row, 0]), -l1_hi, -l1_lo)
    ux_y = imul(*imul(ey_lo, ey_hi, m_lo[row, 1], m_hi[row, 1]), l1_lo, l1_hi)
    uy_y = iadd_scalar(*imul(*imul(ex_lo, ex_hi, m_lo[row, 1], m_hi[row, 1]), -l1_hi, -l1_lo), 1.0)
    cross_x = isub(*imul(vx_lo, vx_hi, *uy_x), *imul(vy_lo, vy_hi, *ux_x))
    cross_y = isub(*imul(vx_lo, vx_hi, *uy_y), *imul(vy_lo, vy_hi, *ux_y))
    b_x = iadd(uy_lo, uy_hi, *cross_x)
    b_y = iadd(-ux_hi, -ux_lo, *cross_y)
    c0 = idiv(cux_lo, cux_hi, cb_lo, cb_hi)
    c1 = idiv(cuy_lo, cuy_hi, cb_lo, cb_hi)
    c2 = idiv(ct_lo, ct_hi, cb_lo, cb_hi)
    rx = widen(r[leg, 0], spread[1])
    ry = widen(r[leg, 1], spread[1])
    if spread[2] > 0.0 or spread[3] > 0.0:  # the centre is the nominal lengths'
        e = (ex_lo, ex_hi, ey_lo, ey_hi)
        u = (ux_lo, ux_hi, uy_lo, uy_hi)
        v = (vx_lo, vx_hi, vy_lo, vy_hi)
        l2 = widen(g[1], spread[3])
        parts = (m_lo, m_hi, row, b_lo, b_hi, (l1_lo, l1_hi), l2, rx, ry, length_cm)
        c0, c1, c2 = length_terms(parts, e, u, v, spread[2], spread[3], c0, c1, c2)
    mean_value(m_lo, m_hi, row, 0, *c0, b_lo, b_hi, ux_x, ux_y, b_x, b_y, dx, dy)
    mean_value(m_lo, m_hi, row, 1, *c1, b_lo, b_hi, uy_x, uy_y, b_x, b_y, dx, dy)
    if length_cm > 0.0:
        t_x = iscale(*isub(*imul(*ux_x, *ry), *imul(*uy_x, *rx)), 1.0 / length_cm)
        t_y = iscale(*isub(*imul(*ux_y, *ry), *imul(*uy_y, *rx)), 1.0 / length_cm)
        mean_value(m_lo, m_hi, row, 2, *c2, b_lo, b_hi, t_x, t_y, b_x, b_y, dx, dy)
    return result, True


@kernel
def length_terms(parts, e, u, v, t1, t2, c0, c1, c2):
    """The row's centre enclosures ``c0, c1, c2`` (at the nominal lengths) plus the
    mean-value terms of the link lengths, :math:`\\partial_{l} m(X, \\Pi)\\,[-t, t]` for
    :math:`l_1` and :math:`l_2`. From :math:`|u|^2 = l_2^2`, :math:`u = v - l_1 e`,
    :math:`b = v \\times u = l_1\\, e \\times u`: :math:`\\partial_{l_1} u = -e + l_1
    \\frac{u \\cdot e}{b} e^\\perp` and :math:`\\partial_{l_2} u = \\frac{l_1 l_2}{b}
    e^\\perp` (:math:`e^\\perp = (-e_y, e_x)`), :math:`\\partial b = v \\times \\partial u`,
    :math:`\\partial (u \\times r) = \\partial u \\times r` (the third entry only with a
    length). ``parts``: ``(m_lo, m_hi, row, b_lo, b_hi, l1, l2, rx, ry, length_cm)``,
    ``e``, ``u``, ``v`` (x lo, x hi, y lo, y hi) enclosures over the box and the robots."""
    m_lo, m_hi, row, b_lo, b_hi, l1, l2, rx, ry, length_cm = parts
    ex_lo, ex_hi, ey_lo, ey_hi = e
    ux_lo, ux_hi, uy_lo, uy_hi = u
    vx_lo, vx_hi, vy_lo, vy_hi = v
    ue = iadd(*imul(ux_lo, ux_hi, ex_lo, ex_hi), *imul(uy_lo, uy_hi, ey_lo, ey_hi))
    k1 = imul(*l1, *idiv(*ue, b_lo, b_hi))
    d1x = isub(-ex_hi, -ex_lo, *imul(*k1, ey_lo, ey_hi))
    d1y = iadd(-ey_hi, -ey_lo, *imul(*k1, ex_lo, ex_hi))
    k2 = idiv(*imul(*l1, *l2), b_lo, b_hi)
    d2x = imul(*k2, -ey_hi, -ey_lo)
    d2y = imul(*k2, ex_lo, ex_hi)
    for dx_, dy_, t in ((d1x, d1y, t1), (d2x, d2y, t2)):
        db = isub(*imul(vx_lo, vx_hi, *dy_), *imul(vy_lo, vy_hi, *dx_))
        c0 = iadd(*c0, *slope_term(m_lo[row, 0], m_hi[row, 0], dx_, db, b_lo, b_hi, t))
        c1 = iadd(*c1, *slope_term(m_lo[row, 1], m_hi[row, 1], dy_, db, b_lo, b_hi, t))
        if length_cm > 0.0:
            dt = iscale(*isub(*imul(*dx_, *ry), *imul(*dy_, *rx)), 1.0 / length_cm)
            c2 = iadd(*c2, *slope_term(m_lo[row, 2], m_hi[row, 2], dt, db, b_lo, b_hi, t))
    return c0, c1, c2


@kernel(parallel=True)
def rr_dexterity(boxes, g, r, elbow, limits, length_cm, spread, verdict, kappa):
    """Per row ``x_lo, x_hi, y_lo, y_hi`` of ``boxes``: the verdict in the mode ``elbow``
    (:mod:`kernels.dexterity`) and ``kappa[i] = (lo, hi)``, an enclosure of κ over the
    box's points in the mode's workspace (``(1, inf)`` where not bounded). ``g`` has one
    geometry row per leg (the 3-RRR's layout, :mod:`kernels.singularity3rrr`: a 3-RRR's
    vector repeated, a five-bar's rows), ``r`` the platform offsets (zeros for the
    five-bar), ``limits`` (legs, 2) radians; three legs: a 3 x 3 :math:`M` with
    :math:`L` = ``length_cm``, two legs: the five-bar's 2 x 2. ``spread`` has one
    :func:`kernels.singularity3rrr.leg_spread` row per leg (zeros: the robot as given);
    with tolerances ``IN`` means every robot closes at every point and ``kappa`` encloses
    every robot's κ."""
    n = len(g)
    length = length_cm if n == 3 else 0.0
    for i in numba.prange(len(boxes)):
        m_lo = np.empty((n, n))
        m_hi = np.empty((n, n))
        norms = np.empty((n, 2))
        state = IN
        defined = True
        for leg in range(n):
            xlo, xhi, ylo, yhi = boxes[i, 0], boxes[i, 1], boxes[i, 2], boxes[i, 3]
            v, ok = rr_leg(
                xlo,
                xhi,
                ylo,
                yhi,
                leg,
                g[leg],
                r,
                elbow,
                limits,
                m_lo,
                m_hi,
                norms,
                leg,
                length,
                spread[leg],
            )
            state = combine(state, v)
            defined = defined and ok
        verdict[i] = state
        kappa[i, 0] = 1.0
        kappa[i, 1] = math.inf
        if state != OUT and defined:
            kappa[i, 0], kappa[i, 1] = kappa_bounds(m_lo, m_hi, n, norms)

"""κ enclosures over (x, y) boxes of the robots with an actuated prismatic joint: the 3-RPR
(the leg's length) and the 3-PRR (the slider on its base line).

**3-RPR** (:mod:`kernels.singularity3rpr`'s model): leg ``i`` runs from its base joint to
:math:`C_i = p + r_i`; with :math:`v_i = p - c_i` (:math:`c_i = A_i - r_i`) its length is
:math:`\\rho_i = |v_i|` and :math:`\\rho_i \\dot\\rho_i = v_i \\cdot (\\dot p + \\dot\\varphi
E r_i)`: the row of :math:`M = J^{-1}` is :math:`(v_{ix}, v_{iy}, \\mp(v_i \\times r_i)/L) /
\\rho_i` (a column's sign leaves κ unchanged). Derivatives for the mean-value form:
:math:`\\partial_x a = (1, 0, r_y / L)`, :math:`\\partial_y a = (0, 1, -r_x / L)`,
:math:`\\partial b = v / \\rho`; smooth wherever :math:`\\rho > 0`. A leg is *in* where
:math:`\\rho` lies in its limits, *out* where it misses them.

**3-PRR** (:mod:`kernels.singularity3prr`'s model): :math:`w = p - B'`, :math:`h = w \\cdot
n`, :math:`q = l^2 - h^2`, the slider :math:`s = w \\cdot u + \\sigma\\sqrt q` and the
distal link :math:`d = h n - \\sigma \\sqrt q\\, u`. Differentiating :math:`|d|^2 = l^2`:
:math:`d \\cdot (\\dot p + \\dot\\varphi E r) = \\dot s\\,(d \\cdot u)` with :math:`d \\cdot u =
-\\sigma\\sqrt q`: the row is :math:`(d_x, d_y, \\mp(d \\times r)/L) / (-\\sigma\\sqrt q)`
(type I where :math:`q = 0`). With :math:`k = \\sigma h / \\sqrt q`: :math:`\\partial_x d =
n_x (n + k u)`, :math:`\\partial_x b = k n_x` (and :math:`y` with :math:`n_y`), smooth
wherever :math:`q > 0`.
"""

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
from .interval import grown_box, iadd, iadd_scalar, imul, iscale, isqr, isqrt, isub, up, widen
from .singularity3rrr import idiv_positive

#: Round-off allowance of the float offsets (cm), as :mod:`kernels.singularity3rrr`'s.
TOLERANCE_CM = 1e-10


@kernel
def rows_and_norm(m_lo, m_hi, norms, row, ax, ay, t, b, length_cm):
    """Row ``row`` of :math:`M`, ``(ax, ay, t) / b`` (``t`` only with a length), and its
    norm bounds (each argument a ``(lo, hi)`` pair)."""
    sq_lo, sq_hi = iadd(*isqr(*ax), *isqr(*ay))
    if length_cm > 0.0:
        sq_lo, sq_hi = iadd(sq_lo, sq_hi, *isqr(*t))
        set_row(m_lo, m_hi, row, 2, *t, *b)
    set_norm(norms, row, sq_lo, sq_hi, *b)
    set_row(m_lo, m_hi, row, 0, *ax, *b)
    set_row(m_lo, m_hi, row, 1, *ay, *b)


@kernel
def rpr_parts(xlo, xhi, ylo, yhi, leg, centres, r, length_cm):
    """``(vx, vy, t, rho)`` enclosures over the box (module docstring)."""
    return rpr_spread(xlo, xhi, ylo, yhi, leg, centres, r, length_cm, 0.0)


@kernel
def rpr_spread(xlo, xhi, ylo, yhi, leg, centres, r, length_cm, offset_cm):
    """:func:`rpr_parts` with :math:`r_i` widened by ``offset_cm`` in :math:`v_i \\times
    r_i`."""
    vx_lo, vx_hi = iadd_scalar(xlo, xhi, -centres[leg, 0])
    vy_lo, vy_hi = iadd_scalar(ylo, yhi, -centres[leg, 1])
    vx = (vx_lo - TOLERANCE_CM, vx_hi + TOLERANCE_CM)
    vy = (vy_lo - TOLERANCE_CM, vy_hi + TOLERANCE_CM)
    rho = isqrt(*iadd(*isqr(*vx), *isqr(*vy)))
    t = (0.0, 0.0)
    if length_cm > 0.0:
        ry = widen(r[leg, 1], offset_cm)
        rx = widen(r[leg, 0], offset_cm)
        cross = isub(*imul(*vx, *ry), *imul(*vy, *rx))
        t = iscale(cross[0] - TOLERANCE_CM, cross[1] + TOLERANCE_CM, 1.0 / length_cm)
    return vx, vy, t, rho


@kernel
def rpr_leg(xlo, xhi, ylo, yhi, leg, centres, r, limits, m_lo, m_hi, norms, length_cm, spread):
    """Leg ``leg``'s verdict over the box, writing its row of :math:`M` (the natural
    enclosure met with the mean-value form where :math:`\\rho > 0` over the box), over
    every robot within ``spread`` = ``(grow_cm, offset_cm)``: the base joint's and the
    platform point's tolerances move :math:`c_i = A_i - r_i` by at most ``grow_cm`` per
    axis, as the position does (the box grown by it, :func:`kernels.interval.grown_box`),
    and :math:`r_i` in :math:`v_i \\times r_i` by ``offset_cm``. ``IN``: every robot's
    leg closes at every point; ``OUT``: none at any."""
    xlo, xhi, ylo, yhi = grown_box(xlo, xhi, ylo, yhi, spread[0])
    offset = spread[1]
    vx, vy, t, rho = rpr_spread(xlo, xhi, ylo, yhi, leg, centres, r, length_cm, offset)
    lo = limits[leg, 0]
    hi = limits[leg, 1]
    if rho[1] < lo or rho[0] > hi:
        return OUT
    result = IN if lo <= rho[0] and rho[1] <= hi else UNSURE
    rows_and_norm(m_lo, m_hi, norms, leg, vx, vy, t, rho, length_cm)
    if rho[0] <= 0.0:
        return result
    cx = 0.5 * (xlo + xhi)
    cy = 0.5 * (ylo + yhi)
    cvx, cvy, ct, crho = rpr_spread(cx, cx, cy, cy, leg, centres, r, length_cm, offset)
    dx = up(max(cx - xlo, xhi - cx))
    dy = up(max(cy - ylo, yhi - cy))
    db_x = idiv(*vx, *rho)
    db_y = idiv(*vy, *rho)
    one = (1.0, 1.0)
    zero = (0.0, 0.0)
    mean_value(m_lo, m_hi, leg, 0, *idiv(*cvx, *crho), *rho, one, zero, db_x, db_y, dx, dy)
    mean_value(m_lo, m_hi, leg, 1, *idiv(*cvy, *crho), *rho, zero, one, db_x, db_y, dx, dy)
    if length_cm > 0.0:
        slack = TOLERANCE_CM + offset
        ta_x = iscale(r[leg, 1] - slack, r[leg, 1] + slack, 1.0 / length_cm)
        ta_y = iscale(-r[leg, 0] - slack, -r[leg, 0] + slack, 1.0 / length_cm)
        c2 = idiv(*ct, *crho)
        mean_value(m_lo, m_hi, leg, 2, *c2, *rho, ta_x, ta_y, db_x, db_y, dx, dy)
    return result


@kernel(parallel=True)
def rpr_dexterity(boxes, centres, r, limits, length_cm, spread, verdict, kappa):
    """Per row ``x_lo, x_hi, y_lo, y_hi`` of ``boxes``: the 3-RPR's verdict and κ
    enclosure (``centres`` (3, 2) :math:`c_i`, ``r`` (3, 2) :math:`r_i`, ``limits`` (3, 2)
    leg lengths, cm; :math:`L` = ``length_cm``), over every robot within ``spread`` (one
    :func:`rpr_leg` row per leg; zeros: the robot as given)."""
    for i in numba.prange(len(boxes)):
        m_lo = np.empty((3, 3))
        m_hi = np.empty((3, 3))
        norms = np.empty((3, 2))
        state = IN
        for leg in range(3):
            xlo, xhi, ylo, yhi = boxes[i, 0], boxes[i, 1], boxes[i, 2], boxes[i, 3]
            v = rpr_leg(
                xlo,
                xhi,
                ylo,
                yhi,
                leg,
                centres,
                r,
                limits,
                m_lo,
                m_hi,
                norms,
                length_cm,
                spread[leg],
            )
            state = combine(state, v)
        verdict[i] = state
        kappa[i, 0] = 1.0
        kappa[i, 1] = np.inf
        if state != OUT:
            kappa[i, 0], kappa[i, 1] = kappa_bounds(m_lo, m_hi, 3, norms)


@kernel
def prr_parts(xlo, xhi, ylo, yhi, leg, g, sigma, r, length_cm):
    """``(reach, s, h, root, dx, dy, t, b)`` over the box (module docstring): ``reach``
    false where :math:`q < 0` everywhere, else enclosures (``root`` of :math:`q \\cap [0,
    \\infty)`)."""
    return prr_spread(xlo, xhi, ylo, yhi, leg, g, sigma, r, length_cm, 0.0, 0.0)


@kernel
def prr_spread(xlo, xhi, ylo, yhi, leg, g, sigma, r, length_cm, offset_cm, t_cm):
    """:func:`prr_parts` with :math:`r_i` widened by ``offset_cm`` in :math:`d \\times
    r_i` and the distal :math:`l \\pm` ``t_cm``."""
    ux = g[leg, 2]
    uy = g[leg, 3]
    wx_lo, wx_hi = iadd_scalar(xlo, xhi, -g[leg, 0])
    wy_lo, wy_hi = iadd_scalar(ylo, yhi, -g[leg, 1])
    wx = (wx_lo - TOLERANCE_CM, wx_hi + TOLERANCE_CM)
    wy = (wy_lo - TOLERANCE_CM, wy_hi + TOLERANCE_CM)
    a = iadd(*iscale(*wx, ux), *iscale(*wy, uy))
    h = iadd(*iscale(*wx, -uy), *iscale(*wy, ux))
    q = isub(*isqr(*widen(g[leg, 6], t_cm)), *isqr(*h))
    zero = (0.0, 0.0)
    if q[1] < 0.0:
        return False, zero, zero, zero, zero, zero, zero, zero
    root = isqrt(*q)
    s = iadd(*a, *iscale(*root, sigma))
    dx = isub(*iscale(*h, -uy), *iscale(*root, sigma * ux))
    dy = isub(*iscale(*h, ux), *iscale(*root, sigma * uy))
    t = zero
    if length_cm > 0.0:
        ry = widen(r[leg, 1], offset_cm)
        rx = widen(r[leg, 0], offset_cm)
        cross = isub(*imul(*dx, *ry), *imul(*dy, *rx))
        t = iscale(cross[0] - TOLERANCE_CM, cross[1] + TOLERANCE_CM, 1.0 / length_cm)
    b = iscale(*root, -sigma)
    return True, s, h, root, dx, dy, t, b


@kernel
def prr_leg(xlo, xhi, ylo, yhi, leg, g, modes, r, m_lo, m_hi, norms, length_cm, spread):
    """Leg ``leg``'s verdict over the box in its mode, writing its row of :math:`M` (the
    mean-value form where :math:`q > 0` over the box), over every robot within ``spread``
    = ``(grow_cm, offset_cm, t_cm)``: the slider point's and the platform point's
    tolerances move the leg as the position does (the box grown by ``grow_cm``,
    :func:`kernels.interval.grown_box`), :math:`r_i` in :math:`d \\times r_i` by
    ``offset_cm``, the distal is :math:`l \\pm` ``t_cm`` with a mean-value term in it
    (:math:`\\partial_l d = -\\sigma (l / \\sqrt q)\\, u`, :math:`\\partial_l b = -\\sigma l /
    \\sqrt q`) about the centre at the nominal :math:`l`."""
    sigma = modes[leg]
    xlo, xhi, ylo, yhi = grown_box(xlo, xhi, ylo, yhi, spread[0])
    offset, t_l = spread[1], spread[2]
    reach, s, h, root, dx, dy, t, b = prr_spread(
        xlo, xhi, ylo, yhi, leg, g, sigma, r, length_cm, offset, t_l
    )
    if not reach or s[1] < g[leg, 4] or s[0] > g[leg, 5]:
        return OUT
    q_in = root[0] > 0.0
    result = IN if (q_in and g[leg, 4] <= s[0] and s[1] <= g[leg, 5]) else UNSURE
    rows_and_norm(m_lo, m_hi, norms, leg, dx, dy, t, b, length_cm)
    if not q_in:
        return result
    cx = 0.5 * (xlo + xhi)
    cy = 0.5 * (ylo + yhi)
    ok, _, _, _, cdx, cdy, ct, cb = prr_spread(
        cx, cx, cy, cy, leg, g, sigma, r, length_cm, offset, 0.0
    )
    if not ok or cb[0] <= 0.0 <= cb[1]:
        return result
    ux = g[leg, 2]
    uy = g[leg, 3]
    nx = -uy
    ny = ux
    k = iscale(*idiv(*h, *root), sigma)
    dd_x = (
        iscale(*iadd_scalar(*iscale(*k, ux), nx), nx),
        iscale(*iadd_scalar(*iscale(*k, uy), ny), nx),
    )
    dd_y = (
        iscale(*iadd_scalar(*iscale(*k, ux), nx), ny),
        iscale(*iadd_scalar(*iscale(*k, uy), ny), ny),
    )
    db_x = iscale(*k, nx)
    db_y = iscale(*k, ny)
    step_x = up(max(cx - xlo, xhi - cx))
    step_y = up(max(cy - ylo, yhi - cy))
    c0 = idiv(*cdx, *cb)
    c1 = idiv(*cdy, *cb)
    c2 = idiv(*ct, *cb)
    ry = widen(r[leg, 1], offset)
    rx = widen(r[leg, 0], offset)
    if t_l > 0.0:  # the distal's mean-value term
        slope = iscale(*idiv_positive(*widen(g[leg, 6], t_l), *root), -sigma)  # -σ l / √q
        dl = (iscale(*slope, ux), iscale(*slope, uy))
        c0 = iadd(*c0, *slope_term(m_lo[leg, 0], m_hi[leg, 0], dl[0], slope, *b, t_l))
        c1 = iadd(*c1, *slope_term(m_lo[leg, 1], m_hi[leg, 1], dl[1], slope, *b, t_l))
        if length_cm > 0.0:
            dl_t = iscale(*isub(*imul(*dl[0], *ry), *imul(*dl[1], *rx)), 1.0 / length_cm)
            c2 = iadd(*c2, *slope_term(m_lo[leg, 2], m_hi[leg, 2], dl_t, slope, *b, t_l))
    mean_value(m_lo, m_hi, leg, 0, *c0, *b, dd_x[0], dd_y[0], db_x, db_y, step_x, step_y)
    mean_value(m_lo, m_hi, leg, 1, *c1, *b, dd_x[1], dd_y[1], db_x, db_y, step_x, step_y)
    if length_cm > 0.0:
        tx = iscale(*isub(*imul(*dd_x[0], *ry), *imul(*dd_x[1], *rx)), 1.0 / length_cm)
        ty = iscale(*isub(*imul(*dd_y[0], *ry), *imul(*dd_y[1], *rx)), 1.0 / length_cm)
        mean_value(m_lo, m_hi, leg, 2, *c2, *b, tx, ty, db_x, db_y, step_x, step_y)
    return result


@kernel(parallel=True)
def prr_dexterity(boxes, g, modes, r, length_cm, spread, verdict, kappa):
    """Per row of ``boxes``: the 3-PRR's verdict in the mode ``modes`` and κ enclosure
    (``g`` (3, 7) as :mod:`kernels.singularity3prr`'s, ``r`` (3, 2) :math:`r_i`), over
    every robot within ``spread`` (one :func:`prr_leg` row per leg; zeros: the robot as
    given)."""
    for i in numba.prange(len(boxes)):
        m_lo = np.empty((3, 3))
        m_hi = np.empty((3, 3))
        norms = np.empty((3, 2))
        state = IN
        for leg in range(3):
            xlo, xhi, ylo, yhi = boxes[i, 0], boxes[i, 1], boxes[i, 2], boxes[i, 3]
            v = prr_leg(
                xlo, xhi, ylo, yhi, leg, g, modes, r, m_lo, m_hi, norms, length_cm, spread[leg]
            )
            state = combine(state, v)
        verdict[i] = state
        kappa[i, 0] = 1.0
        kappa[i, 1] = np.inf
        if state != OUT:
            kappa[i, 0], kappa[i, 1] = kappa_bounds(m_lo, m_hi, 3, norms)

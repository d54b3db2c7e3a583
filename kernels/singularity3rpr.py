"""Parallel (type II) singularities of a 3-RPR at a fixed orientation, by interval analysis.

Leg ``i`` pushes the platform along its own line: with :math:`v_i = C_i - A_i = p - c_i`
(:math:`c_i = A_i - r_i`, :math:`r_i = R(\\varphi) q_i`), differentiating
:math:`\\rho_i^2 = |v_i|^2` gives :math:`\\rho_i\\,\\dot\\rho_i = v_i \\cdot \\dot p +
\\dot\\varphi\\,(r_i \\times v_i)`, so the parallel Jacobian has rows
:math:`[v_i^T,\\ v_i \\times r_i]` up to the sign of its last column (the 3-RRR's rows, with
the leg direction in place of the distal link; :math:`a \\times b = a_x b_y - a_y b_x`), and
a pose is type II singular iff :math:`\\det A = 0`: the three leg lines are concurrent or
parallel. At a fixed orientation there is no working mode: :math:`\\det A` is a polynomial
in :math:`(x, y)`.

**Box test** (:func:`det_range`): :math:`v_i` is :math:`(X - c_x, Y - c_y)` exactly as an
interval, :math:`v_i \\times r_i` and the cofactor expansion of the determinant are enclosed
with the rigorous arithmetic of :mod:`kernels.interval`, so the enclosure holds
:math:`\\det A(p)` for every point of the box.

**Paving** (:func:`singular_level`, a level of
:func:`planar_tui.workspace.paving.levels.pave_in_levels`): a box proved outside the workspace
(:func:`~kernels.workspace3rpr.classify_rpr_box`) or whose determinant enclosure excludes 0
holds no singular pose of the workspace and is dropped; any other box is halved down to
``precision`` and kept. Every singular pose of the workspace lies in a kept leaf.

``p`` is the (3, 4) array of :mod:`kernels.workspace3rpr`; ``offsets`` the (3, 2) float
offsets :math:`r_i = R(\\varphi) q_i`.
"""

import numba

from ._jit import kernel
from .interval import iadd, iadd_scalar, imul, isub
from .workspace3rpr import classify_rpr_box
from .workspace_arc import BOUNDARY, LANES, OUTSIDE, settle_xy_box


@kernel
def _linear(xlo, xhi, ylo, yhi, a_lo, a_hi, b_lo, b_hi, c_lo, c_hi):
    """Enclosure of :math:`a x + b y + c` over the box (interval coefficients)."""
    return iadd(*iadd(*imul(xlo, xhi, a_lo, a_hi), *imul(ylo, yhi, b_lo, b_hi)), c_lo, c_hi)


@kernel
def _cross(a_lo, a_hi, b_lo, b_hi, c_lo, c_hi, d_lo, d_hi):
    """:math:`a d - b c` of interval numbers (``a, b, c, d`` in that order)."""
    return isub(*imul(a_lo, a_hi, d_lo, d_hi), *imul(b_lo, b_hi, c_lo, c_hi))


@kernel
def det_range(xlo, xhi, ylo, yhi, p, offsets):
    """Enclosure of :math:`\\det A` over the box.

    Rows :math:`[v_i^T,\\ t_i]` with :math:`v_i = p - c_i` and :math:`t_i = v_i \\times r_i
    = x\\,r_{y,i} - y\\,r_{x,i} + k_i`, :math:`k_i = c_{y,i} r_{x,i} - c_{x,i} r_{y,i}`.
    Subtracting row 0 from rows 1 and 2 leaves them :math:`[a_i, b_i, t_i - t_0]` with
    constants :math:`a_i = c_{x,0} - c_{x,i}`, :math:`b_i = c_{y,0} - c_{y,i}` and
    :math:`t_i - t_0` linear in :math:`(x, y)`, so

    .. math:: \\det A = v_{x,0} L_1 - v_{y,0} L_2 + t_0 K,

    :math:`L_1 = b_1 (t_2 - t_0) - b_2 (t_1 - t_0)`, :math:`L_2 = a_1 (t_2 - t_0) - a_2
    (t_1 - t_0)` linear, :math:`K = a_1 b_2 - a_2 b_1`: a quadratic (the cubic terms of the
    plain expansion cancel, which the interval form would not see). Every linear factor
    is enclosed exactly (coefficients as rounded intervals), the products naturally.
    """
    c = _coefficients(p, offsets)
    return _natural(xlo, xhi, ylo, yhi, p, offsets, c)


@kernel
def _coefficients(p, offsets):
    """Enclosures (lo, hi pairs) of the coefficients of ``x, y, 1`` in :math:`L_1` and
    :math:`L_2`, then :math:`K` and :math:`k_0` (see :func:`det_range`)."""
    cx0 = p[0, 0]
    cy0 = p[0, 1]
    rx0 = offsets[0, 0]
    ry0 = offsets[0, 1]
    k0_lo, k0_hi = isub(*imul(cy0, cy0, rx0, rx0), *imul(cx0, cx0, ry0, ry0))
    a1_lo, a1_hi, b1_lo, b1_hi, al1_lo, al1_hi, be1_lo, be1_hi, g1_lo, g1_hi = _reduced_row(
        p, offsets, 1, k0_lo, k0_hi
    )
    a2_lo, a2_hi, b2_lo, b2_hi, al2_lo, al2_hi, be2_lo, be2_hi, g2_lo, g2_hi = _reduced_row(
        p, offsets, 2, k0_lo, k0_hi
    )
    # L1 = b1 t2' - b2 t1' and L2 = a1 t2' - a2 t1', coefficient by coefficient
    return (
        *_cross(b1_lo, b1_hi, b2_lo, b2_hi, al1_lo, al1_hi, al2_lo, al2_hi),
        *_cross(b1_lo, b1_hi, b2_lo, b2_hi, be1_lo, be1_hi, be2_lo, be2_hi),
        *_cross(b1_lo, b1_hi, b2_lo, b2_hi, g1_lo, g1_hi, g2_lo, g2_hi),
        *_cross(a1_lo, a1_hi, a2_lo, a2_hi, al1_lo, al1_hi, al2_lo, al2_hi),
        *_cross(a1_lo, a1_hi, a2_lo, a2_hi, be1_lo, be1_hi, be2_lo, be2_hi),
        *_cross(a1_lo, a1_hi, a2_lo, a2_hi, g1_lo, g1_hi, g2_lo, g2_hi),
        *_cross(a1_lo, a1_hi, b1_lo, b1_hi, a2_lo, a2_hi, b2_lo, b2_hi),
        k0_lo,
        k0_hi,
    )


@kernel
def _factors(xlo, xhi, ylo, yhi, p, offsets, c):
    """Enclosures of :math:`v_{x,0}, v_{y,0}, t_0, L_1, L_2` over the box."""
    u_lo, u_hi = iadd_scalar(xlo, xhi, -p[0, 0])
    v_lo, v_hi = iadd_scalar(ylo, yhi, -p[0, 1])
    t_lo, t_hi = _linear(
        xlo,
        xhi,
        ylo,
        yhi,
        offsets[0, 1],
        offsets[0, 1],
        -offsets[0, 0],
        -offsets[0, 0],
        c[14],
        c[15],
    )
    m1_lo, m1_hi = _linear(xlo, xhi, ylo, yhi, c[0], c[1], c[2], c[3], c[4], c[5])
    m2_lo, m2_hi = _linear(xlo, xhi, ylo, yhi, c[6], c[7], c[8], c[9], c[10], c[11])
    return u_lo, u_hi, v_lo, v_hi, t_lo, t_hi, m1_lo, m1_hi, m2_lo, m2_hi


@kernel
def _natural(xlo, xhi, ylo, yhi, p, offsets, c):
    """:math:`v_{x,0} L_1 - v_{y,0} L_2 + t_0 K` evaluated in intervals."""
    u_lo, u_hi, v_lo, v_hi, t_lo, t_hi, m1_lo, m1_hi, m2_lo, m2_hi = _factors(
        xlo, xhi, ylo, yhi, p, offsets, c
    )
    first_lo, first_hi = isub(*imul(u_lo, u_hi, m1_lo, m1_hi), *imul(v_lo, v_hi, m2_lo, m2_hi))
    return iadd(first_lo, first_hi, *imul(t_lo, t_hi, c[12], c[13]))


@kernel
def det_mean_value(xlo, xhi, ylo, yhi, p, offsets):
    """Enclosure of :math:`\\det A` over the box by the mean-value form
    :math:`\\det(m) + G_x (X - m_x) + G_y (Y - m_y)`, intersected with
    :func:`det_range`'s. The gradient of the quadratic (:func:`det_range`):
    :math:`\\partial_x = L_1 + v_{x,0}\\,\\partial_x L_1 - v_{y,0}\\,\\partial_x L_2 +
    r_{y,0} K`, :math:`\\partial_y = v_{x,0}\\,\\partial_y L_1 - L_2 - v_{y,0}\\,
    \\partial_y L_2 - r_{x,0} K`, enclosed over the box. The natural form alone sees the
    cancellation of large terms only at points; this one's width is about the gradient
    times the box width."""
    c = _coefficients(p, offsets)
    mx = 0.5 * (xlo + xhi)
    my = 0.5 * (ylo + yhi)
    d_lo, d_hi = _natural(mx, mx, my, my, p, offsets, c)
    u_lo, u_hi, v_lo, v_hi, _, _, m1_lo, m1_hi, m2_lo, m2_hi = _factors(
        xlo, xhi, ylo, yhi, p, offsets, c
    )
    ry0 = offsets[0, 1]
    rx0 = offsets[0, 0]
    gx_lo, gx_hi = iadd(
        *isub(*iadd(m1_lo, m1_hi, *imul(u_lo, u_hi, c[0], c[1])), *imul(v_lo, v_hi, c[6], c[7])),
        *imul(ry0, ry0, c[12], c[13]),
    )
    gy_lo, gy_hi = isub(
        *isub(*imul(u_lo, u_hi, c[2], c[3]), m2_lo, m2_hi),
        *iadd(*imul(v_lo, v_hi, c[8], c[9]), *imul(rx0, rx0, c[12], c[13])),
    )
    dx_lo, dx_hi = isub(xlo, xhi, mx, mx)
    dy_lo, dy_hi = isub(ylo, yhi, my, my)
    lo, hi = iadd(
        d_lo, d_hi, *iadd(*imul(gx_lo, gx_hi, dx_lo, dx_hi), *imul(gy_lo, gy_hi, dy_lo, dy_hi))
    )
    n_lo, n_hi = _natural(xlo, xhi, ylo, yhi, p, offsets, c)
    return max(lo, n_lo), min(hi, n_hi)


@kernel
def _reduced_row(p, offsets, i, k0_lo, k0_hi):
    """Row ``i`` minus row 0: enclosures of :math:`a_i, b_i` and of the coefficients
    :math:`\\alpha_i, \\beta_i, \\gamma_i` of :math:`t_i - t_0 = \\alpha_i x + \\beta_i y
    + \\gamma_i`."""
    cx = p[i, 0]
    cy = p[i, 1]
    rx = offsets[i, 0]
    ry = offsets[i, 1]
    k_lo, k_hi = isub(*imul(cy, cy, rx, rx), *imul(cx, cx, ry, ry))
    return (
        *isub(p[0, 0], p[0, 0], cx, cx),
        *isub(p[0, 1], p[0, 1], cy, cy),
        *isub(ry, ry, offsets[0, 1], offsets[0, 1]),
        *isub(offsets[0, 0], offsets[0, 0], rx, rx),
        *isub(k_lo, k_hi, k0_lo, k0_hi),
    )


@kernel
def points_det_range(xs, ys, p, offsets, out):
    """:func:`det_range` at each point ``(xs[k], ys[k])``: ``out[k] = (lo, hi)``."""
    for k in range(xs.shape[0]):
        lo, hi = det_range(xs[k], xs[k], ys[k], ys[k], p, offsets)
        out[k, 0] = lo
        out[k, 1] = hi


@kernel(parallel=True)
def singular_level(p, offsets, precision, rows, start, stop, children, outcome):
    """Decide rows ``start .. stop - 1`` of a frontier in parallel (module docstring): a
    box is dropped (``OUTSIDE``) or kept/halved as ``BOUNDARY``
    (:func:`~kernels.workspace_arc.settle_xy_box`)."""
    n = stop - start
    lanes = min(LANES, n)
    for lane in numba.prange(lanes):
        for i in range(lane, n, lanes):
            row = start + i
            xlo = rows[row, 0]
            xhi = rows[row, 1]
            ylo = rows[row, 2]
            yhi = rows[row, 3]
            label = OUTSIDE
            if classify_rpr_box(xlo, xhi, ylo, yhi, p) != OUTSIDE:
                d_lo, d_hi = det_mean_value(xlo, xhi, ylo, yhi, p, offsets)
                if d_lo <= 0.0 <= d_hi:
                    label = BOUNDARY
            outcome[i] = settle_xy_box(label, rows, row, children, 2 * i, precision)

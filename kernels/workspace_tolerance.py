"""Tolerance-certified 3-RRR workspaces: the exact leg-wise test with interval parameters.

Every robot within the tolerances (per leg and independently: base joint
:math:`A_i + a`, :math:`|a_x|, |a_y| \\le t_A`; platform point :math:`q_i + b`,
:math:`|b_x|, |b_y| \\le t_q`; proximal :math:`l_1 + \\tau`, :math:`|\\tau| \\le t_1`;
distal :math:`l_2 + \\kappa`, :math:`|\\kappa| \\le t_2`) closes leg ``i`` at the platform
position :math:`v` iff :math:`D_{\\min} \\le l_2 + \\kappa \\le D_{\\max}` with
:math:`D(v) = \\mathrm{dist}(u + \\delta, \\mathrm{arc}(l_1 + \\tau))`,
:math:`u = v + R(\\varphi) q_i - A_i` and :math:`\\delta = R(\\varphi) b - a`
(:mod:`kernels.workspace_arc`). :math:`D_{\\min}` and :math:`D_{\\max}` are 1-Lipschitz in
the point and in :math:`l_1` (the arc point :math:`l_1 e(\\theta)` moves by
:math:`|\\tau|`), so over the parameter box they stay within :math:`\\sigma` of the
nominal values,

.. math:: \\sigma = \\sqrt2\\,(t_A + t_q) + t_1 \\;\\ge\\; |\\delta| + |\\tau|.

With :math:`c` the box centre, :math:`\\rho` its half-diagonal (plus the round-off margin
``TOLERANCE_CM``, which also absorbs the few float additions below) and :math:`d = D(c)` of the nominal robot, per leg:

* ``ALL`` (the robust workspace, :math:`\\forall\\pi\\,\\forall v \\in B`):
  **inside** if :math:`\\sqrt{d_{\\min}^2 + 2 d_{\\min} m_{near} + \\sigma^2} + \\rho
  \\le l_2 - t_2` and :math:`d_{\\max} - m_{far} - \\rho \\ge l_2 + t_2` for every leg
  (every point, every robot closes). With :math:`w = u - l_1 e(\\theta^*)` for the
  nominal nearest (farthest) arc angle :math:`\\theta^*`, :math:`n = w / |w|` and
  :math:`\\xi = \\delta - \\tau e(\\theta^*)`, a robot's distance to *its* arc point at
  :math:`\\theta^*` is :math:`|w + \\xi|`, with :math:`|w + \\xi|^2 = |w|^2 + 2 w \\cdot \\xi +
  |\\xi|^2 \\le d^2 + 2 d\\,m + \\sigma^2` (:math:`D_{\\min}` is at most that) and
  :math:`|w + \\xi| \\ge n \\cdot (w + \\xi) \\ge d - m` (:math:`D_{\\max}` is at least that),
  where :math:`m = \\max_\\pi n \\cdot \\xi = t_A \\|n\\|_1 + t_q \\|R^T n\\|_1 + t_1 |e
  \\cdot n|` (:func:`first_order_shift`, :math:`\\le \\sigma`); **outside** if some leg fails for one robot :math:`\\pi^*` within the
  tolerances: :math:`D_{\\min}(c; \\pi^*) - \\rho > l_2 - t_2` (:math:`\\pi^*` has the
  shortest distal) or :math:`D_{\\max}(c; \\pi^*) + \\rho < l_2 + t_2` (the longest): then
  every point of :math:`B` is missed by :math:`\\pi^*`, so by *some* robot.
* ``SOME`` (:math:`\\forall v \\in B\\,\\exists\\pi`): **outside** if for some leg
  :math:`d_{\\min} - \\rho - \\sigma > l_2 + t_2` or :math:`d_{\\max} + \\rho + \\sigma < l_2 -
  t_2` (no robot reaches any point); **inside** if one robot :math:`\\pi^*` (per leg, the
  legs' parameters are independent) reaches the whole box:
  :math:`D_{\\min}(c; \\pi^*) + \\rho \\le l_2^* \\le D_{\\max}(c; \\pi^*) - \\rho`.
* otherwise *boundary*.

The robot :math:`\\pi^*` of a leg is a vertex of its parameter box chosen at the box centre
(:func:`vertex_shift`): with :math:`n` the unit gradient of the binding distance
(:math:`(u - l_1 e(\\theta^*)) / D`, :math:`\\theta^*` the nearest or farthest arc angle)
it takes :math:`a = -t_A\\,\\mathrm{sgn}(n)`, :math:`b = t_q\\,\\mathrm{sgn}(R^T n)` and
:math:`\\tau = -t_1\\,\\mathrm{sgn}(e(\\theta^*) \\cdot n)` (times ``VERTEX_SHRINK`` so that
the float robot lies inside the tolerances): to first order it moves :math:`D` by
:math:`t_A \\|n\\|_1 + t_q \\|R^T n\\|_1 + t_1 |e \\cdot n|`. The choice is a heuristic; the
certificate is exact for whichever robot it picks, so it is sound whatever it picks.

Two shortcuts come first, each a special case of the above: a leg the Lipschitz bound
proves (``all``-inside, looser than the first-order one) skips the first-order bound; the
nominal robot with its distal at a vertex (``all``-outside) or as it is (``some``-inside)
is tried before the vertex robot.

At zero tolerance :math:`\\sigma = 0`, :math:`\\pi^*` is the nominal robot and every test is
:func:`kernels.workspace_arc.classify_box`'s: the same boxes.

The tolerance vector ``tol`` (``TOL_COLUMNS`` floats): ``mode`` (``NOMINAL``, ``ALL``,
``SOME``), :math:`t_A, t_q, t_1, t_2` (cm), :math:`\\cos\\varphi, \\sin\\varphi`.
"""

import math

import numba
import numpy as np

from ._jit import kernel
from .interval import up
from .workspace_arc import (
    BOUNDARY,
    INSIDE,
    LANES,
    OUTSIDE,
    TOLERANCE_CM,
    _on_arc,
    arc_distance_range,
    classify_box,
    grid_cell,
    refutable_leaf,
    settle_xy_box,
)

NOMINAL = 0
ALL = 1
SOME = 2
MODE, T_BASE, T_PLATFORM, T_PROXIMAL, T_DISTAL, COS_PHI, SIN_PHI = range(7)
TOL_COLUMNS = 7
#: The vertex robots use ``(1 - 1e-6)`` of each tolerance: their float parameters (a few
#: roundings of ~1e-14 cm) stay inside the tolerance box.
VERTEX_SHRINK = 1.0 - 1e-6


def tolerance_vector(mode, base_cm, platform_cm, proximal_cm, distal_cm, phi_rad):
    """Pack ``tol`` for the kernels (module docstring)."""
    tol = np.zeros(TOL_COLUMNS)
    tol[:5] = [mode, base_cm, platform_cm, proximal_cm, distal_cm]
    tol[COS_PHI] = math.cos(phi_rad)
    tol[SIN_PHI] = math.sin(phi_rad)
    return tol


@kernel
def shift_bound(tol):
    """:math:`\\sigma = \\sqrt2 (t_A + t_q) + t_1`, rounded up: the most a leg's
    :math:`D_{\\min}` or :math:`D_{\\max}` moves over the parameter box."""
    if tol[T_BASE] == 0.0 and tol[T_PLATFORM] == 0.0 and tol[T_PROXIMAL] == 0.0:
        return 0.0
    return up(up(up(math.sqrt(2.0)) * up(tol[T_BASE] + tol[T_PLATFORM])) + tol[T_PROXIMAL])


@kernel
def box_growth(tol):
    """Half-width by which an (x, y) box grows to enclose every robot's leg point for the
    interval forms: :math:`\\delta` and the proximal's :math:`\\tau e(\\theta)` (a vector of
    length :math:`\\le t_1`) move it by at most
    :math:`t_A + t_q(|\\cos\\varphi| + |\\sin\\varphi|) + t_1` per axis."""
    if tol[T_BASE] == 0.0 and tol[T_PLATFORM] == 0.0 and tol[T_PROXIMAL] == 0.0:
        return 0.0
    rotated = up(tol[T_PLATFORM] * up(abs(tol[COS_PHI]) + abs(tol[SIN_PHI])))
    return up(up(tol[T_BASE] + rotated) + tol[T_PROXIMAL])


@kernel
def distal_spread(l2, tol):
    """``(lo, hi)`` enclosing :math:`l_2^2 - (l_2 + \\kappa)^2` over :math:`|\\kappa| \\le t_2`
    (added to a leg's enclosure computed with the nominal :math:`l_2`):
    :math:`[-(2 l_2 t_2 + t_2^2),\\; 2 l_2 t_2]`."""
    t2 = tol[T_DISTAL]
    if t2 == 0.0:
        return 0.0, 0.0
    a = up(2.0 * l2 * t2)
    return -up(a + up(t2 * t2)), a


@kernel
def _sign(value):
    return 1.0 if value >= 0.0 else -1.0


@kernel
def extreme_angles(px, py, l1, tlo, thi):
    """Arc angles of the nearest and the farthest arc point from ``(px, py)`` (relative
    to the base joint): the point's direction :math:`\\alpha` (opposite, :math:`\\alpha + \\pi`)
    where it lies on the arc, else the nearer (farther) endpoint."""
    full = thi - tlo >= 2.0 * math.pi
    alpha = math.atan2(py, px)
    d_lo = math.hypot(px - l1 * math.cos(tlo), py - l1 * math.sin(tlo))
    d_hi = math.hypot(px - l1 * math.cos(thi), py - l1 * math.sin(thi))
    near = alpha if full or _on_arc(alpha, tlo, thi) else (tlo if d_lo <= d_hi else thi)
    far_angle = alpha + math.pi
    far = far_angle if full or _on_arc(far_angle, tlo, thi) else (tlo if d_lo > d_hi else thi)
    return near, far


@kernel
def unit_gradient(px, py, l1, angle):
    """:math:`n = (u - l_1 e) / |u - l_1 e|` (``(1, 0)`` at 0) and :math:`e = e(\\theta^*)`
    for the arc point at ``angle``: the gradient of :math:`D` in the point."""
    ex = math.cos(angle)
    ey = math.sin(angle)
    nx = px - l1 * ex
    ny = py - l1 * ey
    norm = math.hypot(nx, ny)
    if norm > 0.0:
        return nx / norm, ny / norm, ex, ey
    return 1.0, 0.0, ex, ey


@kernel
def first_order_shift(px, py, l1, angle, tol):
    """:math:`m = \\max_\\pi n \\cdot \\xi = t_A \\|n\\|_1 + t_q \\|R^T n\\|_1 + t_1 |e \\cdot n|`,
    :math:`\\xi = \\delta - \\tau e`: the most the distance to the arc point at ``angle``
    moves to first order over the tolerances (at most :math:`\\sigma`)."""
    nx, ny, ex, ey = unit_gradient(px, py, l1, angle)
    c = tol[COS_PHI]
    s = tol[SIN_PHI]
    rotated = abs(c * nx + s * ny) + abs(-s * nx + c * ny)
    return (
        tol[T_BASE] * (abs(nx) + abs(ny))
        + tol[T_PLATFORM] * rotated
        + tol[T_PROXIMAL] * abs(ex * nx + ey * ny)
    )


@kernel
def vertex_shift(px, py, l1, angle, direction, tol):
    """The vertex robot of a leg moving :math:`D = |u - l_1 e(\\theta^*)|` (``angle``
    :math:`\\theta^*`) up (``direction`` 1) or down (-1): returns the shift
    :math:`(\\delta_x, \\delta_y)` of the leg point and :math:`\\tau` of :math:`l_1`."""
    nx, ny, ex, ey = unit_gradient(px, py, l1, angle)
    nx *= direction
    ny *= direction
    t_a = VERTEX_SHRINK * tol[T_BASE]
    t_q = VERTEX_SHRINK * tol[T_PLATFORM]
    c = tol[COS_PHI]
    s = tol[SIN_PHI]
    bx = t_q * _sign(c * nx + s * ny)  # b = t_q sgn(R^T n)
    by = t_q * _sign(-s * nx + c * ny)
    dx = t_a * _sign(nx) + c * bx - s * by  # delta = -a + R b, a = -t_A sgn(n)
    dy = t_a * _sign(ny) + s * bx + c * by
    tau = -VERTEX_SHRINK * tol[T_PROXIMAL] * _sign(ex * nx + ey * ny)
    return dx, dy, tau


@kernel
def robust_range(px, py, l1, tlo, thi, dmin, dmax, sigma, tol):
    """Bounds over every robot at one point: an upper bound of :math:`D_{\\min}` and a
    lower bound of :math:`D_{\\max}` (module docstring, ``all``-inside)."""
    near, far = extreme_angles(px, py, l1, tlo, thi)
    m_near = first_order_shift(px, py, l1, near, tol)
    m_far = first_order_shift(px, py, l1, far, tol)
    return math.sqrt(dmin * dmin + 2.0 * dmin * m_near + sigma * sigma), dmax - m_far


@kernel
def vertex_range(px, py, l1, tlo, thi, angle, direction, tol):
    """``(D_min, D_max)`` of the vertex robot :func:`vertex_shift` picks."""
    dx, dy, tau = vertex_shift(px, py, l1, angle, direction, tol)
    return arc_distance_range(px + dx, py + dy, l1 + tau, tlo, thi)


@kernel
def _leg_refuted_by_vertex(px, py, l1, l2, tlo, thi, dmin, dmax, rho, sigma, tol):
    """``ALL`` mode: one vertex robot misses every point of the box (module docstring)."""
    t2 = VERTEX_SHRINK * tol[T_DISTAL]
    if dmin - rho > l2 - t2 or dmax + rho < l2 + t2:
        return True  # the nominal robot with its distal at a vertex already misses the box
    near, far = extreme_angles(px, py, l1, tlo, thi)
    if dmin - rho + sigma > l2 - t2:  # a robot may push D_min past its shortest distal
        vmin, _ = vertex_range(px, py, l1, tlo, thi, near, 1.0, tol)
        if vmin - rho > l2 - t2:
            return True
    if dmax + rho - sigma < l2 + t2:
        _, vmax = vertex_range(px, py, l1, tlo, thi, far, -1.0, tol)
        if vmax + rho < l2 + t2:
            return True
    return False


@kernel
def _leg_proved_by_vertex(px, py, l1, l2, tlo, thi, dmin, dmax, rho, tol):
    """``SOME`` mode: one vertex robot reaches every point of the box, relaxing the tighter
    of :math:`d_{\\min} \\le l_2` (longest distal) and :math:`l_2 \\le d_{\\max}` (shortest)."""
    t2 = VERTEX_SHRINK * tol[T_DISTAL]
    if dmin + rho <= l2 <= dmax - rho:
        return True  # the nominal robot reaches the whole box
    near, far = extreme_angles(px, py, l1, tlo, thi)
    if l2 - dmin <= dmax - l2:
        vmin, vmax = vertex_range(px, py, l1, tlo, thi, near, -1.0, tol)
        target = l2 + t2
    else:
        vmin, vmax = vertex_range(px, py, l1, tlo, thi, far, 1.0, tol)
        target = l2 - t2
    return vmin + rho <= target and vmax - rho >= target


@kernel
def tolerant_classify_box(xlo, xhi, ylo, yhi, p, limits, tol):
    """``OUTSIDE``, ``BOUNDARY`` or ``INSIDE`` of the (x, y) box for the mode in ``tol``
    (the certificates of the module docstring; ``NOMINAL``: ``classify_box``)."""
    mode = tol[MODE]
    if mode == NOMINAL:
        return classify_box(xlo, xhi, ylo, yhi, p, limits)
    cx = 0.5 * (xlo + xhi)
    cy = 0.5 * (ylo + yhi)
    rho = 0.5 * math.hypot(xhi - xlo, yhi - ylo) + TOLERANCE_CM
    sigma = shift_bound(tol)
    t2 = tol[T_DISTAL]
    l1 = p[0]
    l2 = p[1]
    inside = True
    for leg in range(3):
        px = cx + p[2 + 2 * leg]
        py = cy + p[3 + 2 * leg]
        tlo = limits[leg, 0]
        thi = limits[leg, 1]
        dmin, dmax = arc_distance_range(px, py, l1, tlo, thi)
        if mode == ALL:
            if dmin + rho + sigma <= l2 - t2 and dmax - rho - sigma >= l2 + t2:
                continue  # the Lipschitz bound (looser than robust_range's) proves the leg
            dmin_hi, dmax_lo = robust_range(px, py, l1, tlo, thi, dmin, dmax, sigma, tol)
            if dmin_hi + rho > l2 - t2 or dmax_lo - rho < l2 + t2:
                inside = False
                if _leg_refuted_by_vertex(px, py, l1, l2, tlo, thi, dmin, dmax, rho, sigma, tol):
                    return OUTSIDE
        else:
            if dmin - rho - sigma > l2 + t2 or dmax + rho + sigma < l2 - t2:
                return OUTSIDE
            if inside and not _leg_proved_by_vertex(px, py, l1, l2, tlo, thi, dmin, dmax, rho, tol):
                inside = False
    return INSIDE if inside else BOUNDARY


@kernel
def tolerant_refuted(xlo, xhi, ylo, yhi, p, limits, tol, n):
    """True if :func:`tolerant_classify_box` proves every cell of an ``n`` x ``n`` grid over
    the box ``OUTSIDE`` (then the box is: each cell's certificate covers it)."""
    for cell in range(n * n):
        x0, x1, y0, y1 = grid_cell(xlo, xhi, ylo, yhi, n, cell // n, cell % n)
        if tolerant_classify_box(x0, x1, y0, y1, p, limits, tol) != OUTSIDE:
            return False
    return True


@kernel(parallel=True)
def tolerant_arc_level(p, limits, tol, precision, leaf_grid, rows, start, stop, children, outcome):
    """:func:`kernels.workspace_arc.arc_level` with :func:`tolerant_classify_box` (and its
    leaf grid): rows ``start .. stop - 1`` in parallel, each box's outcome its own, so the
    result does not depend on the number of threads."""
    n = stop - start
    lanes = min(LANES, n)
    for lane in numba.prange(lanes):
        for i in range(lane, n, lanes):
            r = start + i
            box = (rows[r, 0], rows[r, 1], rows[r, 2], rows[r, 3])
            label = tolerant_classify_box(*box, p, limits, tol)
            if refutable_leaf(rows, r, label, precision, leaf_grid):
                label = OUTSIDE if tolerant_refuted(*box, p, limits, tol, leaf_grid) else label
            outcome[i] = settle_xy_box(label, rows, r, children, 2 * i, precision)

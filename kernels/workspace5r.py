"""Exact leg-wise test of the five-bar's workspace (one leg = a 3-RRR leg with
:math:`q_i = 0`) and its level-wise 2-D paving (:mod:`planar_tui.workspace.fivebar.robot`).

``legs`` has one row per leg ``ax, ay, l1, l2, sigma, bx_lo, by_lo, bx_hi, by_hi`` (cm;
``sigma`` the elbow sign of the working mode, 0 for any branch; ``b_lo``, ``b_hi`` the
elbow at the joint limits relative to ``A``), ``limits`` the (2, 2) joint limits in
radians.

**Any branch** (``sigma = 0``): leg ``i`` reaches ``P`` iff :math:`d_{\\min} \\le l_2 \\le
d_{\\max}`, the distances from :math:`P - A_i` to the proximal arc
(:func:`kernels.workspace_arc.arc_distance_range`, 1-Lipschitz): over a box of
half-diagonal :math:`\\rho` about :math:`c` the leg is *out* if :math:`d_{\\min}(c) - \\rho
> l_2` or :math:`d_{\\max}(c) + \\rho < l_2`, *in* if :math:`d_{\\min}(c) + \\rho \\le l_2
\\le d_{\\max}(c) - \\rho`.

**One branch** (``sigma = ±1``): the region :math:`R_\\sigma \\subseteq R` is closed and its
boundary lies on four arcs (module docstring of :mod:`planar_tui.workspace.fivebar.robot`). The
distance from a point to an arc is 1-Lipschitz (the :math:`d_{\\min}` of
:func:`arc_distance_range`): when the box's centre is farther than :math:`\\rho` from all
four arcs, the (connected) box misses :math:`\\partial R_\\sigma`, so it lies wholly inside
or wholly outside, as its centre does (:func:`mode_point_in`). A box *out* of
:math:`R` is out of :math:`R_\\sigma`.

``rho`` is enlarged by ``TOLERANCE_CM`` for the round-off of a few libm calls.
"""

import math

import numba

from ._jit import kernel
from .workspace_arc import (
    BOUNDARY,
    INSIDE,
    LANES,
    OUTSIDE,
    TOLERANCE_CM,
    _on_arc,
    arc_distance_range,
    settle_xy_box,
)


@kernel
def mode_angle(px, py, l1, l2, sigma):
    """:math:`\\theta = \\alpha + \\sigma\\beta` at ``p`` (relative to the base joint), or
    NaN where the leg cannot close."""
    r = math.hypot(px, py)
    if r == 0.0:
        return math.nan
    c = (r * r + l1 * l1 - l2 * l2) / (2.0 * l1 * r)
    if c > 1.0 or c < -1.0:
        return math.nan
    return math.atan2(py, px) + sigma * math.acos(c)


@kernel
def mode_point_in(px, py, l1, l2, tlo, thi, sigma):
    """True if the leg closes at ``p`` in the branch ``sigma`` within ``[tlo, thi]``."""
    theta = mode_angle(px, py, l1, l2, sigma)
    if math.isnan(theta):
        return False
    return thi - tlo >= 2.0 * math.pi or _on_arc(theta, tlo, thi)


@kernel
def near_arc(qx, qy, radius, start, stop, rho):
    """True if ``q`` (relative to the arc's centre) is within ``rho`` of the arc of
    ``radius`` over the angles ``[start, stop]``; the distance to the whole circle, a
    lower bound, settles most calls without trigonometry."""
    if abs(math.hypot(qx, qy) - radius) > rho:
        return False
    return arc_distance_range(qx, qy, radius, start, stop)[0] <= rho


@kernel
def circle_family_far(qx, qy, t_a, radius, spread, rho):
    """True if every circle of centre :math:`a` (:math:`|a_x|, |a_y| \\le t_a`, relative to
    the origin of ``q``) and radius in :math:`[\\max(0, r - s), r + s]` (``radius``,
    ``spread``) is farther than ``rho`` from ``q``: the distance from ``q`` to such a
    circle is :math:`||q - a| - r'|`, and :math:`|q - a|` lies between the distances from
    ``q`` to the nearest and farthest points of the square (exactly, per direction: the
    square's support :math:`t_a (|\\cos\\theta| + |\\sin\\theta|)` instead of
    :math:`\\sqrt2\\,t_a`)."""
    ux = abs(qx)
    uy = abs(qy)
    near = math.hypot(max(ux - t_a, 0.0), max(uy - t_a, 0.0))
    far = math.hypot(ux + t_a, uy + t_a)
    return near - (radius + spread) > rho or max(radius - spread, 0.0) - far > rho


@kernel
def near_family_arc(qx, qy, radius, start, stop, rho, h, t_a, spread):
    """:func:`near_arc` for every robot of a family: False (proved far) if the nominal arc
    is farther than ``rho + h`` (every robot's arc lies within ``h`` of it, point by point)
    or :func:`circle_family_far` (every robot's arc lies on one of those circles); with
    ``h = t_a = spread = 0``, :func:`near_arc` itself."""
    if not near_arc(qx, qy, radius, start, stop, rho + h):
        return False
    return not circle_family_far(qx, qy, t_a, radius, spread, rho)


@kernel
def near_mode_arcs(px, py, rho, l1, l2, sigma, b_lo_x, b_lo_y, b_hi_x, b_hi_y, tlo, thi, family):
    """True if ``p`` (relative to the base joint) is within ``rho`` of one of the four arcs
    holding the boundary of :math:`R_\\sigma` (module docstring) of a leg with links ``l1``,
    ``l2``, elbow sign ``sigma`` and elbows ``b_lo``, ``b_hi`` at the joint limits
    (relative to the base joint); ``family = (h, t_A, t_1 + t_2)`` asks it of every robot
    within the tolerances (:func:`near_family_arc`: the outer and inner arcs are circles of
    centre :math:`A + a` and radius :math:`|l_1 \\pm l_2|` moved by at most
    :math:`t_1 + t_2`; an elbow arc's centre :math:`A + a + (l_1 + \\tau) e(\\theta_\\pm)`
    is the nominal one moved by :math:`a` and by at most :math:`t_1`, which joins the
    radius's :math:`t_2`), ``(0, 0, 0)`` of the nominal robot."""
    h, t_a, spread = family
    if near_family_arc(px, py, l1 + l2, tlo, thi, rho, h, t_a, spread):
        return True
    shift = 0.0 if l1 >= l2 else math.pi
    inner = abs(l1 - l2)
    if near_family_arc(px, py, inner, tlo + shift, thi + shift, rho, h, t_a, spread):
        return True
    if thi - tlo >= 2.0 * math.pi:
        return False
    fold = -sigma * math.pi
    a0 = min(tlo, tlo + fold)
    qx, qy = px - b_lo_x, py - b_lo_y
    if near_family_arc(qx, qy, l2, a0, a0 + math.pi, rho, h, t_a, spread):
        return True
    a1 = min(thi, thi + fold)
    qx, qy = px - b_hi_x, py - b_hi_y
    return near_family_arc(qx, qy, l2, a1, a1 + math.pi, rho, h, t_a, spread)


@kernel
def near_mode_boundary(px, py, rho, legs, leg, tlo, thi):
    """:func:`near_mode_arcs` of leg ``leg`` (``legs[leg, 5:9]`` are the elbows
    :math:`B(\\underline\\theta) - A`, :math:`B(\\overline\\theta) - A`)."""
    return near_mode_arcs(
        px,
        py,
        rho,
        legs[leg, 2],
        legs[leg, 3],
        legs[leg, 4],
        legs[leg, 5],
        legs[leg, 6],
        legs[leg, 7],
        legs[leg, 8],
        tlo,
        thi,
        (0.0, 0.0, 0.0),
    )


@kernel
def leg_at(cx, cy, legs, limits, leg):
    """``(px, py, l1, l2, tlo, thi)``: the point relative to leg ``leg``'s base joint, its
    link lengths and joint limits."""
    px = cx - legs[leg, 0]
    return px, cy - legs[leg, 1], legs[leg, 2], legs[leg, 3], limits[leg, 0], limits[leg, 1]


@kernel
def leg_label(cx, cy, rho, legs, limits, leg):
    """``OUTSIDE``, ``BOUNDARY`` or ``INSIDE`` for one leg over the box about ``(cx, cy)``
    of half-diagonal ``rho`` (module docstring)."""
    px, py, l1, l2, tlo, thi = leg_at(cx, cy, legs, limits, leg)
    sigma = legs[leg, 4]
    dmin, dmax = arc_distance_range(px, py, l1, tlo, thi)
    if dmin - rho > l2 or dmax + rho < l2:
        return OUTSIDE
    if sigma == 0.0:
        return INSIDE if (dmin + rho <= l2 and dmax - rho >= l2) else BOUNDARY
    if near_mode_boundary(px, py, rho, legs, leg, tlo, thi):
        return BOUNDARY
    return INSIDE if mode_point_in(px, py, l1, l2, tlo, thi, sigma) else OUTSIDE


@kernel
def classify_box(xlo, xhi, ylo, yhi, legs, limits):
    """``OUTSIDE`` (some leg out), ``INSIDE`` (both in) or ``BOUNDARY`` for the box."""
    cx = 0.5 * (xlo + xhi)
    cy = 0.5 * (ylo + yhi)
    rho = 0.5 * math.hypot(xhi - xlo, yhi - ylo) + TOLERANCE_CM
    first = leg_label(cx, cy, rho, legs, limits, 0)
    if first == OUTSIDE:
        return OUTSIDE
    second = leg_label(cx, cy, rho, legs, limits, 1)
    return min(first, second)


@kernel
def point_in(x, y, legs, limits):
    """Exact test at one point (a box of half-diagonal 0): both legs close within their
    limits (and modes); the boundary belongs to the workspace (a closed set)."""
    first = leg_label(x, y, 0.0, legs, limits, 0)
    return first != OUTSIDE and leg_label(x, y, 0.0, legs, limits, 1) != OUTSIDE


@kernel
def decide_row(legs, limits, precision, rows, row, children, c):
    """:func:`classify_box` of ``rows[row]`` then
    :func:`kernels.workspace_arc.settle_xy_box` into ``children[c]`` (and ``c + 1``)."""
    label = classify_box(rows[row, 0], rows[row, 1], rows[row, 2], rows[row, 3], legs, limits)
    return settle_xy_box(label, rows, row, children, c, precision)


@kernel(parallel=True)
def level(legs, limits, precision, rows, start, stop, children, outcome):
    """Decide rows ``start .. stop - 1`` of a frontier of (x, y) boxes in parallel by
    :func:`decide_row` (row ``start + i`` writes ``children[2 i]``, ``children[2 i + 1]``,
    ``outcome[i]``); each box's outcome depends on that box only, whatever the number of
    threads."""
    n = stop - start
    lanes = min(LANES, n)
    for lane in numba.prange(lanes):
        for i in range(lane, n, lanes):
            outcome[i] = decide_row(legs, limits, precision, rows, start + i, children, 2 * i)

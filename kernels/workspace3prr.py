"""Exact leg test of a 3-PRR at a fixed orientation and its level-wise 2-D paving.

Leg ``i``: an actuated slider at :math:`B_i + s u_i`, :math:`s \\in [\\underline s_i,
\\overline s_i]` on a base line (:math:`|u_i| = 1`), a revolute joint, a distal link of
length :math:`l_i`, a revolute joint at the platform point :math:`C_i = p + R(\\varphi) q_i`.
The leg closes iff :math:`|C_i - B_i - s u_i| = l_i` for some stroke :math:`s`. The function
:math:`g(s) = |C_i - B_i - s u_i|` is continuous and convex on the segment
:math:`S_i = \\{B_i + s u_i\\}` (endpoints :math:`E_0, E_1`), so its range is
:math:`[d_{seg}(C_i), \\max(|C_i - E_0|, |C_i - E_1|)]` (the minimum is the distance to the
segment, the maximum of a convex function on a segment is at an endpoint). Hence

.. math:: d_{seg}(C_i) \\le l_i \\le d_{end}(C_i) = \\max(|C_i - E_0|, |C_i - E_1|),

i.e. :math:`C_i` lies in the stadium :math:`S_i \\oplus D(0, l_i)` (the Minkowski sum of the
segment and the disc) but not in the open lens :math:`D^\\circ(E_0, l_i) \\cap
D^\\circ(E_1, l_i)`; the union of the circles of radius :math:`l_i` centred on the segment.
With :math:`E'_k = E_k - R(\\varphi) q_i` the test reads the same on the platform position
:math:`p` (``p`` of the kernels holds the shifted endpoints).

Over an (x, y) box, per leg (each bound certified, ``TOLERANCE_CM`` absorbing round-off):

* :math:`\\max_{box} d_{seg}` and :math:`\\max_{box} d_{end}` are at a corner (convex
  functions): exact;
* :math:`\\min_{box} d_{end} \\ge \\max_k \\min_{box} |p - E'_k|` (the distance from a point to
  a box, exact);
* :math:`\\min_{box} d_{seg} \\ge d_{seg}(c) - \\rho` (1-Lipschitz; :math:`c` the centre,
  :math:`\\rho` the half-diagonal).

A box is ``OUTSIDE`` if some leg has :math:`\\min d_{seg} > l` or :math:`\\max d_{end} < l`,
``INSIDE`` if every leg has :math:`\\max d_{seg} \\le l \\le \\min d_{end}`, else ``BOUNDARY``;
a boundary leaf whose ``leaf_grid`` × ``leaf_grid`` cells are all outside is dropped. The
paving is the arc-distance form's: outcomes per box, thread-count independent.

``p`` is (3, 9): per leg ``E'0x, E'0y, E'1x, E'1y, l`` (cm), then the thresholds the labels
compare with in place of :math:`l`: ``out_seg`` (``OUTSIDE`` if :math:`\\min d_{seg} >`
it), ``out_end`` (if :math:`\\max d_{end} <` it), ``in_seg`` (``INSIDE`` needs
:math:`\\max d_{seg} \\le` it), ``in_end`` (and :math:`\\min d_{end} \\ge` it). All four are
:math:`l` for the nominal robot; a tolerance-certified job moves them
(:func:`planar_tui.workspace.prr.tolerance.leg_thresholds`).
"""

import math

import numba

from ._jit import kernel
from .workspace_arc import BOUNDARY, INSIDE, LANES, OUTSIDE, TOLERANCE_CM, settle_xy_box


@kernel
def segment_distance(x, y, ax, ay, bx, by):
    """Distance from ``(x, y)`` to the segment from ``(ax, ay)`` to ``(bx, by)``."""
    dx = bx - ax
    dy = by - ay
    length2 = dx * dx + dy * dy
    t = 0.0 if length2 == 0.0 else ((x - ax) * dx + (y - ay) * dy) / length2
    t = min(1.0, max(0.0, t))
    return math.hypot(x - ax - t * dx, y - ay - t * dy)


@kernel
def end_distance(x, y, ax, ay, bx, by):
    """:math:`d_{end}`: the larger distance from ``(x, y)`` to the segment's endpoints."""
    return max(math.hypot(x - ax, y - ay), math.hypot(x - bx, y - by))


@kernel
def _box_distance(xlo, xhi, ylo, yhi, x, y):
    """Distance from the point ``(x, y)`` to the box (0 inside)."""
    dx = max(xlo - x, 0.0, x - xhi)
    dy = max(ylo - y, 0.0, y - yhi)
    return math.hypot(dx, dy)


@kernel
def prr_leg_label(xlo, xhi, ylo, yhi, ax, ay, bx, by, out_seg, out_end, in_seg, in_end):
    """One leg's ``OUTSIDE``, ``BOUNDARY`` or ``INSIDE`` over the box, its shifted stroke
    ends ``(ax, ay)``, ``(bx, by)`` and its four thresholds (module docstring)."""
    cx = 0.5 * (xlo + xhi)
    cy = 0.5 * (ylo + yhi)
    rho = 0.5 * math.hypot(xhi - xlo, yhi - ylo)
    seg_min = segment_distance(cx, cy, ax, ay, bx, by) - rho
    seg_max = 0.0
    end_max = 0.0
    for x in (xlo, xhi):
        for y in (ylo, yhi):
            seg_max = max(seg_max, segment_distance(x, y, ax, ay, bx, by))
            end_max = max(end_max, end_distance(x, y, ax, ay, bx, by))
    end_min = max(
        _box_distance(xlo, xhi, ylo, yhi, ax, ay), _box_distance(xlo, xhi, ylo, yhi, bx, by)
    )
    if seg_min - TOLERANCE_CM > out_seg or end_max + TOLERANCE_CM < out_end:
        return OUTSIDE
    if seg_max + TOLERANCE_CM > in_seg or end_min - TOLERANCE_CM < in_end:
        return BOUNDARY
    return INSIDE


@kernel
def classify_prr_box(xlo, xhi, ylo, yhi, p):
    """``OUTSIDE``, ``BOUNDARY`` or ``INSIDE`` for the (x, y) box (module docstring)."""
    inside = True
    for leg in range(3):
        label = prr_leg_label(
            xlo,
            xhi,
            ylo,
            yhi,
            p[leg, 0],
            p[leg, 1],
            p[leg, 2],
            p[leg, 3],
            p[leg, 5],
            p[leg, 6],
            p[leg, 7],
            p[leg, 8],
        )
        if label == OUTSIDE:
            return OUTSIDE
        inside = inside and label == INSIDE
    return INSIDE if inside else BOUNDARY


@kernel
def prr_point_feasible(x, y, p):
    """Every leg closes at the platform position ``(x, y)`` (float test, for references)."""
    for leg in range(3):
        ax, ay, bx, by, length = p[leg, 0], p[leg, 1], p[leg, 2], p[leg, 3], p[leg, 4]
        if segment_distance(x, y, ax, ay, bx, by) > length:
            return False
        if end_distance(x, y, ax, ay, bx, by) < length:
            return False
    return True


@kernel
def grid_cell(xlo, xhi, ylo, yhi, n, k):
    """Cell ``k`` (row-major, ``k = n i + j``) of an ``n`` x ``n`` grid over the box."""
    i = k // n
    j = k % n
    hx = (xhi - xlo) / n
    hy = (yhi - ylo) / n
    x0 = xlo + i * hx
    x1 = xhi if i == n - 1 else xlo + (i + 1) * hx
    y0 = ylo + j * hy
    y1 = yhi if j == n - 1 else ylo + (j + 1) * hy
    return x0, x1, y0, y1


@kernel
def _refuted(xlo, xhi, ylo, yhi, p, n):
    """True if each cell of an ``n`` x ``n`` grid over the box is ``OUTSIDE``."""
    for k in range(n * n):
        x0, x1, y0, y1 = grid_cell(xlo, xhi, ylo, yhi, n, k)
        if classify_prr_box(x0, x1, y0, y1, p) != OUTSIDE:
            return False
    return True


#: Leaf check: a boundary leaf whose LEAF_GRID x LEAF_GRID cells are all outside is dropped.
LEAF_GRID = 4


@kernel(parallel=True)
def prr_level(p, precision, rows, start, stop, children, outcome):
    """Decide rows ``start .. stop - 1`` of a frontier of (x, y) boxes in parallel: label
    (:func:`classify_prr_box`, a boundary leaf refuted on a ``LEAF_GRID`` grid), then
    :func:`~kernels.workspace_arc.settle_xy_box`; row ``start + i`` writes
    ``children[2 i]``, ``children[2 i + 1]`` and ``outcome[i]``."""
    n = stop - start
    lanes = min(LANES, n)
    for lane in numba.prange(lanes):
        for i in range(lane, n, lanes):
            r = start + i
            xlo = rows[r, 0]
            xhi = rows[r, 1]
            ylo = rows[r, 2]
            yhi = rows[r, 3]
            label = classify_prr_box(xlo, xhi, ylo, yhi, p)
            leaf = xhi - xlo <= precision and yhi - ylo <= precision
            if leaf and label == BOUNDARY and _refuted(xlo, xhi, ylo, yhi, p, LEAF_GRID):
                label = OUTSIDE
            outcome[i] = settle_xy_box(label, rows, r, children, 2 * i, precision)

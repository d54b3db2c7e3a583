"""Exact leg-wise feasibility of a 3-RRR (the ``arc-distance`` form) and its 2-D paving.

Eliminating the active angle exactly: leg ``i`` closes at the platform point :math:`C_i` for
some :math:`\\theta_i \\in [\\underline\\theta_i, \\overline\\theta_i]` iff the distance from
:math:`C_i` to the arc :math:`B_i(\\theta) = A_i + l_1(\\cos\\theta, \\sin\\theta)` brackets
:math:`l_2`:

.. math:: d_{\\min,i}(C_i) \\le l_2 \\le d_{\\max,i}(C_i),

because :math:`\\theta \\mapsto |C_i - B_i(\\theta)|` is continuous on a connected arc. With
:math:`p = C_i - A_i = r(\\cos\\alpha, \\sin\\alpha)`, the distance to the circle point at
angle :math:`t` grows with the angular separation :math:`|t - \\alpha| \\in [0, \\pi]`, so
:math:`d_{\\min} = |r - l_1|` if :math:`\\alpha` lies on the arc, else the nearer endpoint, and
:math:`d_{\\max} = r + l_1` if :math:`\\alpha + \\pi` lies on the arc, else the farther endpoint.

Both functions are 1-Lipschitz in :math:`C_i`, so over an (x, y) box of half-diagonal
:math:`\\rho` about its centre :math:`c` they lie within :math:`d(c) \\pm \\rho`: a box is
*outside* if some leg has :math:`d_{\\min}(c) - \\rho > l_2` or
:math:`d_{\\max}(c) + \\rho < l_2`, *inside* if every leg has
:math:`d_{\\min}(c) + \\rho \\le l_2 \\le d_{\\max}(c) - \\rho`, else *boundary*. ``rho`` is
enlarged by ``TOLERANCE_CM`` to absorb the round-off of a few libm calls (|error| < 1e-12 cm
for coordinates below 1e3 cm).

The 2-D paving is breadth-first: :func:`arc_level` decides a slice of a frontier of (x, y)
boxes in parallel (``prange``) and the caller appends the kept boxes and the halves in
frontier order, so the boxes, their order and the areas do not depend on the number of
threads.
"""

import math

import numba
import numpy as np

from ._jit import kernel
from .workspace3rrr import split_xy_widest

OUTSIDE = 0
BOUNDARY = 1
INSIDE = 2
#: Outcome of a box in a paving level beside the labels: halved into two children.
SPLIT = 3

#: Parallel lanes of the level-wise pavings: box i goes to lane i % LANES (interleaved, so
#: that neighbouring boxes of similar cost are spread over the threads).
LANES = 64

TOLERANCE_CM = 1e-9


@kernel
def _on_arc(angle, tlo, thi):
    """True if ``angle`` (mod 2 pi) lies in ``[tlo, thi]`` (``thi - tlo < 2 pi``)."""
    two_pi = 2.0 * math.pi
    shifted = tlo + ((angle - tlo) % two_pi)
    return shifted <= thi


@kernel
def arc_distance_range(px, py, l1, tlo, thi):
    """``(d_min, d_max)`` from the point ``p`` (relative to the base joint) to the arc."""
    if thi - tlo >= 2.0 * math.pi:
        r = math.hypot(px, py)
        return abs(r - l1), r + l1
    r = math.hypot(px, py)
    d_lo = math.hypot(px - l1 * math.cos(tlo), py - l1 * math.sin(tlo))
    d_hi = math.hypot(px - l1 * math.cos(thi), py - l1 * math.sin(thi))
    if r == 0.0:
        return l1, l1
    alpha = math.atan2(py, px)
    dmin = abs(r - l1) if _on_arc(alpha, tlo, thi) else min(d_lo, d_hi)
    dmax = r + l1 if _on_arc(alpha + math.pi, tlo, thi) else max(d_lo, d_hi)
    return dmin, dmax


@kernel
def point_feasible(x, y, p, limits):
    """Exact test at one platform position: every leg closes within its joint limits."""
    for leg in range(3):
        dmin, dmax = arc_distance_range(
            x + p[2 + 2 * leg], y + p[3 + 2 * leg], p[0], limits[leg, 0], limits[leg, 1]
        )
        if dmin > p[1] or dmax < p[1]:
            return False
    return True


@kernel
def classify_box(xlo, xhi, ylo, yhi, p, limits):
    """``OUTSIDE``, ``BOUNDARY`` or ``INSIDE`` for the (x, y) box (module docstring)."""
    cx = 0.5 * (xlo + xhi)
    cy = 0.5 * (ylo + yhi)
    rho = 0.5 * math.hypot(xhi - xlo, yhi - ylo) + TOLERANCE_CM
    l2 = p[1]
    inside = True
    for leg in range(3):
        dmin, dmax = arc_distance_range(
            cx + p[2 + 2 * leg], cy + p[3 + 2 * leg], p[0], limits[leg, 0], limits[leg, 1]
        )
        if dmin - rho > l2 or dmax + rho < l2:
            return OUTSIDE
        if dmin + rho > l2 or dmax - rho < l2:
            inside = False
    return INSIDE if inside else BOUNDARY


@kernel
def grid_cell(xlo, xhi, ylo, yhi, n, i, j):
    """Cell ``(i, j)`` ``(x0, x1, y0, y1)`` of an ``n`` x ``n`` grid over the box (the last
    row and column end exactly on the box's edges)."""
    hx = (xhi - xlo) / n
    hy = (yhi - ylo) / n
    x1 = xhi if i == n - 1 else xlo + (i + 1) * hx
    y1 = yhi if j == n - 1 else ylo + (j + 1) * hy
    return xlo + i * hx, x1, ylo + j * hy, y1


@kernel
def refuted(xlo, xhi, ylo, yhi, p, limits, n):
    """True if each cell of an ``n`` x ``n`` grid over the box is ``OUTSIDE`` (so is the box)."""
    for i in range(n):
        for j in range(n):
            x0, x1, y0, y1 = grid_cell(xlo, xhi, ylo, yhi, n, i, j)
            if classify_box(x0, x1, y0, y1, p, limits) != OUTSIDE:
                return False
    return True


@kernel
def refutable_leaf(rows, r, label, precision, leaf_grid):
    """Row ``r`` is a ``BOUNDARY`` leaf (both widths :math:`\\le \\varepsilon`) that a
    ``leaf_grid`` x ``leaf_grid`` grid may prove outside (0: no such check)."""
    leaf = rows[r, 1] - rows[r, 0] <= precision and rows[r, 3] - rows[r, 2] <= precision
    return leaf and label == BOUNDARY and leaf_grid > 0


@kernel
def classify_boxes(boxes, p, limits, out):
    """:func:`classify_box` for every row ``x_lo, x_hi, y_lo, y_hi`` of ``boxes``."""
    for r in range(boxes.shape[0]):
        out[r] = classify_box(boxes[r, 0], boxes[r, 1], boxes[r, 2], boxes[r, 3], p, limits)


@kernel
def points_feasible(xs, ys, p, limits, out):
    """:func:`point_feasible` for every point."""
    for r in range(xs.shape[0]):
        out[r] = point_feasible(xs[r], ys[r], p, limits)


@kernel
def settle_xy_box(label, rows, r, children, c, precision):
    """The step after a box's label in the level-wise 2-D pavings (arc-distance,
    orientation range): copy row ``r`` of ``rows`` (``x_lo, x_hi, y_lo, y_hi``) to
    ``children[c]``; an ``OUTSIDE`` box is dropped, an ``INSIDE`` box is kept (never split),
    a box with both widths :math:`\\le \\varepsilon` is kept with its label, any other
    is halved across its wider side (``children[c]`` and ``children[c + 1]``). Returns
    ``OUTSIDE``, ``BOUNDARY``, ``INSIDE`` (kept with that label) or ``SPLIT``."""
    for j in range(4):
        children[c, j] = rows[r, j]
    if label == OUTSIDE:
        return OUTSIDE
    leaf = rows[r, 1] - rows[r, 0] <= precision and rows[r, 3] - rows[r, 2] <= precision
    if label == INSIDE or leaf:
        return label
    split_xy_widest(children, c, c + 1, np.int64(4))  # np.int64: one signature for every paving
    return SPLIT


@kernel(parallel=True)
def arc_level(p, limits, precision, leaf_grid, rows, start, stop, children, outcome):
    """Decide rows ``start .. stop - 1`` of a frontier of (x, y) boxes with the exact
    leg-wise test, in parallel: a box is labelled by :func:`classify_box`; a ``BOUNDARY``
    leaf (both widths :math:`\\le \\varepsilon`) whose ``leaf_grid`` x ``leaf_grid``
    cells are all ``OUTSIDE`` is dropped (0: no such check); then
    :func:`settle_xy_box`. Row ``start + i`` writes ``children[2 i]``, ``children[2 i + 1]``
    and ``outcome[i]``. Each box's outcome depends on that box only, so the result does
    not depend on the number of threads (boxes go to ``LANES`` interleaved lanes)."""
    n = stop - start
    lanes = min(LANES, n)
    for lane in numba.prange(lanes):
        for i in range(lane, n, lanes):
            r = start + i
            xlo = rows[r, 0]
            xhi = rows[r, 1]
            ylo = rows[r, 2]
            yhi = rows[r, 3]
            label = classify_box(xlo, xhi, ylo, yhi, p, limits)
            if refutable_leaf(rows, r, label, precision, leaf_grid) and refuted(
                xlo, xhi, ylo, yhi, p, limits, leaf_grid
            ):
                label = OUTSIDE
            outcome[i] = settle_xy_box(label, rows, r, children, 2 * i, precision)


def limits_array(limits_rad):
    """Joint limits as a contiguous (3, 2) float64 array (radians)."""
    return np.ascontiguousarray(np.asarray(limits_rad, dtype=np.float64).reshape(3, 2))

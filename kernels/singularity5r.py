"""Singularities and the singularity-free circle of a five-bar, by interval analysis.

With the distal links :math:`u_i = P - B_i` the loop equations
:math:`|P - B_i(\\theta_i)|^2 = l_{2,i}^2` differentiate to :math:`A\\,\\dot P = B\\,
\\dot\\theta` with :math:`A = [u_1^T; u_2^T]` and :math:`B = \\mathrm{diag}(l_{1,i}\\, u_i
\\times e_i)` (:math:`e_i = (\\cos\\theta_i, \\sin\\theta_i)`, :math:`a \\times b = a_x b_y
- a_y b_x`):

* **type I** (serial): :math:`u_i \\times e_i = 0`, leg ``i`` extended or folded,
  :math:`|P - A_i| = l_{1,i} \\pm l_{2,i}`;
* **type II** (parallel): :math:`\\det A = u_1 \\times u_2 = 0`, the distal links aligned.

A leg of the five-bar is a 3-RRR leg with the platform a point (:math:`r_i = 0`), so
:func:`kernels.singularity3rrr.leg_status` encloses :math:`u_i` over an (x, y) box in one
working mode (``elbow``) with the joint limits (the points of the box in the mode's
workspace :math:`W_s`); the geometry vector ``g`` has one row per leg (the 3-RRR's layout:
``l1, l2`` then ``A_i`` at ``8 + 2 i``).

**Singular paving** (:func:`singular_level`): a box is dropped when the five-bar's exact
test (:func:`kernels.workspace5r.classify_box`) proves it outside the workspace, or when it
holds no point of either kind: no base-centred circle :math:`|P - A_i| = l_1 \\pm l_2`
meets it and in every mode of ``modes`` some leg is *out* or the :math:`\\det A` enclosure
excludes 0; else it is halved down to ``precision`` and kept. Every singular point of the
workspace lies in a kept leaf.

**Circle** (:func:`circle_level`) about a centre :math:`c` in :math:`W_s` with
:math:`\\det A(c) \\ne 0`, in one mode: :math:`r^*` is the distance from :math:`c` to the
bad set (outside :math:`W_s`, or type II; type I points lie on :math:`\\partial W_s`).
Boxes farther than ``reach`` from :math:`c` are dropped; a box *out* is kept whole (all
bad); a box with both legs *in* and det excluding 0 is kept as ``INSIDE`` (no bad point);
the rest is halved down to ``precision`` and kept. So every bad point within ``reach`` lies
in a kept non-``INSIDE`` box: :math:`r_{in} = \\min(reach, \\text{their distances})
\\le r^*`. Witnesses give :math:`r_{out}`: an *out* box's distance, and a leaf's centre
proved out or with det of the sign opposite to :math:`\\det A(c)` (det is continuous on
the segment inside :math:`W_s`).
"""

import math

import numba
import numpy as np

from ._jit import kernel
from .interval import imul, isub, up
from .singularity3rrr import LEG_IN, LEG_OUT, LEG_UNDEFINED, box_distance, leg_status
from .workspace5r import classify_box
from .workspace_arc import BOUNDARY, INSIDE, LANES, OUTSIDE, TOLERANCE_CM, settle_xy_box

#: Kinds of a kept singular leaf (bits).
TYPE_I = 1
TYPE_II = 2


@kernel
def mode_status(xlo, xhi, ylo, yhi, g, r, elbow, limits):
    """``(in_w, out_w, det_lo, det_hi)`` over the box in the mode ``elbow``: both legs
    *in*, some leg *out*, and an enclosure of :math:`u_1 \\times u_2` over its points in
    :math:`W_s` (unbounded when a box may hold a base joint)."""
    # np.int64: a literal leg made numba compile leg_status once per leg
    v0, ax0, bx0, ay0, by0, _, _ = leg_status(
        xlo, xhi, ylo, yhi, np.int64(0), g[0], r, elbow, limits
    )
    v1, ax1, bx1, ay1, by1, _, _ = leg_status(
        xlo, xhi, ylo, yhi, np.int64(1), g[1], r, elbow, limits
    )
    if v0 == LEG_OUT or v1 == LEG_OUT:
        return False, True, -math.inf, math.inf
    if v0 == LEG_UNDEFINED or v1 == LEG_UNDEFINED:
        return False, False, -math.inf, math.inf
    d_lo, d_hi = isub(*imul(ax0, bx0, ay1, by1), *imul(ay0, by0, ax1, bx1))
    return v0 == LEG_IN and v1 == LEG_IN, False, d_lo, d_hi


@kernel
def type1_possible(xlo, xhi, ylo, yhi, legs):
    """True if a circle :math:`|P - A_i| = l_1 \\pm l_2` may meet the box."""
    for leg in range(2):
        ax = legs[leg, 0]
        ay = legs[leg, 1]
        near = math.hypot(max(xlo - ax, 0.0, ax - xhi), max(ylo - ay, 0.0, ay - yhi))
        far = math.hypot(max(ax - xlo, xhi - ax), max(ay - ylo, yhi - ay))
        for radius in (legs[leg, 2] + legs[leg, 3], abs(legs[leg, 2] - legs[leg, 3])):
            if near - TOLERANCE_CM <= radius <= far + TOLERANCE_CM:
                return True
    return False


@kernel
def singular_kinds(xlo, xhi, ylo, yhi, g, r, modes, limits, legs):
    """``TYPE_I | TYPE_II`` bits of what the box may hold (0: no singular point of the
    workspace; module docstring)."""
    if classify_box(xlo, xhi, ylo, yhi, legs, limits) == OUTSIDE:
        return 0
    kinds = TYPE_I if type1_possible(xlo, xhi, ylo, yhi, legs) else 0
    for m in range(modes.shape[0]):
        _, out_w, d_lo, d_hi = mode_status(xlo, xhi, ylo, yhi, g, r, modes[m], limits)
        if not out_w and d_lo <= 0.0 <= d_hi:
            return kinds | TYPE_II
    return kinds


@kernel(parallel=True)
def singular_level(g, r, modes, limits, legs, precision, rows, start, stop, children, outcome):
    """One slice of the singular paving (module docstring), as
    :func:`kernels.workspace5r.level`: dropped, halved, or kept as ``BOUNDARY`` leaves."""
    n = stop - start
    lanes = min(LANES, n)
    for lane in numba.prange(lanes):
        for i in range(lane, n, lanes):
            row = start + i
            kinds = singular_kinds(
                rows[row, 0], rows[row, 1], rows[row, 2], rows[row, 3], g, r, modes, limits, legs
            )
            label = OUTSIDE if kinds == 0 else BOUNDARY
            outcome[i] = settle_xy_box(label, rows, row, children, 2 * i, precision)


@kernel
def tag_kinds(boxes, g, r, modes, limits, legs, out):
    """:func:`singular_kinds` of every kept leaf."""
    for row in range(boxes.shape[0]):
        out[row] = singular_kinds(
            boxes[row, 0], boxes[row, 1], boxes[row, 2], boxes[row, 3], g, r, modes, limits, legs
        )


@kernel
def circle_box(rows, row, g, r, elbow, limits, cx, cy, sign, reach, precision, children, c):
    """``(outcome, witness)`` of one box of the circle paving (module docstring)."""
    xlo = rows[row, 0]
    xhi = rows[row, 1]
    ylo = rows[row, 2]
    yhi = rows[row, 3]
    distance = box_distance(xlo, xhi, ylo, yhi, cx, cy)
    if distance > reach:
        return OUTSIDE, math.inf
    in_w, out_w, d_lo, d_hi = mode_status(xlo, xhi, ylo, yhi, g, r, elbow, limits)
    if out_w:
        for j in range(4):
            children[c, j] = rows[row, j]
        return BOUNDARY, distance
    good = in_w and (d_lo > 0.0 or d_hi < 0.0)
    code = settle_xy_box(INSIDE if good else BOUNDARY, rows, row, children, c, precision)
    if code != BOUNDARY:
        return code, math.inf
    qx = 0.5 * (xlo + xhi)
    qy = 0.5 * (ylo + yhi)
    q_in, q_out, q_lo, q_hi = mode_status(qx, qx, qy, qy, g, r, elbow, limits)
    flips = (sign > 0.0 and q_hi < 0.0) or (sign < 0.0 and q_lo > 0.0)
    if q_out or (q_in and flips):
        return code, up(math.hypot(qx - cx, qy - cy))
    return code, math.inf


@kernel(parallel=True)
def circle_level(
    g,
    r,
    elbow,
    limits,
    cx,
    cy,
    sign,
    reach,
    precision,
    rows,
    start,
    stop,
    children,
    outcome,
    witness,
):
    """One slice of the circle paving: ``outcome[i]`` and ``witness[i]`` (an upper bound of
    :math:`r^*`, ``inf`` without one) of row ``start + i``."""
    n = stop - start
    lanes = min(LANES, n)
    for lane in numba.prange(lanes):
        for i in range(lane, n, lanes):
            outcome[i], witness[i] = circle_box(
                rows,
                start + i,
                g,
                r,
                elbow,
                limits,
                cx,
                cy,
                sign,
                reach,
                precision,
                children,
                2 * i,
            )

"""Orientation workspaces of a 3-RRR: the platform orientation ranges over an interval.

For a platform position :math:`p = (x, y)` and orientation :math:`\\varphi`, leg ``i``'s
platform point relative to its base joint is :math:`v_i(p, \\varphi) = p + R(\\varphi) q_i -
A_i`, and the leg closes within its joint limits iff
:math:`d_{\\min,i}(v_i) \\le l_2 \\le d_{\\max,i}(v_i)` (the exact leg-wise test of
:mod:`kernels.workspace_arc`; both distances are 1-Lipschitz in :math:`v_i`). With
:math:`\\Phi = [\\varphi_{lo}, \\varphi_{hi}]`:

* the **maximal** workspace :math:`W_\\exists = \\{p : \\exists \\varphi \\in \\Phi,\\ p \\in
  W(\\varphi)\\}`,
* the **total orientation** workspace :math:`W_\\forall = \\{p : \\forall \\varphi \\in \\Phi,\\
  p \\in W(\\varphi)\\}`.

**Enclosure over a box and a piece of** :math:`\\Phi`. For an (x, y) box :math:`X` with centre
:math:`c` and half-diagonal :math:`\\rho_{xy}`, and a piece :math:`[m - h, m + h]` of
:math:`\\Phi`: for every :math:`p \\in X`, :math:`|\\varphi - m| \\le h`,

.. math:: |v_i(p, \\varphi) - v_i(c, m)| \\le |p - c| + |R(\\varphi) q_i - R(m) q_i|
          \\le \\rho_{xy} + 2 |q_i| \\sin(h / 2) =: \\rho_i

(the chord of an arc of angle :math:`|\\varphi - m| \\le h \\le \\pi` on the circle of radius
:math:`|q_i|`). By the Lipschitz property, over the whole set
:math:`X \\times [m - h, m + h]` leg ``i`` is

* ``IN`` (closes everywhere) if :math:`d_{\\min}(v_i(c, m)) + \\rho_i \\le l_2 \\le
  d_{\\max}(v_i(c, m)) - \\rho_i`,
* ``OUT`` (fails everywhere) if :math:`d_{\\min} - \\rho_i > l_2` or
  :math:`d_{\\max} + \\rho_i < l_2`,

and the piece is *all in* when every leg is ``IN`` (every :math:`(p, \\varphi)` feasible),
*out* when some leg is ``OUT`` (every :math:`(p, \\varphi)` infeasible). A point orientation
is the piece with :math:`h = 0` (:math:`\\rho_i = \\rho_{xy}`). ``rho`` is enlarged by
``TOLERANCE_CM`` for the round-off of a few libm calls.

**Classification of a box** (:func:`classify_box_range`), with :math:`\\Phi` bisected into
pieces down to the width ``phi_min`` (a depth-first stack of pieces):

*Maximal.* ``INSIDE`` as soon as one piece's midpoint orientation :math:`m` is *all in* at
the point :math:`m`, or one piece is *all in*: then every :math:`p \\in X` is feasible at
that :math:`\\varphi \\in \\Phi`, so :math:`X \\subseteq W_\\exists`. ``OUTSIDE`` if every
piece of a cover of :math:`\\Phi` is *out*: then every :math:`(p, \\varphi) \\in X \\times
\\Phi` is infeasible, so :math:`X \\cap W_\\exists = \\emptyset`. A piece neither *all in*
nor *out* is split while wider than ``max(phi_min, rho_xy / |q|max)``; else ``BOUNDARY``.

The narrowest piece grows with the box (``rho_xy`` its half-diagonal, ``|q|max`` the
farthest platform point): a piece whose chord term :math:`|q| h` is below the box's own
:math:`\\rho_{xy}` rarely decides a box that splitting it in (x, y) would not, and without
the floor one large box of a fine paving bisected Φ down to ``phi_min`` (seconds per box,
with no progress or cancel in between). Leaves at the precision (``rho_xy ≤ precision/√2 <
|q|max · phi_min``) keep ``phi_min``, so every verdict stays certified and only the level
that decides a region changes. The areas can move by a few boxes at the precision, because
a box is tested through its bounding disc and a half's disc is not inside its parent's (on
12 random robots and ranges, both modes, the inside and kept areas were the same as with
``phi_min`` everywhere on 9 and within 0.02 % on the others).

*Total.* ``OUTSIDE`` as soon as some leg is ``OUT`` at one piece's midpoint orientation
:math:`m` (a point): every :math:`p \\in X` is infeasible at :math:`m \\in \\Phi`, so
:math:`X \\cap W_\\forall = \\emptyset`. ``INSIDE`` if every piece of a cover of
:math:`\\Phi` is *all in*: every :math:`(p, \\varphi) \\in X \\times \\Phi` is feasible, so
:math:`X \\subseteq W_\\forall`. Otherwise as above.

The 2-D paving (:func:`range_level`, one level of a breadth-first frontier at a time, in
parallel) is the arc-distance form's (:func:`kernels.workspace_arc.arc_level`) with this
test: inside boxes are never split, outside boxes dropped, boxes at the precision kept as
boundary. With :math:`\\Phi` a single point both modes reduce to the exact leg-wise test.

Geometry vector ``g``: ``[l1, l2, qx1, qy1, qx2, qy2, qx3, qy3, ax1, ay1, ax2, ay2, ax3,
ay3]`` (cm); ``limits`` the (3, 2) joint limits in radians.
"""

import math

import numba
import numpy as np

from ._jit import kernel
from .workspace3prr import LEAF_GRID, grid_cell
from .workspace_arc import (
    BOUNDARY,
    INSIDE,
    LANES,
    OUTSIDE,
    TOLERANCE_CM,
    arc_distance_range,
    settle_xy_box,
)
from .workspace_parallel_orientation import parallel_piece_status

MAXIMAL = 0
TOTAL = 1

#: The mechanism of ``g`` and ``limits``: a 3-RRR (module docstring), a 3-RPR or a 3-PRR
#: (:mod:`kernels.workspace_parallel_orientation`).
RRR = 0
RPR = 1
PRR = 2

#: Piece verdicts: some leg fails everywhere, undecided, every leg closes everywhere.
PIECE_OUT = 0
PIECE_UNKNOWN = 1
PIECE_IN = 2

#: Rows of the orientation-piece stack: a depth-first bisection needs one per level.
PIECE_STACK = 128


@kernel
def piece_status(cx, cy, rho_xy, phi_mid, phi_half, g, limits):
    """``PIECE_IN``, ``PIECE_OUT`` or ``PIECE_UNKNOWN`` for the box of centre ``(cx, cy)`` and
    half-diagonal ``rho_xy`` over the orientations ``[phi_mid - phi_half, phi_mid +
    phi_half]`` (module docstring)."""
    c = math.cos(phi_mid)
    s = math.sin(phi_mid)
    chord = 2.0 * math.sin(0.5 * min(phi_half, math.pi))
    l2 = g[1]
    all_in = True
    for leg in range(3):
        qx = g[2 + 2 * leg]
        qy = g[3 + 2 * leg]
        rho = rho_xy + chord * math.hypot(qx, qy) + TOLERANCE_CM
        vx = cx + c * qx - s * qy - g[8 + 2 * leg]
        vy = cy + s * qx + c * qy - g[9 + 2 * leg]
        dmin, dmax = arc_distance_range(vx, vy, g[0], limits[leg, 0], limits[leg, 1])
        if dmin - rho > l2 or dmax + rho < l2:
            return PIECE_OUT
        if dmin + rho > l2 or dmax - rho < l2:
            all_in = False
    return PIECE_IN if all_in else PIECE_UNKNOWN


@kernel
def box_piece_status(mechanism, xlo, xhi, ylo, yhi, phi_mid, phi_half, g, limits):
    """:func:`piece_status` of the box for a 3-RRR (``mechanism`` = ``RRR``), else
    :func:`kernels.workspace_parallel_orientation.parallel_piece_status` of a 3-RPR
    (``RPR``) or a 3-PRR (``PRR``)."""
    if mechanism != RRR:
        return parallel_piece_status(
            mechanism == PRR, xlo, xhi, ylo, yhi, phi_mid, phi_half, g, limits
        )
    cx = 0.5 * (xlo + xhi)
    cy = 0.5 * (ylo + yhi)
    rho_xy = 0.5 * math.hypot(xhi - xlo, yhi - ylo)
    return piece_status(cx, cy, rho_xy, phi_mid, phi_half, g, limits)


@kernel
def classify_box_range(
    xlo, xhi, ylo, yhi, mode, phi_lo, phi_hi, phi_min, g, limits, pieces, mechanism
):
    """``(label, work)``: ``OUTSIDE``, ``BOUNDARY`` or ``INSIDE`` of the box for the maximal
    (``mode`` = ``MAXIMAL``) or total (``TOTAL``) orientation workspace over ``[phi_lo,
    phi_hi]`` (module docstring), and the orientation pieces looked at (the work done);
    ``pieces`` is a scratch array of ``(PIECE_STACK, 2)``. The piece test is
    :func:`box_piece_status` of ``mechanism`` (both keep the platform points at ``g[2:8]``)."""
    rho_xy = 0.5 * math.hypot(xhi - xlo, yhi - ylo)
    # pieces no narrower than the box's own blur: |q|·width ≥ rho_xy (see module docstring)
    q_far = max(math.hypot(g[2], g[3]), math.hypot(g[4], g[5]), math.hypot(g[6], g[7]))
    narrowest = max(phi_min, rho_xy / max(q_far, 1e-300))
    pieces[0, 0] = phi_lo
    pieces[0, 1] = phi_hi
    n = 1
    work = 0
    undecided = False
    while n > 0:
        n -= 1
        work += 1
        lo = pieces[n, 0]
        hi = pieces[n, 1]
        mid = 0.5 * (lo + hi)
        half = max(hi - mid, mid - lo)
        at_point = box_piece_status(mechanism, xlo, xhi, ylo, yhi, mid, 0.0, g, limits)
        if mode == MAXIMAL:
            if at_point == PIECE_IN:
                return INSIDE, work
            verdict = box_piece_status(mechanism, xlo, xhi, ylo, yhi, mid, half, g, limits)
            if verdict == PIECE_IN:
                return INSIDE, work
            if verdict == PIECE_OUT:
                continue
        else:
            if at_point == PIECE_OUT:
                return OUTSIDE, work
            verdict = box_piece_status(mechanism, xlo, xhi, ylo, yhi, mid, half, g, limits)
            if verdict == PIECE_IN:
                continue
        if hi - lo > narrowest and n + 2 <= pieces.shape[0]:
            pieces[n, 0] = mid
            pieces[n, 1] = hi
            pieces[n + 1, 0] = lo
            pieces[n + 1, 1] = mid
            n += 2
        else:
            undecided = True
    if undecided:
        return BOUNDARY, work
    return (OUTSIDE if mode == MAXIMAL else INSIDE), work


@kernel(parallel=True)
def range_level(
    mode,
    phi_lo,
    phi_hi,
    phi_min,
    g,
    limits,
    precision,
    rows,
    start,
    stop,
    children,
    outcome,
    work,
    mechanism,
):
    """Decide rows ``start .. stop - 1`` of a frontier of (x, y) boxes with
        :func:`classify_box_range`, in parallel, then
        :func:`~kernels.workspace_arc.settle_xy_box` (outside dropped, inside kept unsplit,
        leaves at the precision kept as boundary, the rest halved across the wider side).

        Row ``start + i`` writes ``children[2 i]``, ``children[2 i + 1]``, ``outcome[i]``
        (``OUTSIDE``, ``BOUNDARY``, ``INSIDE`` or ``SPLIT``) and ``work[i]`` (orientation pieces
        looked at). A 3-PRR's boundary leaf is dropped when its ``LEAF_GRID`` × ``LEAF_GRID``
    cells are all ``OUTSIDE`` (as :func:`kernels.workspace3prr.prr_level` does). Boxes go to
    ``LANES`` interleaved lanes run by ``prange``, each with its own
        piece stack; a box's outcome depends on that box only, so the result does not depend on
        the number of threads.
    """
    n = stop - start
    lanes = min(LANES, n)
    for lane in numba.prange(lanes):
        pieces = np.empty((PIECE_STACK, 2))
        for i in range(lane, n, lanes):
            r = start + i
            label, cost = classify_box_range(
                rows[r, 0],
                rows[r, 1],
                rows[r, 2],
                rows[r, 3],
                mode,
                phi_lo,
                phi_hi,
                phi_min,
                g,
                limits,
                pieces,
                mechanism,
            )
            leaf = rows[r, 1] - rows[r, 0] <= precision and rows[r, 3] - rows[r, 2] <= precision
            if mechanism == PRR and leaf and label == BOUNDARY:  # the 3-PRR's leaf check
                refuted = True
                for k in range(LEAF_GRID * LEAF_GRID):
                    x0, x1, y0, y1 = grid_cell(
                        rows[r, 0], rows[r, 1], rows[r, 2], rows[r, 3], LEAF_GRID, k
                    )
                    cell, more = classify_box_range(
                        x0,
                        x1,
                        y0,
                        y1,
                        mode,
                        phi_lo,
                        phi_hi,
                        phi_min,
                        g,
                        limits,
                        pieces,
                        mechanism,
                    )
                    cost += more
                    if cell != OUTSIDE:
                        refuted = False
                        break
                label = OUTSIDE if refuted else label
            work[i] = cost
            outcome[i] = settle_xy_box(label, rows, r, children, 2 * i, precision)

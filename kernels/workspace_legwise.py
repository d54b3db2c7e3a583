"""Leg-wise interval paving of the 3-RRR workspace: (x, y) boxes, a 1-D θ search per leg.

Each leg constraint :math:`f_i(x, y, \\theta_i)` (see :mod:`kernels.workspace3rrr`) depends
on its own angle only, so an (x, y) box :math:`B` lies in the workspace iff every leg
separately closes: :math:`\\forall (x, y) \\in B\\; \\exists \\theta_i \\in
[\\underline\\theta_i, \\overline\\theta_i]: f_i = 0`. Per box and leg the joint range is
cut into pieces :math:`T_k` (a 1-D bisection, stackless depth-first) and
:math:`F_i(B, T_k)` is enclosed by the chosen interval form:

* :math:`\\underline F > 0` or :math:`\\overline F < 0` on a piece: :math:`f_i` has that
  sign on all of :math:`B \\times T_k`;
* pieces of **both signs** prove the leg over the whole box: for every :math:`(x, y) \\in
  B`, :math:`f_i(x, y, \\cdot)` is continuous on the connected range and changes sign
  between the two pieces, so it has a root in the range (intermediate value theorem);
* **every** piece of one sign refutes the leg: no root for any :math:`(x, y) \\in B`;
* otherwise the leg is undecided: pieces holding 0 reached the smallest width
  :math:`\\max(w_x, w_y) / k` (``angle_scale`` :math:`k` in cm per radian).

A box is *outside* if one leg is refuted, *inside* if all three are proved, else it is
halved across its wider side until both widths are :math:`\\le \\varepsilon` and kept as
*boundary*. A child inherits each leg's state: a proved leg stays proved (a sub-box), an
undecided leg keeps the hull :math:`[t_{lo}, t_{hi}]` of its undecided pieces and the sign
:math:`\\sigma` of the pieces outside that hull (all of one sign, or the leg would be
proved; 0 when none was found), since a sign proved over the parent holds over the child.
So the cost per box is a sum over the legs, not the product of the joint 5-D bisection.

Frontier row layout (``ROW_COLUMNS``): ``x_lo, x_hi, y_lo, y_hi`` then per leg
``t_lo, t_hi, state`` with ``state`` = ``LEG_PROVED`` or the sign :math:`\\sigma`.

:func:`pave_level` decides a slice of a frontier of (x, y) boxes in parallel (``prange``);
each box's outcome depends on that box only, so the boxes and areas do not depend on the
number of threads, and the caller keeps the frontier's order.
"""

import math

import numba
import numpy as np

from ._jit import kernel
from .interval import down, up
from .workspace3rrr import leg_enclosure, split_xy_widest
from .workspace_arc import LANES
from .workspace_tolerance import (
    ALL,
    MODE,
    NOMINAL,
    SOME,
    TOL_COLUMNS,
    box_growth,
    distal_spread,
    tolerant_classify_box,
)

ROW_COLUMNS = 13
#: Leg state beside the signs -1, 0, +1.
LEG_PROVED = 2.0

# Outcome of one leg (leg_search) and of one box (pave_level).
OUT = 0
UNDECIDED = 1
PROVED = 2
# Box outcomes: OUT, BOUNDARY (a leaf kept undecided), INSIDE, SPLIT.
BOUNDARY = 1
INSIDE = 2
SPLIT = 3

#: The ``tol`` of a nominal paving (:mod:`kernels.workspace_tolerance`).
NO_TOLERANCE = np.zeros(TOL_COLUMNS)

#: Deepest θ bisection of one leg search (pieces of 2**-MAX_DEPTH of the hull).
MAX_DEPTH = 40


@kernel
def leg_search(form, leg, xlo, xhi, ylo, yhi, tlo, thi, sign, min_width, p, spread):
    """Decide leg ``leg`` over the (x, y) box from its hull ``[tlo, thi]`` and inherited sign.

    Returns ``(outcome, new_tlo, new_thi, new_sign, evaluations)`` with ``outcome`` one of
    ``OUT``, ``UNDECIDED`` (then the new hull and sign) or ``PROVED`` (module docstring).

    With tolerances (:mod:`kernels.workspace_tolerance`) every piece's enclosure covers
    every robot within them: the caller passes the box grown by
    :func:`~kernels.workspace_tolerance.box_growth` per side, and the distal spread
    ``spread = (lo, hi)`` is added, so a proved leg closes for every robot and a refuted
    one for none (``(0, 0)``: the nominal robot).
    """
    width = thi - tlo
    hull_lo = math.inf
    hull_hi = -math.inf
    evaluations = 0
    depth = 0
    index = 0  # piece ``index`` of the 2**depth equal pieces of [tlo, thi]
    while True:
        step = width * 2.0**-depth
        lo = tlo + index * step
        hi = thi if index + 1 == 1 << depth else tlo + (index + 1) * step
        flo, fhi = leg_enclosure(form, leg, xlo, xhi, ylo, yhi, lo, hi, p)
        if spread[1] != 0.0:
            flo = down(flo + spread[0])
            fhi = up(fhi + spread[1])
        evaluations += 1
        piece_sign = 1.0 if flo > 0.0 else (-1.0 if fhi < 0.0 else 0.0)
        if piece_sign != 0.0:
            if sign == 0.0:
                sign = piece_sign
            elif piece_sign != sign:
                return PROVED, tlo, thi, sign, evaluations
        elif hi - lo > min_width and depth < MAX_DEPTH:
            depth += 1  # descend to the left half
            index *= 2
            continue
        else:
            hull_lo = min(hull_lo, lo)
            hull_hi = max(hull_hi, hi)
        # next piece: climb while this is a right child, then go to the right sibling
        while depth > 0 and index % 2 == 1:
            depth -= 1
            index //= 2
        if depth == 0:
            break
        index += 1
    if hull_lo > hull_hi:
        return OUT, tlo, thi, sign, evaluations
    return UNDECIDED, hull_lo, hull_hi, sign, evaluations


@kernel
def decide_box(form, p, precision, angle_scale, rows, r, children, c, limits, tol):
    """Decide row ``r`` of ``rows``: write its updated row to ``children[c]`` (kept or
    first child) and, when split, the second half to ``children[c + 1]``.

    Returns ``(outcome, evaluations)``: ``OUT``, ``BOUNDARY``, ``INSIDE`` or ``SPLIT``.

    With non-zero tolerances (``tol``'s mode not ``NOMINAL``) the box is first labelled by
    :func:`kernels.workspace_tolerance.tolerant_classify_box` (with ``limits``): its
    single-robot certificate decides the side the forms cannot (``all``: outside,
    ``some``: inside) at once; then the legs are searched for every robot
    (:func:`leg_search`), and a box they leave undecided takes the label's universal
    certificate (``all``: inside, ``some``: outside) before it is kept or split.
    """
    for j in range(ROW_COLUMNS):
        children[c, j] = rows[r, j]
    xlo = rows[r, 0]
    xhi = rows[r, 1]
    ylo = rows[r, 2]
    yhi = rows[r, 3]
    wx = xhi - xlo
    wy = yhi - ylo
    evaluations = 0
    inside = True
    grow = box_growth(tol)
    spread = distal_spread(p[1], tol)
    # θ pieces down to the width of the box the forms see (grown by the tolerances)
    min_width = (max(wx, wy) + 2.0 * grow) / angle_scale
    gxlo, gxhi, gylo, gyhi = xlo, xhi, ylo, yhi
    if grow > 0.0:  # rounded outwards: the grown box holds every robot's leg point
        gxlo, gxhi, gylo, gyhi = down(xlo - grow), up(xhi + grow), down(ylo - grow), up(yhi + grow)
    label = BOUNDARY
    if tol[MODE] != NOMINAL and (grow > 0.0 or spread[1] != 0.0):
        label = tolerant_classify_box(xlo, xhi, ylo, yhi, p, limits, tol)
        # the single-robot certificate first: the side the forms cannot decide
        if (label == OUT and tol[MODE] == ALL) or (label == INSIDE and tol[MODE] == SOME):
            return label, evaluations
    for leg in range(3):
        col = 4 + 3 * leg
        state = rows[r, col + 2]
        if state == LEG_PROVED:
            continue
        outcome, tlo, thi, sign, n = leg_search(
            form,
            leg,
            gxlo,
            gxhi,
            gylo,
            gyhi,
            rows[r, col],
            rows[r, col + 1],
            state,
            min_width,
            p,
            spread,
        )
        evaluations += n
        if outcome == OUT:
            return OUT, evaluations
        if outcome == PROVED:
            children[c, col + 2] = LEG_PROVED
        else:
            inside = False
            children[c, col] = tlo
            children[c, col + 1] = thi
            children[c, col + 2] = sign
    if inside:
        return INSIDE, evaluations
    if label in (OUT, INSIDE):  # the exact test's certificate over every robot
        return label, evaluations
    if wx <= precision and wy <= precision:
        return BOUNDARY, evaluations
    split_xy_widest(children, c, c + 1, np.int64(ROW_COLUMNS))  # one signature, not a literal's
    return SPLIT, evaluations


@kernel(parallel=True)
def pave_level(
    form,
    p,
    precision,
    angle_scale,
    rows,
    start,
    stop,
    children,
    outcome,
    evaluations,
    limits,
    tol,
):
    """Decide rows ``start .. stop - 1`` of a frontier in parallel.

    Row ``start + i`` writes ``children[2 i]`` (the kept box or the first half) and
    ``children[2 i + 1]`` (the second half), ``outcome[i]`` and ``evaluations[i]`` (interval
    evaluations). Boxes go to ``LANES`` interleaved lanes run by ``prange``. ``limits``
    and ``tol``: :func:`decide_box`'s (``NO_TOLERANCE``: the nominal robot).
    """
    n = stop - start
    lanes = min(LANES, n)
    for lane in numba.prange(lanes):
        for i in range(lane, n, lanes):
            code, count = decide_box(
                form, p, precision, angle_scale, rows, start + i, children, 2 * i, limits, tol
            )
            outcome[i] = code
            evaluations[i] = count


@kernel(parallel=True)
def classify_boxes_parallel(boxes, p, limits, out, tol):
    """:func:`kernels.workspace_arc.classify_box` (the exact leg-wise test; with
    tolerances in ``tol``, :func:`kernels.workspace_tolerance.tolerant_classify_box`) for
    every row ``x_lo, x_hi, y_lo, y_hi`` of ``boxes``, rows spread over the threads."""
    n = boxes.shape[0]
    lanes = min(LANES, n)
    for lane in numba.prange(lanes):
        for r in range(lane, n, lanes):
            out[r] = tolerant_classify_box(
                boxes[r, 0], boxes[r, 1], boxes[r, 2], boxes[r, 3], p, limits, tol
            )


def root_row(box, limits_rad):
    """The frontier's first row: the (x, y) search box, every leg undecided over its
    whole range with no sign known."""
    row = np.zeros(ROW_COLUMNS)
    row[:4] = [box[0][0], box[0][1], box[1][0], box[1][1]]
    for leg, (lo, hi) in enumerate(limits_rad):
        row[4 + 3 * leg : 7 + 3 * leg] = [lo, hi, 0.0]
    return row

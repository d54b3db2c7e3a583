"""Certified clearance bounds over (x, y) boxes of the robots with RR legs: the 3-RRR and
the five-bar (:mod:`kernels.interference`).

Leg ``i`` (the model of :mod:`kernels.singularity3rrr`): the base joint :math:`A_i`, the
elbow :math:`B_i = C_i - u_i` and the platform joint :math:`C_i = p + r_i`; its links are
the proximal :math:`A_i B_i` (no moving joint) and the distal :math:`B_i C_i` (at the joint
:math:`C_i`). :func:`kernels.singularity3rrr.leg_status` encloses :math:`u_i` over the box's
points in the working mode (without the joint limits where they may cut the box, as
:mod:`kernels.dexterity_rr` does: a superset), :math:`C_i` is the box shifted. The 3-RRR's
platform is the triangle :math:`C_1 C_2 C_3`; the five-bar's two distal links meet at its
end point (one joint, not checked against each other) and it has no platform polygon.
"""

import numba
import numpy as np

from ._jit import kernel
from .dexterity import IN, OUT, UNSURE, combine
from .dexterity_rr import FREE
from .interference import settle_gap
from .interval import iadd_scalar, isub
from .singularity3rrr import LEG_IN, LEG_OUT, LEG_UNDEFINED, TOLERANCE_CM, leg_status


@kernel
def rr_links(xlo, xhi, ylo, yhi, leg, g, r, elbow, limits, ends, platform):
    """Leg ``leg``'s verdict over the box (``OUT``, ``UNSURE``, ``IN``; ``-1`` when the box
    may hold the base joint's direction singularity), writing its two links' ends into rows
    ``2 leg`` (proximal) and ``2 leg + 1`` (distal) of ``ends`` and
    :math:`C_i` into ``platform[leg]`` when it has that row."""
    verdict, ux_lo, ux_hi, uy_lo, uy_hi, _, _ = leg_status(
        xlo, xhi, ylo, yhi, leg, g, r, elbow, limits
    )
    if verdict == LEG_UNDEFINED:
        return -1
    if verdict == LEG_OUT:
        return OUT
    if verdict != LEG_IN:
        reach, ux_lo, ux_hi, uy_lo, uy_hi, _, _ = leg_status(
            xlo, xhi, ylo, yhi, leg, g, r, elbow, FREE
        )
        if reach == LEG_UNDEFINED:
            return -1
    cx_lo, cx_hi = iadd_scalar(xlo, xhi, r[leg, 0])
    cy_lo, cy_hi = iadd_scalar(ylo, yhi, r[leg, 1])
    cx_lo -= TOLERANCE_CM
    cx_hi += TOLERANCE_CM
    cy_lo -= TOLERANCE_CM
    cy_hi += TOLERANCE_CM
    bx_lo, bx_hi = isub(cx_lo, cx_hi, ux_lo, ux_hi)
    by_lo, by_hi = isub(cy_lo, cy_hi, uy_lo, uy_hi)
    ax = g[8 + 2 * leg]
    ay = g[9 + 2 * leg]
    k = 2 * leg
    ends[k, 0, 0, 0], ends[k, 0, 0, 1], ends[k, 0, 1, 0], ends[k, 0, 1, 1] = ax, ax, ay, ay
    for link in (k, k + 1):
        e = 1 if link == k else 0
        ends[link, e, 0, 0], ends[link, e, 0, 1] = bx_lo, bx_hi
        ends[link, e, 1, 0], ends[link, e, 1, 1] = by_lo, by_hi
    ends[k + 1, 1, 0, 0], ends[k + 1, 1, 0, 1] = cx_lo, cx_hi
    ends[k + 1, 1, 1, 0], ends[k + 1, 1, 1, 1] = cy_lo, cy_hi
    if leg < len(platform):
        platform[leg, 0, 0, 0], platform[leg, 0, 0, 1] = cx_lo, cx_hi
        platform[leg, 0, 1, 0], platform[leg, 0, 1, 1] = cy_lo, cy_hi
    return IN if verdict == LEG_IN else UNSURE


@kernel
def rr_topology(n):
    """The links of ``n`` RR legs for :func:`kernels.interference.clearance_gap`: the
    platform's vertices (three legs: the 3-RRR's triangle; two: the five-bar, none), each
    link's leg (``chain``: proximal ``2 i``, distal ``2 i + 1``) and the platform vertex it
    is jointed to (``joint``: a distal link at vertex ``i``, the five-bar's both at its end
    point; ``-1`` for none)."""
    vertices = n if n == 3 else 0
    chain = np.repeat(np.arange(n), 2)
    joint = np.full(2 * n, -1, dtype=np.int64)
    for leg in range(n):
        joint[2 * leg + 1] = leg if n == 3 else 0
    return vertices, chain, joint


@kernel(parallel=True)
def rr_interference(boxes, g, r, elbow, limits, width_cm, verdict, gap):
    """Per row ``x_lo, x_hi, y_lo, y_hi`` of ``boxes``: the verdict in the mode ``elbow``
    (:mod:`kernels.dexterity`) and ``gap[i] = (lo, hi)``, an enclosure of the clearance gap
    (:mod:`kernels.interference`) over the box's points in the mode's workspace
    (``(-inf, inf)`` where not bounded). ``g`` has one geometry row per leg (the 3-RRR's
    layout, :mod:`kernels.singularity3rrr`), ``r`` the platform offsets, ``limits`` (legs,
    2) radians; three legs: the 3-RRR (its platform triangle, distal ``i`` at vertex ``i``),
    two legs: the five-bar (both distal links at one end point, no polygon)."""
    n = len(g)
    vertices, chain, joint = rr_topology(n)
    for i in numba.prange(len(boxes)):
        ends = np.empty((2 * n, 2, 2, 2))
        platform = np.empty((vertices, 1, 2, 2))
        centre = np.empty((2 * n + vertices, 5))
        state = IN
        defined = True
        for leg in range(n):
            xlo, xhi, ylo, yhi = boxes[i, 0], boxes[i, 1], boxes[i, 2], boxes[i, 3]
            v = rr_links(xlo, xhi, ylo, yhi, leg, g[leg], r, elbow, limits, ends, platform)
            if v < 0:
                defined = False
                v = UNSURE
            state = combine(state, v)
        settle_gap(state, defined, ends, chain, joint, platform, width_cm, centre, verdict, gap, i)

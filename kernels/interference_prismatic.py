"""Certified clearance bounds over (x, y) boxes of the robots with an actuated prismatic
joint (:mod:`kernels.interference`), in :mod:`kernels.dexterity_prismatic`'s models.

**3-RPR**: leg ``i`` is one link, the segment from its base joint :math:`A_i` to its
platform joint :math:`C_i = p + r_i` (the box shifted); it closes where its length
:math:`\\rho_i = |p - c_i|` lies within its limits.

**3-PRR**: leg ``i``'s moving link runs from the slider :math:`S_i = C_i - d_i` to
:math:`C_i` (:math:`d_i` the distal link, enclosed in the slider mode over the box's points
where the leg reaches); the slider lines themselves are fixed and not checked.

Both platforms are the triangle :math:`C_1 C_2 C_3`, leg ``i`` jointed to it at vertex ``i``.
"""

import numba
import numpy as np

from ._jit import kernel
from .dexterity import IN, OUT, UNSURE, combine
from .dexterity_prismatic import TOLERANCE_CM, prr_parts, rpr_parts
from .interference import settle_gap
from .interval import iadd_scalar, isub


@kernel
def set_joint(xlo, xhi, ylo, yhi, leg, r, ends, platform):
    """Enclose :math:`C_i = p + r_i` over the box: end 1 of link ``leg`` and vertex
    ``leg`` of the platform; returns its ``(x_lo, x_hi, y_lo, y_hi)``."""
    cx_lo, cx_hi = iadd_scalar(xlo, xhi, r[leg, 0])
    cy_lo, cy_hi = iadd_scalar(ylo, yhi, r[leg, 1])
    cx_lo -= TOLERANCE_CM
    cx_hi += TOLERANCE_CM
    cy_lo -= TOLERANCE_CM
    cy_hi += TOLERANCE_CM
    for box in (ends[leg, 1], platform[leg, 0]):
        box[0, 0] = cx_lo
        box[0, 1] = cx_hi
        box[1, 0] = cy_lo
        box[1, 1] = cy_hi
    return cx_lo, cx_hi, cy_lo, cy_hi


@kernel
def rpr_link(xlo, xhi, ylo, yhi, leg, bases, centres, r, limits, ends, platform):
    """3-RPR leg ``leg``'s verdict over the box (its length within ``limits[leg]``:
    ``IN``, outside: ``OUT``, else ``UNSURE``; :func:`kernels.dexterity_prismatic.rpr_parts`
    about ``centres[leg]`` with the offset ``r[leg]``), writing its link from
    :math:`A_i` (``bases[leg]``) to :math:`C_i` into ``ends[leg]`` and
    :math:`C_i` into ``platform[leg]``."""
    _, _, _, rho = rpr_parts(xlo, xhi, ylo, yhi, leg, centres, r, 0.0)
    lo = limits[leg, 0]
    hi = limits[leg, 1]
    ends[leg, 0, 0, 0] = ends[leg, 0, 0, 1] = bases[leg, 0]
    ends[leg, 0, 1, 0] = ends[leg, 0, 1, 1] = bases[leg, 1]
    set_joint(xlo, xhi, ylo, yhi, leg, r, ends, platform)
    if rho[1] < lo or rho[0] > hi:
        return OUT
    return IN if lo <= rho[0] and rho[1] <= hi else UNSURE


@kernel
def prr_link(xlo, xhi, ylo, yhi, leg, g, modes, r, ends, platform):
    """3-PRR leg ``leg``'s verdict over the box in its slider mode ``modes[leg]`` (``OUT``
    where it cannot reach or leaves its stroke), writing, where it may close, its moving
    link from the slider :math:`S_i = C_i - d_i` to :math:`C_i` into ``ends[leg]`` and
    :math:`C_i` into ``platform[leg]``."""
    reach, s, _, root, dx, dy, _, _ = prr_parts(xlo, xhi, ylo, yhi, leg, g, modes[leg], r, 0.0)
    if not reach or s[1] < g[leg, 4] or s[0] > g[leg, 5]:
        return OUT
    cx_lo, cx_hi, cy_lo, cy_hi = set_joint(xlo, xhi, ylo, yhi, leg, r, ends, platform)
    ends[leg, 0, 0, 0], ends[leg, 0, 0, 1] = isub(cx_lo, cx_hi, *dx)
    ends[leg, 0, 1, 0], ends[leg, 0, 1, 1] = isub(cy_lo, cy_hi, *dy)
    inside = root[0] > 0.0 and g[leg, 4] <= s[0] and s[1] <= g[leg, 5]
    return IN if inside else UNSURE


@kernel(parallel=True)
def rpr_interference(boxes, bases, centres, r, limits, width_cm, verdict, gap):
    """Per row ``x_lo, x_hi, y_lo, y_hi`` of ``boxes``: the verdict (every leg's length
    within ``limits`` (3, 2) cm: ``IN``; some leg's outside them: ``OUT``) and ``gap[i] =
    (lo, hi)``, an enclosure of the clearance gap over the box's points in the workspace
    (``(-inf, inf)`` where some leg is out). ``bases`` are the :math:`A_i`, ``centres`` the
    annuli's centres :math:`A_i - r_i`, ``r`` the platform offsets."""
    chain = np.arange(3)
    joint = np.arange(3)
    for i in numba.prange(len(boxes)):
        ends = np.empty((3, 2, 2, 2))
        platform = np.empty((3, 1, 2, 2))
        centre = np.empty((6, 5))
        state = IN
        xlo, xhi, ylo, yhi = boxes[i, 0], boxes[i, 1], boxes[i, 2], boxes[i, 3]
        for leg in range(3):
            v = rpr_link(xlo, xhi, ylo, yhi, leg, bases, centres, r, limits, ends, platform)
            state = combine(state, v)
        settle_gap(state, True, ends, chain, joint, platform, width_cm, centre, verdict, gap, i)


@kernel(parallel=True)
def prr_interference(boxes, g, modes, r, width_cm, verdict, gap):
    """Per row of ``boxes``: the 3-PRR's verdict in the slider mode ``modes`` (as
    :func:`kernels.dexterity_prismatic.prr_leg`'s) and ``gap[i]``, an enclosure of the
    clearance gap over the box's points in the mode's workspace (``g`` (3, 7) as
    :mod:`kernels.singularity3prr`'s, ``r`` (3, 2) the :math:`r_i`)."""
    chain = np.arange(3)
    joint = np.arange(3)
    for i in numba.prange(len(boxes)):
        ends = np.empty((3, 2, 2, 2))
        platform = np.empty((3, 1, 2, 2))
        centre = np.empty((6, 5))
        state = IN
        xlo, xhi, ylo, yhi = boxes[i, 0], boxes[i, 1], boxes[i, 2], boxes[i, 3]
        for leg in range(3):
            state = combine(state, prr_link(xlo, xhi, ylo, yhi, leg, g, modes, r, ends, platform))
            if state == OUT:
                break
        settle_gap(state, True, ends, chain, joint, platform, width_cm, centre, verdict, gap, i)

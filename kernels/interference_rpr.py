"""Certified clearance bounds over (x, y) boxes of the 3-RPR (:mod:`kernels.interference`).

Leg ``i`` (:mod:`kernels.dexterity_prismatic`'s model) is one link, the segment from its
base joint :math:`A_i` to its platform joint :math:`C_i = p + r_i` (the box shifted); it
closes where its length :math:`\\rho_i = |p - c_i|` lies within its limits. The platform is
the triangle :math:`C_1 C_2 C_3`, leg ``i`` jointed to it at vertex ``i``.
"""

import math

import numba
import numpy as np

from ._jit import kernel
from .dexterity import IN, OUT, UNSURE, combine
from .dexterity_prismatic import TOLERANCE_CM, rpr_parts
from .interference import clearance_gap


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
            _, _, _, rho = rpr_parts(xlo, xhi, ylo, yhi, leg, centres, r, 0.0)
            lo = limits[leg, 0]
            hi = limits[leg, 1]
            v = IN if lo <= rho[0] and rho[1] <= hi else UNSURE
            state = combine(state, OUT if rho[1] < lo or rho[0] > hi else v)
            ends[leg, 0, 0, 0] = ends[leg, 0, 0, 1] = bases[leg, 0]
            ends[leg, 0, 1, 0] = ends[leg, 0, 1, 1] = bases[leg, 1]
            cx_lo = xlo + r[leg, 0]
            cx_hi = xhi + r[leg, 0]
            cy_lo = ylo + r[leg, 1]
            cy_hi = yhi + r[leg, 1]
            slack = 2.0 * TOLERANCE_CM + 1e-15 * (abs(cx_lo) + abs(cx_hi) + abs(cy_lo) + abs(cy_hi))
            ends[leg, 1, 0, 0] = platform[leg, 0, 0, 0] = cx_lo - slack
            ends[leg, 1, 0, 1] = platform[leg, 0, 0, 1] = cx_hi + slack
            ends[leg, 1, 1, 0] = platform[leg, 0, 1, 0] = cy_lo - slack
            ends[leg, 1, 1, 1] = platform[leg, 0, 1, 1] = cy_hi + slack
        verdict[i] = state
        gap[i, 0] = -math.inf
        gap[i, 1] = math.inf
        if state != OUT:
            gap[i, 0], gap[i, 1] = clearance_gap(ends, chain, joint, platform, width_cm, centre)

"""Certified clearance of platform pose boxes for the 3-RPR and the 3-PRR: the interference
part of a certified path's box test (:mod:`planar_tui.workspace.path.certify`,
``leg_width_cm``), in :mod:`kernels.interference_prismatic`'s models.

Over a pose box :math:`X \\times Y \\times \\Phi` leg ``i``'s platform joint :math:`C_i`
lies in the box :math:`(X + r_{ix}) \\times (Y + r_{iy})`, :math:`r_i` the enclosure of
:math:`R(\\varphi) q_i` (:func:`kernels.path_certify_rr.platform_offset`); each leg depends
on the pose only through :math:`C_i`, so the (x, y) box kernels' leg parts over that box
(offsets zero) enclose its link, and :func:`kernels.interference.clearance_gap` the gap for
every choice of ends and vertices in their boxes: an outer enclosure over the pose box.
"""

import math

import numba
import numpy as np

from ._jit import kernel
from .dexterity import IN, OUT, UNSURE, combine
from .dexterity_prismatic import prr_parts, rpr_parts
from .interference import clearance_gap
from .interference_prismatic import set_joint
from .interval import iadd, isincos, isub
from .path_certify_rr import platform_offset


@kernel
def joint_box(boxes, i, q, leg, s_lo, s_hi, c_lo, c_hi):
    """The box ``(x_lo, x_hi, y_lo, y_hi)`` of :math:`C_i` over pose box ``i``."""
    rx_lo, rx_hi, ry_lo, ry_hi = platform_offset(q[leg, 0], q[leg, 1], s_lo, s_hi, c_lo, c_hi)
    cx_lo, cx_hi = iadd(boxes[i, 0], boxes[i, 1], rx_lo, rx_hi)
    cy_lo, cy_hi = iadd(boxes[i, 2], boxes[i, 3], ry_lo, ry_hi)
    return cx_lo, cx_hi, cy_lo, cy_hi


@kernel(parallel=True)
def rpr_pose_clearance(boxes, bases, q, limits, width_cm, verdict, gap):
    """Per row ``x_lo, x_hi, y_lo, y_hi, phi_lo, phi_hi`` of ``boxes`` (cm, rad): the
    legs' verdict (every length within ``limits`` (3, 2) cm: ``IN``, some outside: ``OUT``)
    and ``gap[i]`` enclosing the clearance gap over the box's poses (``(-inf, inf)`` where
    some leg is out). ``bases`` (3, 2) the :math:`A_i`, ``q`` (3, 2) the platform points."""
    chain = np.arange(3)
    joint = np.arange(3)
    zero = np.zeros((3, 2))
    for i in numba.prange(len(boxes)):
        ends = np.empty((3, 2, 2, 2))
        platform = np.empty((3, 1, 2, 2))
        centre = np.empty((6, 5))
        state = IN
        s_lo, s_hi, c_lo, c_hi = isincos(boxes[i, 4], boxes[i, 5])
        for leg in range(3):
            cx_lo, cx_hi, cy_lo, cy_hi = joint_box(boxes, i, q, leg, s_lo, s_hi, c_lo, c_hi)
            _, _, _, rho = rpr_parts(cx_lo, cx_hi, cy_lo, cy_hi, leg, bases, zero, 0.0)
            lo = limits[leg, 0]
            hi = limits[leg, 1]
            v = IN if lo <= rho[0] and rho[1] <= hi else UNSURE
            state = combine(state, OUT if rho[1] < lo or rho[0] > hi else v)
            ends[leg, 0, 0, 0] = ends[leg, 0, 0, 1] = bases[leg, 0]
            ends[leg, 0, 1, 0] = ends[leg, 0, 1, 1] = bases[leg, 1]
            set_joint(cx_lo, cx_hi, cy_lo, cy_hi, leg, zero, ends, platform)
        verdict[i] = state
        gap[i, 0] = -math.inf
        gap[i, 1] = math.inf
        if state != OUT:
            gap[i, 0], gap[i, 1] = clearance_gap(ends, chain, joint, platform, width_cm, centre)


@kernel(parallel=True)
def prr_pose_clearance(boxes, g, modes, q, width_cm, verdict, gap):
    """As :func:`rpr_pose_clearance` for the 3-PRR in the slider modes ``modes``: ``g``
    (3, 7) rows ``bx, by, ux, uy, s_lo, s_hi, l`` (:mod:`kernels.path_certify_prismatic`'s),
    each leg's moving link from its slider :math:`S_i = C_i - d_i` to :math:`C_i`."""
    chain = np.arange(3)
    joint = np.arange(3)
    zero = np.zeros((3, 2))
    for i in numba.prange(len(boxes)):
        ends = np.empty((3, 2, 2, 2))
        platform = np.empty((3, 1, 2, 2))
        centre = np.empty((6, 5))
        state = IN
        s_lo, s_hi, c_lo, c_hi = isincos(boxes[i, 4], boxes[i, 5])
        for leg in range(3):
            cx_lo, cx_hi, cy_lo, cy_hi = joint_box(boxes, i, q, leg, s_lo, s_hi, c_lo, c_hi)
            reach, s, _, root, dx, dy, _, _ = prr_parts(
                cx_lo, cx_hi, cy_lo, cy_hi, leg, g, modes[leg], zero, 0.0
            )
            if not reach or s[1] < g[leg, 4] or s[0] > g[leg, 5]:
                state = OUT
                break
            inside = root[0] > 0.0 and g[leg, 4] <= s[0] and s[1] <= g[leg, 5]
            state = combine(state, IN if inside else UNSURE)
            cx_lo, cx_hi, cy_lo, cy_hi = set_joint(
                cx_lo, cx_hi, cy_lo, cy_hi, leg, zero, ends, platform
            )
            ends[leg, 0, 0, 0], ends[leg, 0, 0, 1] = isub(cx_lo, cx_hi, *dx)
            ends[leg, 0, 1, 0], ends[leg, 0, 1, 1] = isub(cy_lo, cy_hi, *dy)
        verdict[i] = state
        gap[i, 0] = -math.inf
        gap[i, 1] = math.inf
        if state != OUT:
            gap[i, 0], gap[i, 1] = clearance_gap(ends, chain, joint, platform, width_cm, centre)

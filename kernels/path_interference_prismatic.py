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

import numba
import numpy as np

from ._jit import kernel
from .dexterity import IN, OUT, combine
from .interference import settle_gap
from .interference_prismatic import prr_link, rpr_link
from .interval import isincos
from .path_certify_rr import joint_box


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
            v = rpr_link(
                cx_lo, cx_hi, cy_lo, cy_hi, leg, bases, bases, zero, limits, ends, platform
            )
            state = combine(state, v)
        settle_gap(state, True, ends, chain, joint, platform, width_cm, centre, verdict, gap, i)


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
            v = prr_link(cx_lo, cx_hi, cy_lo, cy_hi, leg, g, modes, zero, ends, platform)
            state = combine(state, v)
            if state == OUT:
                break
        settle_gap(state, True, ends, chain, joint, platform, width_cm, centre, verdict, gap, i)

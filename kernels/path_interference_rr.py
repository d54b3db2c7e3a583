"""Certified clearance of platform pose boxes for the robots with RR legs (the 3-RRR and the
five-bar): the interference part of a certified path's box test
(:mod:`planar_tui.workspace.path.certify`, ``leg_width_cm``).

Over a pose box :math:`X \\times Y \\times \\Phi` leg ``i``'s platform point :math:`C_i`
lies in the box :math:`(X + r_{ix}) \\times (Y + r_{iy})` with :math:`r_i` the enclosure
of :math:`R(\\varphi) q_i` (:func:`kernels.path_certify_rr.platform_offset`), and the leg
depends on the pose only through :math:`C_i`. :func:`kernels.interference_rr.rr_links`
over that box (its offsets zero) encloses the leg's two links' ends and the platform
vertex; :func:`kernels.interference.clearance_gap` then encloses the gap
:math:`\\min_{pairs}(d - d_{req})` for every choice of ends and vertices in their boxes, a
superset of the rigid platform's poses: an outer enclosure over the pose box.
"""

import numba
import numpy as np

from ._jit import kernel
from .dexterity import IN, UNSURE, combine
from .interference import settle_gap
from .interference_rr import rr_links, rr_topology
from .interval import isincos
from .path_certify_rr import joint_box


@kernel(parallel=True)
def rr_pose_clearance(boxes, g, q, elbow, limits, width_cm, verdict, gap):
    """Per row ``x_lo, x_hi, y_lo, y_hi, phi_lo, phi_hi`` of ``boxes`` (cm, rad): the legs'
    verdict (as :func:`kernels.interference_rr.rr_interference`'s) and ``gap[i] = (lo,
    hi)`` enclosing the clearance gap over the box's poses where the legs close
    (``(-inf, inf)`` where not bounded). ``g``: one geometry row per leg, ``q`` (legs, 2)
    the platform points in the platform frame (zero for the five-bar)."""
    n = len(g)
    vertices, chain, joint = rr_topology(n)
    zero = np.zeros((n, 2))
    for i in numba.prange(len(boxes)):
        ends = np.empty((2 * n, 2, 2, 2))
        platform = np.empty((vertices, 1, 2, 2))
        centre = np.empty((2 * n + vertices, 5))
        state = IN
        defined = True
        s_lo, s_hi, c_lo, c_hi = isincos(boxes[i, 4], boxes[i, 5])
        for leg in range(n):
            cx_lo, cx_hi, cy_lo, cy_hi = joint_box(boxes, i, q, leg, s_lo, s_hi, c_lo, c_hi)
            v = rr_links(
                cx_lo, cx_hi, cy_lo, cy_hi, leg, g[leg], zero, elbow, limits, ends, platform
            )
            if v < 0:
                defined = False
                v = UNSURE
            state = combine(state, v)
        settle_gap(state, defined, ends, chain, joint, platform, width_cm, centre, verdict, gap, i)

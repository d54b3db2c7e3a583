"""Certified tests of platform pose boxes for the robots with a prismatic actuator, the
3-RPR and the 3-PRR: the box tests of a certified path
(:mod:`planar_tui.workspace.path.certify`).

Over a pose box :math:`X \\times Y \\times \\Phi`, leg ``i``'s platform joint :math:`C_i = p
+ R(\\varphi) q_i` lies in the box :math:`(X + r_{ix}) \\times (Y + r_{iy})` with
:math:`r_i` the interval enclosure of :math:`R(\\varphi) q_i`
(:func:`kernels.path_certify_rr.platform_offset`). The leg :math:`v_i = C_i - A_i` has the
length :math:`\\rho_i = |v_i|`, enclosed over that box: the leg is *in* where the enclosure
lies in its limits, *out* (reason ``JOINT_LIMIT``: its actuated length leaves them) where
it misses them. The row of :math:`M = J^{-1}` (:mod:`kernels.dexterity_prismatic`) is
:math:`(v_{ix}, v_{iy}, (v_i \\times r_i)/L) / \\rho_i`, each factor enclosed by interval
arithmetic over the box (the natural extension), then
:func:`kernels.dexterity.kappa_bounds`.

**3-PRR**: :func:`kernels.dexterity_prismatic.prr_parts` over the same box of :math:`C_i`
(its slider origin unshifted: :math:`w = C_i - B_i`) gives, in the slider mode, whether
the leg can close anywhere (*out*, reason ``LEG``, where :math:`q = l^2 - h^2 < 0`
everywhere), the slider's stroke enclosure (*out*, reason ``JOINT_LIMIT``, where it misses
the stroke), the distal link :math:`d` and :math:`b = -\\sigma\\sqrt q`; the row is
:math:`(d_x, d_y, (d \times r_i)/L) / b` with :math:`r_i`'s interval enclosure.
"""

import math

import numba
import numpy as np

from ._jit import kernel
from .dexterity import IN, OUT, UNSURE, combine, kappa_bounds
from .dexterity_prismatic import prr_parts, rows_and_norm
from .interval import iadd, iadd_scalar, imul, iscale, isincos, isqr, isqrt, isub
from .path_certify_rr import JOINT_LIMIT, LEG, NO_REASON, platform_offset


@kernel
def offset_cross(dx, dy, rx_lo, rx_hi, ry_lo, ry_hi, length_cm):
    """:math:`(d \times r)/L` over the intervals, widened for the rounded :math:`1/L`."""
    t = isub(*imul(*dx, ry_lo, ry_hi), *imul(*dy, rx_lo, rx_hi))
    t = iscale(*t, 1.0 / length_cm)
    return iadd(*t, -1e-15 * abs(t[0]), 1e-15 * abs(t[1]))


@kernel(parallel=True)
def rpr_pose_boxes(boxes, bases, q, limits, length_cm, verdict, reason, kappa):
    """Per row ``x_lo, x_hi, y_lo, y_hi, phi_lo, phi_hi`` of ``boxes`` (cm, rad): the
    verdict (``OUT``, ``UNSURE``, ``IN``), the reason of an ``OUT`` box and ``kappa[i] =
    (lo, hi)`` enclosing κ over the box's poses (``(1, inf)`` where not bounded). ``bases``
    (3, 2) the base joints, ``q`` (3, 2) the platform points in the platform frame,
    ``limits`` (3, 2) the leg lengths' limits (cm), :math:`L` = ``length_cm``."""
    for i in numba.prange(len(boxes)):
        m_lo = np.empty((3, 3))
        m_hi = np.empty((3, 3))
        norms = np.empty((3, 2))
        state = IN
        s_lo, s_hi, c_lo, c_hi = isincos(boxes[i, 4], boxes[i, 5])
        for leg in range(3):
            rx_lo, rx_hi, ry_lo, ry_hi = platform_offset(
                q[leg, 0], q[leg, 1], s_lo, s_hi, c_lo, c_hi
            )
            vx = iadd_scalar(*iadd(boxes[i, 0], boxes[i, 1], rx_lo, rx_hi), -bases[leg, 0])
            vy = iadd_scalar(*iadd(boxes[i, 2], boxes[i, 3], ry_lo, ry_hi), -bases[leg, 1])
            rho = isqrt(*iadd(*isqr(*vx), *isqr(*vy)))
            lo = limits[leg, 0]
            hi = limits[leg, 1]
            if rho[1] < lo or rho[0] > hi:
                state = OUT
                continue
            state = combine(state, IN if lo <= rho[0] and rho[1] <= hi else UNSURE)
            t = offset_cross(vx, vy, rx_lo, rx_hi, ry_lo, ry_hi, length_cm)
            rows_and_norm(m_lo, m_hi, norms, leg, vx, vy, t, rho, length_cm)
        verdict[i] = state
        reason[i] = JOINT_LIMIT if state == OUT else NO_REASON
        kappa[i, 0] = 1.0
        kappa[i, 1] = math.inf
        if state != OUT:
            kappa[i, 0], kappa[i, 1] = kappa_bounds(m_lo, m_hi, 3, norms)


@kernel(parallel=True)
def prr_pose_boxes(boxes, g, modes, q, length_cm, verdict, reason, kappa):
    """As :func:`rpr_pose_boxes` for the 3-PRR (module docstring): ``g`` (3, 7) rows
    ``bx, by, ux, uy, s_lo, s_hi, l`` (the slider lines' origins :math:`B_i`, unshifted),
    ``modes`` the three slider modes."""
    zero = np.zeros((3, 2))
    for i in numba.prange(len(boxes)):
        m_lo = np.empty((3, 3))
        m_hi = np.empty((3, 3))
        norms = np.empty((3, 2))
        state = IN
        why = NO_REASON
        s_lo, s_hi, c_lo, c_hi = isincos(boxes[i, 4], boxes[i, 5])
        for leg in range(3):
            rx_lo, rx_hi, ry_lo, ry_hi = platform_offset(
                q[leg, 0], q[leg, 1], s_lo, s_hi, c_lo, c_hi
            )
            cx = iadd(boxes[i, 0], boxes[i, 1], rx_lo, rx_hi)
            cy = iadd(boxes[i, 2], boxes[i, 3], ry_lo, ry_hi)
            reach, s, _, root, dx, dy, _, b = prr_parts(*cx, *cy, leg, g, modes[leg], zero, 0.0)
            if not reach or s[1] < g[leg, 4] or s[0] > g[leg, 5]:
                if why != LEG:  # a leg that cannot close outranks a stroke
                    why = JOINT_LIMIT if reach else LEG
                state = OUT
                continue
            inside = root[0] > 0.0 and g[leg, 4] <= s[0] and s[1] <= g[leg, 5]
            state = combine(state, IN if inside else UNSURE)
            t = offset_cross(dx, dy, rx_lo, rx_hi, ry_lo, ry_hi, length_cm)
            rows_and_norm(m_lo, m_hi, norms, leg, dx, dy, t, b, length_cm)
        verdict[i] = state
        reason[i] = why
        kappa[i, 0] = 1.0
        kappa[i, 1] = math.inf
        if state != OUT:
            kappa[i, 0], kappa[i, 1] = kappa_bounds(m_lo, m_hi, 3, norms)

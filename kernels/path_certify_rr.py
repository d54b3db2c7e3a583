"""Certified tests of platform pose boxes for the robots with RR legs (the 3-RRR and the
five-bar): the box tests of a certified path (:mod:`planar_tui.workspace.path.certify`).

A pose box is :math:`X \\times Y \\times \\Phi` (cm, cm, rad; the five-bar's
:math:`\\Phi = [0, 0]` and its platform points zero). Leg ``i``'s platform point is
:math:`C_i = p + R(\\varphi) q_i`; over the pose box :math:`R(\\varphi) q_i` lies in the
interval vector :math:`r_i = ([\\cos\\Phi] q_{ix} - [\\sin\\Phi] q_{iy},\\ [\\sin\\Phi]
q_{ix} + [\\cos\\Phi] q_{iy})` (:func:`kernels.interval.isincos`, rounded outward), so
:math:`C_i` lies in the box :math:`(X + r_{ix}) \\times (Y + r_{iy})`. Leg ``i`` depends on
the pose only through :math:`C_i`, so :func:`kernels.singularity3rrr.leg_status` over that
box (its offsets zero) holds for every pose of the pose box: *in* (the leg closes in its
working mode within its joint limits at every pose), *out* (at none: out of reach when the
same test without limits, ``FREE``, says *out*, else off its joint limits) and enclosures
of the distal link :math:`u_i` over the poses where it closes within its limits.

κ (:mod:`kernels.dexterity_rr`): the row of :math:`M = J^{-1}` is :math:`(u_{ix}, u_{iy},
(u_i \\times r_i) / L) / (v_i \\times u_i)` with :math:`v_i = C_i - A_i`, each factor
enclosed by interval arithmetic (the natural extension: every :math:`\\varphi`-dependent
factor takes its enclosure over :math:`\\Phi`, a superset of the joint values). Each row
is then met (:func:`tighten_row`) with the mean-value form of its first two entries over
the box of :math:`C_i` (:func:`kernels.dexterity_rr.rr_leg`, the constant-orientation
dexterity's: a row depends on the position only through :math:`C_i`, so its enclosure
over that box holds every pose) and its third entry with :math:`(M_{i0} r_{iy} - M_{i1}
r_{ix}) / L`: natural in :math:`\\varphi` but no longer in :math:`u_i` and :math:`b_i`,
whose dependence the natural extension loses (on the Table-3 3-RRR, boxes of 0.125 cm and
±0.005 rad about regular points: the median ratio of κ's upper bound to κ at the centre
falls from 3.0 to 1.4). Then
:func:`kernels.dexterity.kappa_bounds`. The enclosure tightens linearly with the pose box's
width, so bisecting time converges to the point value.
"""

import math

import numba
import numpy as np

from ._jit import kernel
from .dexterity import IN, OUT, UNSURE, combine, kappa_bounds, meet, set_norm, set_row
from .dexterity_rr import FREE, rr_leg
from .interval import down, iadd, iadd_scalar, imul, iscale, isincos, isqr, isub, up
from .singularity3rrr import LEG_IN, LEG_OUT, LEG_UNDEFINED, leg_status

#: Why a pose box fails (``reason``): a leg cannot close, a joint leaves its limits.
NO_REASON = 0
LEG = 1
JOINT_LIMIT = 2


@kernel
def platform_offset(qx, qy, s_lo, s_hi, c_lo, c_hi):
    """The enclosure ``(rx_lo, rx_hi, ry_lo, ry_hi)`` of :math:`R(\\varphi) q` over the
    orientations whose sine and cosine lie in ``[s_lo, s_hi]``, ``[c_lo, c_hi]``."""
    rx_lo, rx_hi = isub(*iscale(c_lo, c_hi, qx), *iscale(s_lo, s_hi, qy))
    ry_lo, ry_hi = iadd(*iscale(s_lo, s_hi, qx), *iscale(c_lo, c_hi, qy))
    return rx_lo, rx_hi, ry_lo, ry_hi


@kernel
def joint_box(boxes, i, q, leg, s_lo, s_hi, c_lo, c_hi):
    """The box ``(x_lo, x_hi, y_lo, y_hi)`` of leg ``leg``'s platform point
    :math:`C_i = p + R(\\varphi) q_i` over pose box ``i`` (:func:`platform_offset`)."""
    rx_lo, rx_hi, ry_lo, ry_hi = platform_offset(q[leg, 0], q[leg, 1], s_lo, s_hi, c_lo, c_hi)
    cx_lo, cx_hi = iadd(boxes[i, 0], boxes[i, 1], rx_lo, rx_hi)
    cy_lo, cy_hi = iadd(boxes[i, 2], boxes[i, 3], ry_lo, ry_hi)
    return cx_lo, cx_hi, cy_lo, cy_hi


@kernel
def tighten_row(m_lo, m_hi, mv_lo, mv_hi, norms, leg, n, r, length_cm):
    """Meet row ``leg`` of the natural :math:`M` (``m_lo, m_hi``) with the mean-value
    enclosures of its first two entries over the platform point's box (``mv_lo, mv_hi``,
    :func:`kernels.dexterity_rr.rr_leg`); with three legs, its third entry
    :math:`(u \\times r) / (L\\,b) = (M_{i0} r_y - M_{i1} r_x) / L` with ``r`` the
    enclosure ``(rx_lo, rx_hi, ry_lo, ry_hi)`` of :math:`R(\\varphi) q_i`; then its norm with the entries' (the square
    roots of the sums of the entries' least and greatest squares)."""
    for k in range(2):
        m_lo[leg, k], m_hi[leg, k] = meet(m_lo[leg, k], m_hi[leg, k], mv_lo[leg, k], mv_hi[leg, k])
    if n == 3:
        a_lo, a_hi = isub(
            *imul(m_lo[leg, 0], m_hi[leg, 0], r[2], r[3]),
            *imul(m_lo[leg, 1], m_hi[leg, 1], r[0], r[1]),
        )
        a_lo, a_hi = iscale(a_lo, a_hi, 1.0 / length_cm)
        a_lo, a_hi = iadd(a_lo, a_hi, -1e-15 * abs(a_lo), 1e-15 * abs(a_hi))  # 1 / L
        m_lo[leg, 2], m_hi[leg, 2] = meet(m_lo[leg, 2], m_hi[leg, 2], a_lo, a_hi)
    least = 0.0
    most = 0.0
    for k in range(n):
        lo = m_lo[leg, k]
        hi = m_hi[leg, k]
        gap = 0.0 if lo <= 0.0 <= hi else min(abs(lo), abs(hi))
        least = down(least + down(gap * gap))
        most = up(most + up(max(abs(lo), abs(hi)) ** 2))
    norms[leg, 0] = max(norms[leg, 0], down(math.sqrt(least)))
    norms[leg, 1] = min(norms[leg, 1], up(math.sqrt(most)))


@kernel(parallel=True)
def rr_pose_boxes(boxes, g, q, elbow, limits, length_cm, verdict, reason, kappa):
    """Per row ``x_lo, x_hi, y_lo, y_hi, phi_lo, phi_hi`` of ``boxes`` (cm, rad): the
    verdict (:mod:`kernels.dexterity`'s ``OUT``, ``UNSURE``, ``IN``), with ``OUT`` its
    ``reason`` (``LEG`` where some leg cannot close, else ``JOINT_LIMIT``) and ``kappa[i] = (lo,
    hi)`` enclosing κ over the box's poses where every leg closes within its limits
    (``(1, inf)`` where not bounded). ``g`` has one geometry row per leg (the 3-RRR's
    layout of :mod:`kernels.singularity3rrr`), ``q`` (legs, 2) the platform points in the
    platform frame, ``limits`` (legs, 2) radians; three legs: :math:`L` = ``length_cm``."""
    n = len(g)
    zero = np.zeros((n, 2))
    nominal = np.zeros(4)  # rr_leg's spread: the robot as given
    for i in numba.prange(len(boxes)):
        m_lo = np.empty((n, n))
        m_hi = np.empty((n, n))
        mv_lo = np.empty((n, n))
        mv_hi = np.empty((n, n))
        norms = np.empty((n, 2))
        scratch = np.empty((n, 2))
        state = IN
        why = NO_REASON
        defined = True
        s_lo, s_hi, c_lo, c_hi = isincos(boxes[i, 4], boxes[i, 5])
        for leg in range(n):
            rx_lo, rx_hi, ry_lo, ry_hi = platform_offset(
                q[leg, 0], q[leg, 1], s_lo, s_hi, c_lo, c_hi
            )
            cx_lo, cx_hi = iadd(boxes[i, 0], boxes[i, 1], rx_lo, rx_hi)
            cy_lo, cy_hi = iadd(boxes[i, 2], boxes[i, 3], ry_lo, ry_hi)
            v, ux_lo, ux_hi, uy_lo, uy_hi, _, _ = leg_status(
                cx_lo, cx_hi, cy_lo, cy_hi, leg, g[leg], zero, elbow, limits
            )
            if v == LEG_OUT:
                if why != LEG:  # a leg that cannot close outranks a joint limit
                    free = leg_status(cx_lo, cx_hi, cy_lo, cy_hi, leg, g[leg], zero, elbow, FREE)
                    why = LEG if free[0] == LEG_OUT else JOINT_LIMIT
                state = OUT
                continue
            if v == LEG_UNDEFINED:
                state = combine(state, UNSURE)
                defined = False
                continue
            state = combine(state, IN if v == LEG_IN else UNSURE)
            vx_lo, vx_hi = iadd_scalar(cx_lo, cx_hi, -g[leg, 8 + 2 * leg])
            vy_lo, vy_hi = iadd_scalar(cy_lo, cy_hi, -g[leg, 9 + 2 * leg])
            b_lo, b_hi = isub(*imul(vx_lo, vx_hi, uy_lo, uy_hi), *imul(vy_lo, vy_hi, ux_lo, ux_hi))
            sq_lo, sq_hi = iadd(*isqr(ux_lo, ux_hi), *isqr(uy_lo, uy_hi))
            if n == 3:
                t_lo, t_hi = isub(
                    *imul(ux_lo, ux_hi, ry_lo, ry_hi), *imul(uy_lo, uy_hi, rx_lo, rx_hi)
                )
                t_lo, t_hi = iscale(t_lo, t_hi, 1.0 / length_cm)
                t_lo, t_hi = iadd(t_lo, t_hi, -1e-15 * abs(t_lo), 1e-15 * abs(t_hi))  # 1 / L
                sq_lo, sq_hi = iadd(sq_lo, sq_hi, *isqr(t_lo, t_hi))
                set_row(m_lo, m_hi, leg, 2, t_lo, t_hi, b_lo, b_hi)
            set_norm(norms, leg, sq_lo, sq_hi, b_lo, b_hi)
            set_row(m_lo, m_hi, leg, 0, ux_lo, ux_hi, b_lo, b_hi)
            set_row(m_lo, m_hi, leg, 1, uy_lo, uy_hi, b_lo, b_hi)
            cbox = (cx_lo, cx_hi, cy_lo, cy_hi)
            mv, written = rr_leg(
                *cbox, leg, g[leg], zero, elbow, limits, mv_lo, mv_hi, scratch, leg, 0.0, nominal
            )
            if written and mv != OUT:  # its rows are written
                r = (rx_lo, rx_hi, ry_lo, ry_hi)
                tighten_row(m_lo, m_hi, mv_lo, mv_hi, norms, leg, n, r, length_cm)
        verdict[i] = state
        reason[i] = why
        kappa[i, 0] = 1.0
        kappa[i, 1] = math.inf
        if state != OUT and defined:
            kappa[i, 0], kappa[i, 1] = kappa_bounds(m_lo, m_hi, n, norms)

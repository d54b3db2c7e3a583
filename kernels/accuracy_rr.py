"""Pose error enclosures over (x, y) boxes of the robots with RR legs: the 3-RRR and the
five-bar (:mod:`kernels.accuracy`).

Leg ``i`` (the model of :mod:`kernels.singularity3rrr`): the elbow :math:`B_i = A_i + l_1
e_i`, :math:`e_i = (\\cos\\theta_i, \\sin\\theta_i)`, the distal link :math:`d_i = C_i -
B_i` of length :math:`l_2`, :math:`C_i = p + R(\\varphi) c_i`. The errors: the active angle
:math:`\\theta_i` within :math:`\\pm\\delta_\\theta` (``actuator_deg``); each coordinate
of :math:`A_i` and of :math:`c_i` (platform frame) and each leg's :math:`l_1`, :math:`l_2`
within :math:`\\pm t` (``tolerance_cm``), each leg's own. :math:`e_i` over the box in the
mode is :math:`(v_i - u_i) / l_1` (:math:`v_i = C_i - A_i`, :math:`u_i` enclosed by
:func:`kernels.singularity3rrr.leg_status`), turned by :math:`[-\\delta_\\theta,
\\delta_\\theta]`. With :math:`f_i = \\frac12(|d_i|^2 - l_2^2)` the residual bound is

.. math:: \\rho_i = |l_1|\\,|d_i \\cdot E e_i|\\,\\delta_\\theta
          + t\\,(|d_{ix}| + |d_{iy}|) + t\\,|R(\\varphi)^T d_i|_1
          + t\\,|d_i \\cdot e_i| + t\\,|l_2|

(the terms of :math:`\\theta_i, A_i, c_i, l_1, l_2`; every magnitude the largest over the
hull of the box and the perturbed robots).
"""

import numba
import numpy as np

from ._jit import kernel
from .accuracy import (
    BLOCK_ROWS,
    block_rows,
    joint_box,
    joint_terms,
    leg_scratch,
    mag,
    pose_offsets,
    settle,
    widen,
)
from .dexterity import IN, OUT, UNSURE, combine
from .interval import iadd, iadd_scalar, imul, iscale, isincos, isub, up
from .singularity3rrr import LEG_IN, LEG_OUT, TOLERANCE_CM, leg_status


@kernel
def rr_leg_terms(
    xlo, xhi, ylo, yhi, leg, g, zero, elbow, limits, errors, trig, w_lo, w_hi, r_lo, r_hi, rho
):
    """Leg ``leg``'s verdict over the pose box (``OUT``, ``UNSURE``, ``IN``), writing,
    where ``IN``, its rows of ``w`` (:math:`p - B_i`), ``r`` (:math:`R(\\varphi) c_i`, on
    entry its enclosure over the box's orientations, :func:`kernels.accuracy.pose_offsets`)
    and ``rho`` (module docstring). ``errors`` = ``(delta_theta_rad, t_cm, platform_cm)``,
    ``platform_cm`` the platform joints' tolerance (0: the five-bar); ``zero`` (legs, 2)
    zero offsets (the leg is tested over its platform joint's box)."""
    cx = joint_box(xlo, xhi, ylo, yhi, leg, r_lo, r_hi)
    status, ux_lo, ux_hi, uy_lo, uy_hi, _, _ = leg_status(*cx, leg, g, zero, elbow, limits)
    if status == LEG_OUT:
        return OUT
    if status != LEG_IN:
        return UNSURE
    delta, t = errors[0], errors[1]
    l1 = g[0]
    l2 = g[1]
    ax = g[8 + 2 * leg]
    ay = g[9 + 2 * leg]
    vx = widen(*iadd_scalar(cx[0], cx[1], -ax), TOLERANCE_CM)
    vy = widen(*iadd_scalar(cx[2], cx[3], -ay), TOLERANCE_CM)
    ex_lo, ex_hi = widen(*iscale(*isub(*vx, ux_lo, ux_hi), 1.0 / l1), 1e-15)
    ey_lo, ey_hi = widen(*iscale(*isub(*vy, uy_lo, uy_hi), 1.0 / l1), 1e-15)
    ex_lo, ex_hi = max(ex_lo, -1.0), min(ex_hi, 1.0)
    ey_lo, ey_hi = max(ey_lo, -1.0), min(ey_hi, 1.0)
    s_lo, s_hi, c_lo, c_hi = isincos(-delta, delta)
    px = isub(*imul(c_lo, c_hi, ex_lo, ex_hi), *imul(s_lo, s_hi, ey_lo, ey_hi))
    py = iadd(*imul(s_lo, s_hi, ex_lo, ex_hi), *imul(c_lo, c_hi, ey_lo, ey_hi))
    proximal = widen(l1, l1, t)
    bx = iadd(*widen(ax, ax, t), *imul(*proximal, *px))
    by = iadd(*widen(ay, ay, t), *imul(*proximal, *py))
    w_lo[leg, 0], w_hi[leg, 0] = isub(xlo, xhi, *bx)
    w_lo[leg, 1], w_hi[leg, 1] = isub(ylo, yhi, *by)
    dx, dy, joints = joint_terms(leg, errors, trig, w_lo, w_hi, r_lo, r_hi)
    turn = isub(*imul(*dy, *px), *imul(*dx, *py))  # d . E e
    along = iadd(*imul(*dx, *px), *imul(*dy, *py))  # d . e
    total = up(joints + up(up(mag(*proximal) * mag(*turn)) * delta))
    total = up(total + up(t * mag(*along)))
    rho[leg] = up(total + up(t * (l2 + t)))
    return IN


@kernel(parallel=True)
def rr_accuracy(boxes, g, q, elbow, limits, errors, verdict, bound):
    """Per row ``x_lo, x_hi, y_lo, y_hi, phi_lo, phi_hi`` of ``boxes`` (cm, rad): the
    verdict in the mode ``elbow`` (:mod:`kernels.dexterity`) and, where every leg closes
    (``IN``) at every pose of the box and the Krawczyk test holds, the bounds of
    :math:`|\\Delta x|, |\\Delta y|` (cm) and, three legs, :math:`|\\Delta\\varphi|` (rad)
    in ``bound`` (k, n); ``inf`` elsewhere. ``g`` and ``limits`` as
    :func:`kernels.dexterity_rr.rr_dexterity` takes them, ``q`` (legs, 2) the platform
    points in its frame (zero: the five-bar), ``errors`` as :func:`rr_leg_terms`."""
    n = len(g)
    zero = np.zeros((n, 2))
    for block in numba.prange((len(boxes) + BLOCK_ROWS - 1) // BLOCK_ROWS):
        w_lo, w_hi, r_lo, r_hi, rho = leg_scratch(n)
        start, stop = block_rows(block, len(boxes))
        for i in range(start, stop):
            trig = pose_offsets(boxes, i, q, n, r_lo, r_hi)
            state = IN
            for leg in range(n):
                v = rr_leg_terms(
                    boxes[i, 0],
                    boxes[i, 1],
                    boxes[i, 2],
                    boxes[i, 3],
                    leg,
                    g[leg],
                    zero,
                    elbow,
                    limits,
                    errors,
                    trig,
                    w_lo,
                    w_hi,
                    r_lo,
                    r_hi,
                    rho,
                )
                state = combine(state, v)
            settle(state, w_lo, w_hi, r_lo, r_hi, rho, n, verdict, bound, i)

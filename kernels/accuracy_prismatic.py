"""Pose error enclosures over (x, y) boxes of the robots with an actuated prismatic joint:
the 3-RPR and the 3-PRR (:mod:`kernels.accuracy`; the legs' models of
:mod:`kernels.dexterity_prismatic`). Their errors: the actuated length within
:math:`\\pm\\delta` (``actuator_cm``); each coordinate of the base points and of the platform
joints :math:`c_i` (platform frame) within :math:`\\pm t` (``tolerance_cm``), each leg's
own, and the 3-PRR's distal lengths within :math:`\\pm t`.

**3-RPR**: :math:`B_i = A_i`, the leg's length :math:`\\ell_i = \\rho_i` actuated:

.. math:: \\rho_i^{res} = |\\rho_i|\\,\\delta + t\\,(|d_{ix}| + |d_{iy}|) + t\\,|R^T d_i|_1.

**3-PRR**: the slider :math:`B_i = P_i + s_i u_i` on the line through :math:`P_i` of
direction :math:`u_i` (exact), :math:`s_i` actuated, the distal link of length :math:`l_i`:

.. math:: \\rho_i^{res} = |d_i \\cdot u_i|\\,\\delta + t\\,(|d_{ix}| + |d_{iy}|) + t\\,|R^T
          d_i|_1 + t\\,|l_i|

(:math:`\\partial f_i / \\partial s_i = -d_i \\cdot u_i`, :math:`\\partial f_i / \\partial
P_i = -d_i`, :math:`\\partial f_i / \\partial l_i = -l_i`). There :math:`p - B_i = d_i - s_i`
uses the mode's distal link enclosure, moved by the errors of :math:`P_i` and
:math:`s_i`.
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
from .dexterity_prismatic import TOLERANCE_CM, prr_parts, rpr_parts
from .interval import iadd, iscale, isub, up


@kernel
def rpr_leg_terms(
    xlo, xhi, ylo, yhi, leg, bases, zero, limits, errors, trig, w_lo, w_hi, r_lo, r_hi, rho
):
    """The 3-RPR leg ``leg``'s verdict over the pose box (``OUT``, ``UNSURE``, ``IN``: its
    length within its limits), writing where ``IN`` its rows of ``w``, ``r`` (on entry the
    enclosure of :math:`R(\\varphi) c_i`) and ``rho`` (module docstring; ``bases`` the
    :math:`A_i`, ``zero`` (3, 2) zero offsets, ``errors`` and ``trig`` as
    :func:`kernels.accuracy.joint_terms` takes them, the actuator's in cm)."""
    cx_lo, cx_hi, cy_lo, cy_hi = joint_box(xlo, xhi, ylo, yhi, leg, r_lo, r_hi)
    vx, vy, _, length = rpr_parts(cx_lo, cx_hi, cy_lo, cy_hi, leg, bases, zero, 0.0)
    if length[1] < limits[leg, 0] or length[0] > limits[leg, 1]:
        return OUT
    if not (limits[leg, 0] <= length[0] and length[1] <= limits[leg, 1]):
        return UNSURE
    delta, t = errors[0], errors[1]
    w_lo[leg, 0], w_hi[leg, 0] = widen(*isub(*vx, r_lo[leg, 0], r_hi[leg, 0]), t + TOLERANCE_CM)
    w_lo[leg, 1], w_hi[leg, 1] = widen(*isub(*vy, r_lo[leg, 1], r_hi[leg, 1]), t + TOLERANCE_CM)
    _, _, joints = joint_terms(leg, errors, trig, w_lo, w_hi, r_lo, r_hi)
    rho[leg] = up(joints + up(up(length[1] + delta) * delta))
    return IN


@kernel
def prr_leg_terms(
    xlo, xhi, ylo, yhi, leg, g, modes, zero, errors, trig, w_lo, w_hi, r_lo, r_hi, rho
):
    """The 3-PRR leg ``leg``'s verdict over the pose box in its mode ``modes[leg]``
    (``IN``: it closes with the slider within its stroke at every pose), writing where
    ``IN`` its rows of ``w``, ``r`` and ``rho`` (module docstring; ``g`` (3, 7) as
    :mod:`kernels.path_certify_prismatic`'s, the slider lines unshifted)."""
    cx_lo, cx_hi, cy_lo, cy_hi = joint_box(xlo, xhi, ylo, yhi, leg, r_lo, r_hi)
    reach, s, _, root, dx, dy, _, _ = prr_parts(
        cx_lo, cx_hi, cy_lo, cy_hi, leg, g, modes[leg], zero, 0.0
    )
    if not reach or s[1] < g[leg, 4] or s[0] > g[leg, 5]:
        return OUT
    if not (root[0] > 0.0 and g[leg, 4] <= s[0] and s[1] <= g[leg, 5]):
        return UNSURE
    delta, t = errors[0], errors[1]
    ux, uy = g[leg, 2], g[leg, 3]
    slide = (-delta, delta)
    wx = isub(*isub(*dx, r_lo[leg, 0], r_hi[leg, 0]), *iscale(*slide, ux))
    wy = isub(*isub(*dy, r_lo[leg, 1], r_hi[leg, 1]), *iscale(*slide, uy))
    w_lo[leg, 0], w_hi[leg, 0] = widen(*wx, t + TOLERANCE_CM)
    w_lo[leg, 1], w_hi[leg, 1] = widen(*wy, t + TOLERANCE_CM)
    ddx, ddy, joints = joint_terms(leg, errors, trig, w_lo, w_hi, r_lo, r_hi)
    along = iadd(*iscale(*ddx, ux), *iscale(*ddy, uy))
    rho[leg] = up(up(joints + up(mag(*along) * delta)) + up(t * (g[leg, 6] + t)))
    return IN


@kernel(parallel=True)
def rpr_accuracy(boxes, bases, q, limits, errors, verdict, bound):
    """Per row ``x_lo, x_hi, y_lo, y_hi, phi_lo, phi_hi`` of ``boxes`` (cm, rad): the
    3-RPR's verdict and, where every leg closes and the certificate of
    :mod:`kernels.accuracy` holds, the bounds of :math:`|\\Delta x|, |\\Delta y|` (cm),
    :math:`|\\Delta\\varphi|` (rad) in ``bound`` (k, 3); ``inf`` elsewhere. ``bases``
    the :math:`A_i`, ``q`` the platform points in its frame, ``limits`` (3, 2) cm."""
    zero = np.zeros((3, 2))
    for block in numba.prange((len(boxes) + BLOCK_ROWS - 1) // BLOCK_ROWS):
        w_lo, w_hi, r_lo, r_hi, rho = leg_scratch(3)
        start, stop = block_rows(block, len(boxes))
        for i in range(start, stop):
            trig = pose_offsets(boxes, i, q, 3, r_lo, r_hi)
            state = IN
            for leg in range(3):
                v = rpr_leg_terms(
                    boxes[i, 0],
                    boxes[i, 1],
                    boxes[i, 2],
                    boxes[i, 3],
                    leg,
                    bases,
                    zero,
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
            settle(state, w_lo, w_hi, r_lo, r_hi, rho, 3, verdict, bound, i)


@kernel(parallel=True)
def prr_accuracy(boxes, g, modes, q, errors, verdict, bound):
    """Per pose box of ``boxes``: the 3-PRR's verdict in the slider ``modes`` and, as
    :func:`rpr_accuracy`'s, its bounds (k, 3)."""
    zero = np.zeros((3, 2))
    for block in numba.prange((len(boxes) + BLOCK_ROWS - 1) // BLOCK_ROWS):
        w_lo, w_hi, r_lo, r_hi, rho = leg_scratch(3)
        start, stop = block_rows(block, len(boxes))
        for i in range(start, stop):
            trig = pose_offsets(boxes, i, q, 3, r_lo, r_hi)
            state = IN
            for leg in range(3):
                v = prr_leg_terms(
                    boxes[i, 0],
                    boxes[i, 1],
                    boxes[i, 2],
                    boxes[i, 3],
                    leg,
                    g,
                    modes,
                    zero,
                    errors,
                    trig,
                    w_lo,
                    w_hi,
                    r_lo,
                    r_hi,
                    rho,
                )
                state = combine(state, v)
            settle(state, w_lo, w_hi, r_lo, r_hi, rho, 3, verdict, bound, i)

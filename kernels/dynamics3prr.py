r"""Inverse dynamics of the 3-PRR by the Natural Orthogonal Complement (NOC).

Conventions of :mod:`kernels.dynamics3rrr`: y up, gravity :math:`(0, -g)`, SI units,
:math:`a\times b = a_x b_y - a_y b_x`, the independent coordinates the platform pose
:math:`X = (x, y, \varphi)`.

**Body model.** Leg ``i``: the *slider* translates along its rail (no rotation), its joint
and centre of mass at :math:`S_i = B_i + s_i u_i` (the actuated stroke :math:`s_i`); the
*link* of length :math:`l_i` joins :math:`S_i` to the platform joint
:math:`C_i = p + r_i`, :math:`r_i = R(\varphi) q_i`, along :math:`w_i = (C_i - S_i)/l_i`
(angle :math:`\psi_i`, :math:`\nu_i = k\times w_i`), its centre of mass mid-link. The
working mode :math:`\sigma_i` picks the stroke
:math:`s_i = g_i\cdot u_i + \sigma_i\sqrt{l_i^2 - (g_i\times u_i)^2}`,
:math:`g_i = C_i - B_i` (the slider ahead of or behind the foot of the perpendicular
from :math:`C_i` to its rail). The platform's centre of mass is its frame's origin.

**Leg kinematics.** :math:`\dot C_i = \dot s_i u_i + l_i\dot\psi_i\nu_i`; dotted with
:math:`w_i` and :math:`\nu_i` (:math:`u_i\cdot w_i = 0`: a serial, type I, singularity):

.. math:: \dot s_i = J_{s,i}\dot X,\; J_{s,i} = \frac{[w_i^T,\ r_i\times w_i]}
          {u_i\cdot w_i},\qquad
          \dot\psi_i = J_{\psi,i}\dot X,\; J_{\psi,i} = \frac{[\nu_i^T,\ r_i\times\nu_i]
          - (\nu_i\cdot u_i) J_{s,i}}{l_i},

and with :math:`h_i = \ddot C_i = \ddot p + \ddot\varphi\,k\times r_i - \dot\varphi^2 r_i`:
:math:`\ddot s_i = (w_i\cdot h_i + l_i\dot\psi_i^2)/(u_i\cdot w_i)`,
:math:`\ddot\psi_i = (\nu_i\cdot h_i - \ddot s_i\,\nu_i\cdot u_i)/l_i`.

**NOC.** Twists :math:`t_b = N_b\dot X`: slider :math:`N = [0;\ u J_s]`, link
:math:`N = [J_\psi;\ u J_s + \tfrac{l}{2}\nu J_\psi]`, platform
:math:`N = [0\,0\,1;\ I_2\,0]`; the generalised force
:math:`F = \sum_b N_b^T (M_b\dot t_b - w_b)` (:mod:`kernels.dynamics3rpr`) is, leg by leg,
:math:`J_s^T Q_s + J_\psi^T Q_\psi` with :math:`Q_s = u\cdot(f_s + f_l)`,
:math:`Q_\psi = I_l\ddot\psi + \tfrac{l}{2}\nu\cdot f_l`, :math:`f_b = m_b(\ddot c_b +
(0, g))`, :math:`\ddot c_s = \ddot s u`, :math:`\ddot c_l = \ddot s u +
\tfrac{l}{2}(\ddot\psi\nu - \dot\psi^2 w)`; plus the platform's
:math:`(m\ddot x, m(\ddot y + g), I\ddot\varphi)`. The slider forces (positive: pushing
the slider towards larger :math:`s_i`) solve :math:`A^T f = F`, :math:`A` the rows
:math:`J_{s,i}` (:math:`\det A = 0`: a parallel, type II, singularity).
"""

import numpy as np

from ._jit import kernel
from .dynamics3rrr import (
    NO_CLOSURE,
    OK,
    OUT_OF_LIMITS,
    SERIAL_SINGULAR,
    _finish_row,
)

#: Columns of a leg row: rail point, rail direction, platform point (platform frame), link
#: length, working mode sign, stroke limits (lengths in m).
LEG_BX, LEG_BY, LEG_UX, LEG_UY, LEG_QX, LEG_QY, LEG_L, LEG_SIGMA, LEG_LO, LEG_HI = range(10)
LEG_COLUMNS = 10
#: Entries of the body array: slider mass, link mass and inertia, platform's, gravity.
BODY_MS, BODY_ML, BODY_IL, BODY_M, BODY_I, BODY_G = range(6)
BODY_ENTRIES = 6


@kernel
def prr_path_dynamics(
    legs,
    body,
    pose,
    rate,
    acceleration,
    singular_relative,
    stroke,
    stroke_rate,
    stroke_acceleration,
    effort,
    status,
    closure,
):
    r"""Strokes, their rates and accelerations and the slider forces at every row of
    ``pose``, ``rate``, ``acceleration`` ((n, 3)); ``legs`` (3, :data:`LEG_COLUMNS`),
    ``body`` (:data:`BODY_ENTRIES`). Writes per row the outputs (n, 3; m, N), ``status``
    (``OK`` or ``code * 10 + leg``, the row's other outputs then NaN) and ``closure`` (the
    largest :math:`||C_i - S_i| - l_i|`, m): module docstring for the equations."""
    n = pose.shape[0]
    a = np.empty((3, 3))
    f = np.empty(3)
    ms, ml, il = body[BODY_MS], body[BODY_ML], body[BODY_IL]
    m, inertia, g = body[BODY_M], body[BODY_I], body[BODY_G]
    for k in range(n):
        x, y, phi = pose[k, 0], pose[k, 1], pose[k, 2]
        xd, yd, phid = rate[k, 0], rate[k, 1], rate[k, 2]
        xdd, ydd, phidd = acceleration[k, 0], acceleration[k, 1], acceleration[k, 2]
        c, s = np.cos(phi), np.sin(phi)
        f[0] = m * xdd
        f[1] = m * (ydd + g)
        f[2] = inertia * phidd
        code = OK
        worst = 0.0
        for i in range(3):
            ux, uy, link = legs[i, LEG_UX], legs[i, LEG_UY], legs[i, LEG_L]
            rx = c * legs[i, LEG_QX] - s * legs[i, LEG_QY]
            ry = s * legs[i, LEG_QX] + c * legs[i, LEG_QY]
            gx, gy = x + rx - legs[i, LEG_BX], y + ry - legs[i, LEG_BY]
            across = gx * uy - gy * ux
            squared = link * link - across * across
            if not squared >= 0.0:
                code = NO_CLOSURE * 10 + i + 1
                break
            st = gx * ux + gy * uy + legs[i, LEG_SIGMA] * np.sqrt(squared)
            if st < legs[i, LEG_LO] or st > legs[i, LEG_HI]:
                code = OUT_OF_LIMITS * 10 + i + 1
                break
            wx, wy = gx - st * ux, gy - st * uy
            length = np.sqrt(wx * wx + wy * wy)
            worst = max(worst, abs(length - link))
            wx, wy = wx / length, wy / length
            vx, vy = -wy, wx
            uw, uv = ux * wx + uy * wy, ux * vx + uy * vy
            if not abs(uw) >= singular_relative:
                code = SERIAL_SINGULAR * 10 + i + 1
                break
            cdx, cdy = xd - phid * ry, yd + phid * rx
            sd = (wx * cdx + wy * cdy) / uw
            psid = (vx * cdx + vy * cdy - sd * uv) / link
            hx = xdd - phidd * ry - phid * phid * rx
            hy = ydd + phidd * rx - phid * phid * ry
            sdd = (wx * hx + wy * hy + link * psid * psid) / uw
            psidd = (vx * hx + vy * hy - sdd * uv) / link
            # the bodies' forces f_b = m_b (c_b'' + (0, g))
            fsx, fsy = ms * sdd * ux, ms * (sdd * uy + g)
            half = 0.5 * link
            flx = ml * (sdd * ux + half * (psidd * vx - psid * psid * wx))
            fly = ml * (sdd * uy + half * (psidd * vy - psid * psid * wy) + g)
            q_s = ux * (fsx + flx) + uy * (fsy + fly)
            q_psi = il * psidd + half * (vx * flx + vy * fly)
            # F += J_s^T Q_s + J_psi^T Q_psi; row i of A is J_s
            a[i, 0], a[i, 1], a[i, 2] = wx / uw, wy / uw, (rx * wy - ry * wx) / uw
            f[0] += q_s * a[i, 0] + q_psi * (vx - uv * a[i, 0]) / link
            f[1] += q_s * a[i, 1] + q_psi * (vy - uv * a[i, 1]) / link
            f[2] += q_s * a[i, 2] + q_psi * (rx * vy - ry * vx - uv * a[i, 2]) / link
            stroke[k, i], stroke_rate[k, i], stroke_acceleration[k, i] = st, sd, sdd
        _finish_row(
            code,
            worst,
            a,
            f,
            k,
            singular_relative,
            stroke,
            stroke_rate,
            stroke_acceleration,
            effort,
            status,
            closure,
        )

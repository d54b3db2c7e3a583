r"""Inverse dynamics of the 3-RPR by the Natural Orthogonal Complement (NOC).

Conventions of :mod:`kernels.dynamics3rrr`: y up, gravity :math:`(0, -g)`, SI units,
:math:`a\times b = a_x b_y - a_y b_x`, the independent coordinates the platform pose
:math:`X = (x, y, \varphi)`.

**Body model.** Leg ``i`` joins the base joint :math:`A_i` (revolute) to the platform joint
:math:`C_i = p + r_i`, :math:`r_i = R(\varphi) q_i` (revolute), through an actuated
prismatic joint of length :math:`\rho_i = |C_i - A_i|`, direction :math:`e_i =
(C_i - A_i)/\rho_i`, :math:`n_i = k\times e_i`, leg angle :math:`\psi_i`. The *cylinder*
turns about :math:`A_i`, its centre of mass at :math:`A_i + c\,e_i` (``cylinder_com``
:math:`c`); the *piston* turns with the cylinder and slides in it, its centre of mass at
:math:`C_i - c_p e_i`, i.e. at the distance :math:`d_i = \rho_i - c_p` from :math:`A_i`.
The platform's centre of mass is the platform frame's origin :math:`p`.

**Leg kinematics.** :math:`\dot C_i = \dot p + \dot\varphi\,k\times r_i =
\dot\rho_i e_i + \rho_i\dot\psi_i n_i`, so

.. math:: \dot\rho_i = J_{\rho,i}\dot X,\; J_{\rho,i} = [e_i^T,\ r_i\times e_i],\qquad
          \dot\psi_i = J_{\psi,i}\dot X,\; J_{\psi,i} = [n_i^T,\ r_i\times n_i]/\rho_i,

and with :math:`h_i = \ddot C_i = \ddot p + \ddot\varphi\,k\times r_i - \dot\varphi^2 r_i`:
:math:`\ddot\rho_i = e_i\cdot h_i + \rho_i\dot\psi_i^2`,
:math:`\ddot\psi_i = (n_i\cdot h_i - 2\dot\rho_i\dot\psi_i)/\rho_i`.

**NOC.** Each body's twist :math:`t_b = (\omega_b, \dot c_b) = N_b\dot X`: cylinder
:math:`N = [J_\psi;\ c\,n J_\psi]`, piston :math:`N = [J_\psi;\ e J_\rho + d\,n J_\psi]`,
platform :math:`N = [0\,0\,1;\ I_2\,0]`. The generalised force in platform coordinates,

.. math:: F = \sum_b N_b^T (M_b\dot t_b - w_b),\quad M_b = \mathrm{diag}(I_b, m_b, m_b),
          \quad w_b = (0, 0, -m_b g),

is evaluated leg by leg as :math:`J_\rho^T Q_\rho + J_\psi^T Q_\psi`,
:math:`Q_\rho = e\cdot f_p`, :math:`Q_\psi = (I_c + I_p)\ddot\psi + c\,n\cdot f_c +
d\,n\cdot f_p`, with the bodies' forces :math:`f_b = m_b(\ddot c_b + (0, g))`, the centres'
accelerations :math:`\ddot c_c = c(\ddot\psi n - \dot\psi^2 e)` and :math:`\ddot c_p =
(\ddot\rho - d\dot\psi^2) e + (2\dot\rho\dot\psi + d\ddot\psi) n`; plus the platform's
:math:`(m\ddot x, m(\ddot y + g), I\ddot\varphi)`. The actuated rates are
:math:`\dot\rho = A\dot X` (rows :math:`J_{\rho,i}`), so by virtual power the leg forces
(positive: extending the leg) solve :math:`A^T f = F`; :math:`\det A = 0` (the three leg
lines concurrent or parallel) is a parallel (type II) singularity.
"""

import numpy as np

from ._jit import kernel
from .dynamics3rrr import (
    OK,
    OUT_OF_LIMITS,
    SERIAL_SINGULAR,
    _finish_row,
)

#: Columns of a leg row: base joint, platform point (platform frame), stroke limits (m).
LEG_AX, LEG_AY, LEG_QX, LEG_QY, LEG_LO, LEG_HI = range(6)
LEG_COLUMNS = 6
#: Entries of the body array: cylinder, piston (mass, inertia, centre of mass distance),
#: platform (mass, inertia), gravity.
BODY_MC, BODY_IC, BODY_CC, BODY_MP, BODY_IP, BODY_CP, BODY_M, BODY_I, BODY_G = range(9)
BODY_ENTRIES = 9


@kernel
def rpr_path_dynamics(
    legs,
    body,
    pose,
    rate,
    acceleration,
    singular_relative,
    rho,
    rho_rate,
    rho_acceleration,
    effort,
    status,
    closure,
):
    r"""Leg lengths, rates, accelerations and forces at every row of ``pose``, ``rate``,
    ``acceleration`` ((n, 3), :math:`(x, y, \varphi)`); ``legs`` (3, :data:`LEG_COLUMNS`),
    ``body`` (:data:`BODY_ENTRIES`). Writes per row the outputs (n, 3; m, N), ``status``
    (``OK`` or ``code * 10 + leg`` of the first problem, the row's other outputs then NaN)
    and ``closure`` (the largest :math:`|\rho_i e_i - (C_i - A_i)|`, m): module docstring."""
    n = pose.shape[0]
    a = np.empty((3, 3))
    f = np.empty(3)
    mc, ic, cc = body[BODY_MC], body[BODY_IC], body[BODY_CC]
    mp, ip, cp = body[BODY_MP], body[BODY_IP], body[BODY_CP]
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
            rx = c * legs[i, LEG_QX] - s * legs[i, LEG_QY]
            ry = s * legs[i, LEG_QX] + c * legs[i, LEG_QY]
            vx, vy = x + rx - legs[i, LEG_AX], y + ry - legs[i, LEG_AY]
            length = np.sqrt(vx * vx + vy * vy)
            if not length > 0.0:
                code = SERIAL_SINGULAR * 10 + i + 1
                break
            if length < legs[i, LEG_LO] or length > legs[i, LEG_HI]:
                code = OUT_OF_LIMITS * 10 + i + 1
                break
            ex, ey = vx / length, vy / length
            nx, ny = -ey, ex
            worst = max(worst, np.hypot(length * ex - vx, length * ey - vy))
            cdx, cdy = xd - phid * ry, yd + phid * rx
            rhod = ex * cdx + ey * cdy
            psid = (nx * cdx + ny * cdy) / length
            hx = xdd - phidd * ry - phid * phid * rx
            hy = ydd + phidd * rx - phid * phid * ry
            rhodd = ex * hx + ey * hy + length * psid * psid
            psidd = (nx * hx + ny * hy - 2.0 * rhod * psid) / length
            # the bodies' forces f_b = m_b (c_b'' + (0, g))
            fcx = mc * cc * (psidd * nx - psid * psid * ex)
            fcy = mc * (cc * (psidd * ny - psid * psid * ey) + g)
            d = length - cp
            along, across = rhodd - d * psid * psid, 2.0 * rhod * psid + d * psidd
            fpx = mp * (along * ex + across * nx)
            fpy = mp * (along * ey + across * ny + g)
            q_rho = ex * fpx + ey * fpy
            q_psi = (ic + ip) * psidd + cc * (nx * fcx + ny * fcy) + d * (nx * fpx + ny * fpy)
            # F += J_rho^T Q_rho + J_psi^T Q_psi; row i of A is J_rho
            a[i, 0], a[i, 1], a[i, 2] = ex, ey, rx * ey - ry * ex
            f[0] += q_rho * ex + q_psi * nx / length
            f[1] += q_rho * ey + q_psi * ny / length
            f[2] += q_rho * a[i, 2] + q_psi * (rx * ny - ry * nx) / length
            rho[k, i], rho_rate[k, i], rho_acceleration[k, i] = length, rhod, rhodd
        _finish_row(
            code,
            worst,
            a,
            f,
            k,
            singular_relative,
            rho,
            rho_rate,
            rho_acceleration,
            effort,
            status,
            closure,
        )

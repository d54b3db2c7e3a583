r"""Inverse dynamics of a platform carried by RR legs, by the Natural Orthogonal Complement.

The 3-RRR (three legs, platform pose :math:`X = (x, y, \varphi)`) and, with a point
platform and two legs, the five-bar (:mod:`kernels.dynamics5r`, :math:`X = (x, y)`) share
this kernel. Conventions of paper A's NOC (:mod:`kernels.dynamics`): y up, gravity
:math:`(0, -g)`, :math:`e(a) = (\cos a, \sin a)`, :math:`e^\perp(a) = (-\sin a, \cos a)`,
SI units, each link a rigid body with its centre of mass at mid-link.

**Leg i** (base joint :math:`A_i`, platform point :math:`q_i` in the platform frame,
proximal length :math:`l_1`, distal :math:`l_2`, elbow sign :math:`\sigma_i`): the platform
joint :math:`C_i = p + r_i`, :math:`r_i = R(\varphi) q_i`; the actuated angle
:math:`\theta_i = \alpha_i + \sigma_i\beta_i` with :math:`C_i - A_i = \rho_i e(\alpha_i)`,
:math:`\cos\beta_i = (\rho_i^2 + l_1^2 - l_2^2)/(2 l_1\rho_i)`; the elbow
:math:`B_i = A_i + l_1 e(\theta_i)`, the distal angle :math:`\psi_i` of :math:`C_i - B_i`.

**Leg Jacobians.** :math:`\dot C_i = \dot p + \dot\varphi\,k\times r_i = l_1\dot\theta_i
e^\perp(\theta_i) + l_2\dot\psi_i e^\perp(\psi_i)`; with :math:`s_i = \sin(\psi_i -
\theta_i)` (zero: a serial, type I, singularity)

.. math:: \dot\theta_i = J_{\theta,i}\dot X,\; J_{\theta,i} = \frac{[e(\psi_i)^T,\;
          r_i\times e(\psi_i)]}{l_1 s_i},\qquad
          \dot\psi_i = J_{\psi,i}\dot X,\; J_{\psi,i} = \frac{[e(\theta_i)^T,\;
          r_i\times e(\theta_i)]}{-l_2 s_i},

and the accelerations from the same 2x2 system with the right-hand side
:math:`\ddot C_i + l_1\dot\theta_i^2 e(\theta_i) + l_2\dot\psi_i^2 e(\psi_i)`,
:math:`\ddot C_i = \ddot p + \ddot\varphi\,k\times r_i - \dot\varphi^2 r_i`.

**NOC.** Each body's twist :math:`t_b = (\omega_b, \dot c_b)` is :math:`N_b\dot X`:
proximal link :math:`N = [J_\theta;\ \tfrac{l_1}{2}e^\perp(\theta)J_\theta]`, distal link
:math:`N = [J_\psi;\ l_1 e^\perp(\theta)J_\theta + \tfrac{l_2}{2}e^\perp(\psi)J_\psi]`,
platform :math:`N = [0\,0\,1;\ I_2\,0]`. The generalised force in platform coordinates is

.. math:: F = \sum_b N_b^T (M_b\dot t_b - w_b),\quad M_b = \mathrm{diag}(I_b, m_b, m_b),
          \quad w_b = (0, 0, -m_b g),

evaluated leg by leg as :math:`J_\theta^T Q_\theta + J_\psi^T Q_\psi` with
:math:`f_b = m_b(\ddot c_b + (0, g))`, :math:`Q_\theta = I_1\ddot\theta +
\tfrac{l_1}{2}e^\perp(\theta)\cdot f_1 + l_1 e^\perp(\theta)\cdot f_2`,
:math:`Q_\psi = I_2\ddot\psi + \tfrac{l_2}{2}e^\perp(\psi)\cdot f_2` (the legs' generalised
forces in absolute angles), plus the platform's :math:`(m_p\ddot x, m_p(\ddot y + g),
I_p\ddot\varphi)`. The actuated rates are :math:`\dot\theta_a = A\dot X` (rows
:math:`J_{\theta,i}`), so by virtual power the actuator torques solve
:math:`A^T\tau = F` (:math:`\det A = 0`: a parallel, type II, singularity).
"""

import numpy as np

from ._jit import kernel

#: Columns of a leg row: base joint, platform point (platform frame), lengths, elbow sign,
#: joint limit start and width (rad; a width of at least 2 pi: no limit).
LEG_AX, LEG_AY, LEG_QX, LEG_QY, LEG_L1, LEG_L2, LEG_SIGMA, LEG_LO, LEG_WIDTH = range(9)
LEG_COLUMNS = 9
#: Entries of the body array: link masses and inertias, platform mass and inertia, g.
BODY_M1, BODY_I1, BODY_M2, BODY_I2, BODY_MP, BODY_IP, BODY_G = range(7)
BODY_ENTRIES = 7
#: Status codes, ``code * 10 + leg`` (leg 1-based; 0 for a parallel singularity).
OK, NO_CLOSURE, OUT_OF_LIMITS, SERIAL_SINGULAR, PARALLEL_SINGULAR = range(5)


@kernel
def _solve_transposed(a, f, out, k, singular_relative):
    r"""Solve :math:`A^T\tau = F` (``a`` and ``f`` overwritten) into row ``k`` of ``out``
    by Gaussian elimination with partial pivoting; returns False when
    :math:`|\det A| < \epsilon\prod_i\|A_i\|` (rows' norms, :math:`\epsilon` =
    ``singular_relative``)."""
    n = a.shape[0]
    scale = 1.0
    for i in range(n):
        norm = 0.0
        for j in range(n):
            norm += a[i, j] * a[i, j]
        scale *= np.sqrt(norm)
    det = 1.0
    for col in range(n):  # eliminate on A^T: element (r, c) of A^T is a[c, r]
        pivot = col
        for r in range(col + 1, n):
            if abs(a[col, r]) > abs(a[col, pivot]):
                pivot = r
        if pivot != col:
            for c in range(n):
                a[c, col], a[c, pivot] = a[c, pivot], a[c, col]
            f[col], f[pivot] = f[pivot], f[col]
            det = -det
        det *= a[col, col]
        if a[col, col] == 0.0:
            return False
        for r in range(col + 1, n):
            factor = a[col, r] / a[col, col]
            for c in range(col, n):
                a[c, r] -= factor * a[c, col]
            f[r] -= factor * f[col]
    if not abs(det) >= singular_relative * scale:
        return False
    for r in range(n - 1, -1, -1):
        total = f[r]
        for c in range(r + 1, n):
            total -= a[c, r] * out[k, c]
        out[k, r] = total / a[r, r]
    return True


@kernel(inline=True)
def _finish_row(
    code, worst, a, f, k, singular_relative, q, q_rate, q_acceleration, effort, status, closure
):
    r"""Row ``k``'s end, shared by the path kernels: where every leg closed (``code`` is
    ``OK``) the efforts :math:`\tau` from :math:`A^T\tau = F` (:func:`_solve_transposed`,
    else ``PARALLEL_SINGULAR``); the row's ``status`` and ``closure``; a row with a problem
    has NaN actuator coordinates ``q``, rates, accelerations, efforts and closure."""
    if code == OK and not _solve_transposed(a, f, effort, k, singular_relative):
        code = PARALLEL_SINGULAR * 10
    status[k] = code
    closure[k] = worst
    if code != OK:
        for i in range(q.shape[1]):
            q[k, i] = q_rate[k, i] = q_acceleration[k, i] = np.nan
            effort[k, i] = np.nan
        closure[k] = np.nan


@kernel
def rr_path_dynamics(
    legs,
    body,
    pose,
    rate,
    acceleration,
    singular_relative,
    theta,
    theta_rate,
    theta_acceleration,
    effort,
    status,
    closure,
):
    r"""Leg kinematics and actuator torques at every row of ``pose``, ``rate``,
    ``acceleration`` ((n, d), d = 3: :math:`(x, y, \varphi)`; d = 2: a point platform,
    :math:`(x, y)`, as many legs as d); ``legs`` (d, :data:`LEG_COLUMNS`), ``body``
    (:data:`BODY_ENTRIES`). Writes per row the actuated angles, rates and accelerations
    (n, d), the torques (n, d; N m), ``status`` (:data:`OK`, or ``code * 10 + leg`` of the
    first problem, the row's other outputs then NaN) and ``closure`` (the largest
    :math:`||C_i - B_i| - l_2|` over the legs, m): module docstring for the equations."""
    n, d = pose.shape
    a = np.empty((d, d))
    f = np.empty(d)
    m1, i1, m2, i2 = body[BODY_M1], body[BODY_I1], body[BODY_M2], body[BODY_I2]
    mp, ip, g = body[BODY_MP], body[BODY_IP], body[BODY_G]
    for k in range(n):
        x, y, xd, yd = pose[k, 0], pose[k, 1], rate[k, 0], rate[k, 1]
        xdd, ydd = acceleration[k, 0], acceleration[k, 1]
        phi = pose[k, 2] if d == 3 else 0.0
        phid = rate[k, 2] if d == 3 else 0.0
        phidd = acceleration[k, 2] if d == 3 else 0.0
        c, s = np.cos(phi), np.sin(phi)
        f[0] = mp * xdd
        f[1] = mp * (ydd + g)
        if d == 3:
            f[2] = ip * phidd
        code = OK
        worst = 0.0
        for i in range(d):
            ax, ay, l1, l2 = legs[i, LEG_AX], legs[i, LEG_AY], legs[i, LEG_L1], legs[i, LEG_L2]
            rx = c * legs[i, LEG_QX] - s * legs[i, LEG_QY]
            ry = s * legs[i, LEG_QX] + c * legs[i, LEG_QY]
            vx, vy = x + rx - ax, y + ry - ay
            rho = np.sqrt(vx * vx + vy * vy)
            cosine = (rho * rho + l1 * l1 - l2 * l2) / (2.0 * l1 * rho) if rho > 0.0 else 2.0
            if not abs(cosine) <= 1.0:
                code = NO_CLOSURE * 10 + i + 1
                break
            th = np.arctan2(vy, vx) + legs[i, LEG_SIGMA] * np.arccos(cosine)
            lo = legs[i, LEG_LO]
            th = lo + (th - lo) % (2.0 * np.pi)
            if th - lo > legs[i, LEG_WIDTH] + 1e-12:
                code = OUT_OF_LIMITS * 10 + i + 1
                break
            ct, st = np.cos(th), np.sin(th)
            ux, uy = vx - l1 * ct, vy - l1 * st
            length = np.sqrt(ux * ux + uy * uy)
            worst = max(worst, abs(length - l2))
            cp, sp = ux / length, uy / length
            sn = sp * ct - cp * st
            if not abs(sn) >= singular_relative:
                code = SERIAL_SINGULAR * 10 + i + 1
                break
            cdx, cdy = xd - phid * ry, yd + phid * rx
            thd = (cp * cdx + sp * cdy) / (l1 * sn)
            psd = -(ct * cdx + st * cdy) / (l2 * sn)
            hx = xdd - phidd * ry - phid * phid * rx + l1 * thd * thd * ct + l2 * psd * psd * cp
            hy = ydd + phidd * rx - phid * phid * ry + l1 * thd * thd * st + l2 * psd * psd * sp
            thdd = (cp * hx + sp * hy) / (l1 * sn)
            psdd = -(ct * hx + st * hy) / (l2 * sn)
            # centre-of-mass accelerations and the links' forces f_b = m_b (c_b'' + (0, g))
            bx = l1 * (-thdd * st - thd * thd * ct)
            by = l1 * (thdd * ct - thd * thd * st)
            f1x, f1y = m1 * 0.5 * bx, m1 * (0.5 * by + g)
            f2x = m2 * (bx + 0.5 * l2 * (-psdd * sp - psd * psd * cp))
            f2y = m2 * (by + 0.5 * l2 * (psdd * cp - psd * psd * sp) + g)
            q_theta = i1 * thdd + 0.5 * l1 * (-st * f1x + ct * f1y) + l1 * (-st * f2x + ct * f2y)
            q_psi = i2 * psdd + 0.5 * l2 * (-sp * f2x + cp * f2y)
            # F += J_theta^T Q_theta + J_psi^T Q_psi; row i of A is J_theta
            jt, jp = 1.0 / (l1 * sn), -1.0 / (l2 * sn)
            a[i, 0], a[i, 1] = cp * jt, sp * jt
            f[0] += q_theta * cp * jt + q_psi * ct * jp
            f[1] += q_theta * sp * jt + q_psi * st * jp
            if d == 3:
                a[i, 2] = (rx * sp - ry * cp) * jt
                f[2] += q_theta * a[i, 2] + q_psi * (rx * st - ry * ct) * jp
            theta[k, i], theta_rate[k, i], theta_acceleration[k, i] = th, thd, thdd
        _finish_row(
            code,
            worst,
            a,
            f,
            k,
            singular_relative,
            theta,
            theta_rate,
            theta_acceleration,
            effort,
            status,
            closure,
        )


def solve_legs(dynamics, legs, body, pose, rate, acceleration, singular_relative):
    """``dynamics`` (:func:`rr_path_dynamics`, :func:`kernels.dynamics3rpr.rpr_path_dynamics`
    or :func:`kernels.dynamics3prr.prr_path_dynamics`) with its outputs allocated, one
    column per pose coordinate: ``(coordinate, rate, acceleration, effort, status,
    closure)``."""
    pose = np.ascontiguousarray(pose, dtype=np.float64)
    n, d = pose.shape
    outputs = [np.empty((n, d)) for _ in range(4)]
    status = np.empty(n, dtype=np.int64)
    closure = np.empty(n)
    dynamics(
        np.ascontiguousarray(legs, dtype=np.float64),
        np.ascontiguousarray(body, dtype=np.float64),
        pose,
        np.ascontiguousarray(rate, dtype=np.float64),
        np.ascontiguousarray(acceleration, dtype=np.float64),
        singular_relative,
        *outputs,
        status,
        closure,
    )
    return (*outputs, status, closure)


def solve_rr_path(legs, body, pose, rate, acceleration, singular_relative):
    """:func:`rr_path_dynamics` with its outputs allocated (:func:`solve_legs`):
    ``(theta, theta_rate, theta_acceleration, effort, status, closure)``."""
    return solve_legs(rr_path_dynamics, legs, body, pose, rate, acceleration, singular_relative)

r"""O(n) forward dynamics of a planar serial revolute chain: the articulated-body algorithm.

Same model, conventions and arguments as :func:`kernels.dynamics.forward_dynamics` (NOC,
paper A eqs. 1-8; y up, gravity :math:`(0,-g)`, relative joint angles, centre of mass at
mid-link, :math:`I_i` about it), evaluated by Featherstone's articulated-body recursion
specialised to the plane. Every link quantity is a planar spatial vector in world axes
taken **at the link's joint** :math:`p_i` (so the joint axis is the constant
:math:`S = (1, 0, 0)`): motions :math:`A = (\dot\Omega, a_x, a_y)` (angular and classical
linear acceleration of the point :math:`p_i`), forces :math:`f = (n, f_x, f_y)` (moment
about :math:`p_i`, force).

* Link inertia about :math:`p_i` (:math:`c = a_i/2`):
  :math:`\mathcal I_i = \begin{bmatrix} I_i + m_i|c|^2 & -m_i c_y & m_i c_x\\ -m_i c_y & m_i & 0\\
  m_i c_x & 0 & m_i\end{bmatrix}`, velocity-product wrench :math:`\beta_i = (0, -m_i\Omega_i^2 c)`.
* Joint i+1 seen from joint i: :math:`A_{i+1} = X_i A_i + S\ddot\theta_{i+1} + b_{i+1}` with
  the translation :math:`X_i A = (\dot\Omega, a + \dot\Omega E a_i)` and
  :math:`b_{i+1} = (0, -\Omega_i^2 a_i)`; forces go back by :math:`X_i^T f = (n + a_i\times F, F)`.
  Gravity is the base acceleration :math:`A_0 = (0, 0, g)`.

**Tip to base** (articulated inertia :math:`\mathcal I^A_i`, bias :math:`p^A_i`, with
:math:`f_i = \mathcal I^A_i A_i + p^A_i`):

.. math:: \mathcal I^A_i = \mathcal I_i + X_i^T J_{i+1} X_i,\quad p^A_i = \beta_i + X_i^T\pi_{i+1},\quad
          D_i = \mathcal I^A_{i,00},\ U_i = \mathcal I^A_i S,\ u_i = \tau_i - p^A_{i,0},

.. math:: J_i = \mathcal I^A_i - U_iU_i^T/D_i,\qquad \pi_i = p^A_i + J_i b_i + U_i u_i/D_i .

Because :math:`S = e_0`, :math:`J_i` has a zero first row and column: what a revolute joint
passes to its parent is a 2×2 symmetric linear inertia (3 numbers) and a force, and
:math:`\pi_{i,0} = \tau_i` exactly.

**Base to tip**: :math:`A' = X_{i-1}A_{i-1} + b_i`,
:math:`\ddot\theta_i = (u_i - U_i\cdot A')/D_i`, :math:`A_i = A' + S\ddot\theta_i`.

About 60 multiply-adds, one division and one ``sincos`` per link: O(n) against the
O(n³) mass matrix + ``LDLᵀ`` of :mod:`kernels.dynamics`, cheaper from
:data:`ABA_MIN_LINKS` links on (measured, ``docs/dynamics.md``).
:func:`forward_dynamics_rows_auto` is the one place that picks the algorithm.
"""

import numpy as np

from ._jit import kernel
from .dynamics import _forward_dynamics_rows

#: Chains of this many links or more take the articulated-body algorithm, shorter ones the
#: NOC mass matrix + LDLᵀ (measured: the recursion is faster from n = 3 on, by 1.1× at n = 6,
#: 1.2× at 7, 1.3× at 8, 2× at 20; the switch sits just above the bundled presets' 6 links
#: so their results keep every bit; docs/dynamics.md).
ABA_MIN_LINKS = 7

# Rows of the (9, n) work array: link vectors a_i, absolute rates, b_i = -Ω²_{i-1} a_{i-1}
# (-0.0 for the first link), then per joint 1/D_i, U_i1, U_i2 and u_i of the tip-to-base
# sweep.
_AX, _AY, _RATE, _INV_D, _U1, _U2, _BIAS, _BX, _BY = 0, 1, 2, 3, 4, 5, 6, 7, 8
ABA_WORK_ROWS = 9


@kernel
def aba_rows(
    lengths_m,
    masses_kg,
    inertias_kgm2,
    gravity_m_s2,
    theta_rad,
    omega_rad_s,
    tau_Nm,
    work,
    alpha_rad_s2,
    orow,
):
    r""":math:`\ddot\theta` of the chain into ``alpha_rad_s2[orow]`` by the planar
    articulated-body algorithm (module docstring). Parameters, state and torques are (n,)
    arrays, ``work`` is (9, n) scratch; allocation-free. (Written branch-free, statement
    by statement as the lane kernel :func:`kernels.motion_lanes._aba_lanes`.)"""
    n = lengths_m.shape[0]
    phi = 0.0
    rate = 0.0
    w2_prev = 0.0
    ax_prev = 0.0
    ay_prev = 0.0
    for i in range(n):
        phi += theta_rad[i]
        rate += omega_rad_s[i]
        ax = lengths_m[i] * np.cos(phi)
        ay = lengths_m[i] * np.sin(phi)
        work[_AX, i] = ax
        work[_AY, i] = ay
        work[_RATE, i] = rate
        work[_BX, i] = -(w2_prev * ax_prev)
        work[_BY, i] = -(w2_prev * ay_prev)
        w2_prev = rate * rate
        ax_prev = ax
        ay_prev = ay
    # tip to base: J = (j11, j12, j22) and pi = (tau, p1, p2) from the child
    j11 = 0.0
    j12 = 0.0
    j22 = 0.0
    p0 = 0.0
    p1 = 0.0
    p2 = 0.0
    for kk in range(n):
        i = n - 1 - kk
        ax = work[_AX, i]
        ay = work[_AY, i]
        w2 = work[_RATE, i] * work[_RATE, i]
        mass = masses_kg[i]
        cx = 0.5 * ax
        cy = 0.5 * ay
        # X^T J X with e = E a_i = (-ay, ax): J e, e.J e
        je1 = j12 * ax - j11 * ay
        je2 = j22 * ax - j12 * ay
        d = inertias_kgm2[i] + mass * (cx * cx + cy * cy) + (ax * je2 - ay * je1)
        u1 = je1 - mass * cy
        u2 = je2 + mass * cx
        bias0 = p0 + (ax * p2 - ay * p1)
        bias1 = p1 - mass * w2 * cx
        bias2 = p2 - mass * w2 * cy
        u = tau_Nm[i] - bias0
        inv_d = 1.0 / d
        work[_INV_D, i] = inv_d
        work[_U1, i] = u1
        work[_U2, i] = u2
        work[_BIAS, i] = u
        k1 = u1 * inv_d
        k2 = u2 * inv_d
        j11 = mass + j11 - u1 * k1
        j12 = j12 - u1 * k2
        j22 = mass + j22 - u2 * k2
        bx = work[_BX, i]
        by = work[_BY, i]
        p0 = tau_Nm[i]
        p1 = bias1 + j11 * bx + j12 * by + k1 * u
        p2 = bias2 + j12 * bx + j22 * by + k2 * u
    # base to tip
    a0 = 0.0
    a1 = 0.0
    a2 = gravity_m_s2
    ax_prev = 0.0
    ay_prev = 0.0
    for i in range(n):
        a1 = a1 - a0 * ay_prev + work[_BX, i]
        a2 = a2 + a0 * ax_prev + work[_BY, i]
        ax_prev = work[_AX, i]
        ay_prev = work[_AY, i]
        qdd = (work[_BIAS, i] - work[_U1, i] * a1 - work[_U2, i] * a2) * work[_INV_D, i] - a0
        alpha_rad_s2[orow, i] = qdd
        a0 += qdd


@kernel
def aba_forward_dynamics(
    lengths_m, masses_kg, inertias_kgm2, gravity_m_s2, theta_rad, omega_rad_s, tau_Nm
):
    r"""Joint accelerations :math:`\ddot\theta` (n,) by the articulated-body algorithm
    (:func:`aba_rows`); same arguments as :func:`kernels.dynamics.forward_dynamics`."""
    n = lengths_m.shape[0]
    work = np.empty((ABA_WORK_ROWS, n))
    alpha = np.empty((1, n))
    aba_rows(
        lengths_m,
        masses_kg,
        inertias_kgm2,
        gravity_m_s2,
        theta_rad,
        omega_rad_s,
        tau_Nm,
        work,
        alpha,
        0,
    )
    return alpha[0]


@kernel
def uses_aba(n_links):
    """Whether :func:`forward_dynamics_rows_auto` takes the O(n) recursion for ``n_links``."""
    return n_links >= ABA_MIN_LINKS


@kernel
def auto_work(n):
    """Work arrays ``(work (9, n), matrix)`` of :func:`forward_dynamics_rows_auto`: the
    matrix is (n, n) for the NOC path, (1, 1) (unused) for the articulated-body one."""
    size = 1 if n >= ABA_MIN_LINKS else n
    return np.zeros((ABA_WORK_ROWS, n)), np.zeros((size, size))


@kernel
def forward_dynamics_rows_auto(
    lengths_m,
    masses_kg,
    inertias_kgm2,
    gravity_m_s2,
    theta_rad,
    omega_rad_s,
    tau_Nm,
    work,
    matrix,
    alpha_rad_s2,
    orow,
):
    r""":math:`\ddot\theta` into ``alpha_rad_s2[orow]``: the articulated-body algorithm for
    chains of :data:`ABA_MIN_LINKS` links or more, else the NOC mass matrix + ``LDLᵀ``
    (:func:`kernels.dynamics._forward_dynamics_rows`, unchanged to the last bit). Work
    arrays from :func:`auto_work`."""
    if lengths_m.shape[0] >= ABA_MIN_LINKS:
        aba_rows(
            lengths_m,
            masses_kg,
            inertias_kgm2,
            gravity_m_s2,
            theta_rad,
            omega_rad_s,
            tau_Nm,
            work,
            alpha_rad_s2,
            orow,
        )
    else:
        _forward_dynamics_rows(
            lengths_m,
            masses_kg,
            inertias_kgm2,
            gravity_m_s2,
            theta_rad,
            omega_rad_s,
            tau_Nm,
            work,
            matrix,
            alpha_rad_s2,
            orow,
            True,
        )

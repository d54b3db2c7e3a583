r"""Dynamics of an n-link planar serial revolute robot by the Natural Orthogonal Complement.

Paper A (Mehrafrooz et al. 2016), section 2, eqs. (1)-(8), with the conventions fixed by
the project (see ``docs/dynamics.md``): y up, gravity :math:`(0, -g)`,
:math:`E = \begin{bmatrix}0&-1\\1&0\end{bmatrix}` (rotation by +90°), relative joint angles
(link i's absolute angle :math:`\phi_i = \sum_{j\le i}\theta_j`), centre of mass at mid-link,
inertia :math:`I_i` about the centre of mass, and the planar term :math:`T^T W M T\dot\theta`
identically zero.

Notation used in every docstring:

* :math:`a_i = l_i u_i`, :math:`u_i = [\cos\phi_i, \sin\phi_i]^T` (eq. 1), joint positions
  :math:`p_1 = 0`, :math:`p_{i+1} = p_i + a_i`, centres of mass :math:`c_i = p_i + \tfrac12 a_i`;
* :math:`\Omega_i = \sum_{j\le i}\dot\theta_j` and :math:`\dot\Omega_i = \sum_{j\le i}\ddot\theta_j`,
  the absolute angular rate and acceleration of link i;
* twist of link i :math:`t_i = [\Omega_i, \dot c_i^T]^T`, :math:`t = T\dot\theta` (eq. 4);
* :math:`M = \mathrm{diag}(I_i, m_i, m_i)` (eq. 7), gravity wrench
  :math:`w_{G,i} = [0, 0, -m_i g]^T` (eq. 8 with its sign misprint corrected).

The equation of motion (eqs. 2-3) is

.. math::  I(\theta)\ddot\theta + C(\theta,\dot\theta)\dot\theta - \gamma = \tau,\qquad
           I = T^T M T,\quad C\dot\theta = T^T M \dot T\dot\theta,\quad \gamma = T^T w_G .

Inverse dynamics is evaluated as :math:`T^T(M T\ddot\theta + M\dot T\dot\theta - w_G)` by a
forward sweep (the twist rate :math:`T\ddot\theta + \dot T\dot\theta` of every link, i.e. the
centre-of-mass accelerations, with gravity entered as an upward base acceleration) and a
backward sweep that applies :math:`T^T` as suffix sums over the lower-triangular blocks of
T: this is the recursive Newton-Euler algorithm, O(n) per evaluation, and equal to the NOC
expression term by term (tested against the dense product in ``tests/``).

The NOC terms as separate arrays (T, :math:`\dot T`, I, :math:`C\dot\theta`, :math:`\gamma`)
are in :mod:`kernels.noc_matrices`; this module holds the inverse and forward dynamics, the
energies and the building blocks both use; the batched inverse dynamics (S samples in
parallel) are in :mod:`kernels.dynamics_batch`.

All functions take float64 arrays and are compiled with :func:`kernels._jit.kernel`, so they
can be called both from Python and from other kernels.
"""

import numpy as np

from ._jit import kernel

# ---------------------------------------------------------------------------------------
# Building blocks (allocation-free; work arrays are passed in)
# ---------------------------------------------------------------------------------------


# Rows of the kinematics work array ``kin`` (6, n) shared by the building blocks.
_UX, _UY, _RATE, _ACCEL, _FX, _FY = 0, 1, 2, 3, 4, 5
_KIN_ROWS = 6


@kernel
def _link_kinematics(theta_rad, omega_rad_s, alpha_rad_s2, row, kin):
    r"""Absolute link directions, rates and accelerations from relative joint values.

    .. math:: \phi_i = \sum_{j\le i}\theta_j,\; u_i = [\cos\phi_i,\sin\phi_i],\;
              \Omega_i = \sum_{j\le i}\dot\theta_j,\; \dot\Omega_i = \sum_{j\le i}\ddot\theta_j

    Reads row ``row`` of the (·, n) state arrays, writes rows ``_UX.._ACCEL`` of ``kin``.
    (Building blocks index 2-D arrays by row instead of taking row views: a view per
    sample costs about as much as the whole 6R evaluation.)
    """
    phi = 0.0
    w = 0.0
    wd = 0.0
    for i in range(theta_rad.shape[1]):
        phi += theta_rad[row, i]
        w += omega_rad_s[row, i]
        wd += alpha_rad_s2[row, i]
        kin[_UX, i] = np.cos(phi)
        kin[_UY, i] = np.sin(phi)
        kin[_RATE, i] = w
        kin[_ACCEL, i] = wd


@kernel
def _newton_euler(lengths_m, masses_kg, inertias_kgm2, prow, gravity_m_s2, kin, out, orow):
    r"""Recursive evaluation of :math:`\tau = T^T(M T\ddot\theta + M\dot T\dot\theta - w_G)`.

    Forward sweep: with :math:`\beta_i = \dot\Omega_i E u_i - \Omega_i^2 u_i`, the
    acceleration of joint i+1 is :math:`A_{i+1} = A_i + l_i\beta_i`, :math:`A_1 = (0, g)` (gravity
    as base acceleration, i.e. :math:`-w_G`), the centre of mass one
    :math:`A_i + \tfrac12 l_i\beta_i`, and :math:`f_i = m_i(A_i + \tfrac12 l_i\beta_i)`: the
    linear part of :math:`M(T\ddot\theta + \dot T\dot\theta) - w_G` (eqs. 4, 5, 8); the angular
    part is :math:`I_i\dot\Omega_i`.

    Backward sweep (:math:`T^T`, eq. 4, using :math:`(Ex)\cdot f = x\times f`):
    :math:`\tau_j = \sum_{i\ge j}[I_i\dot\Omega_i + (c_i - p_j)\times f_i]`, computed as
    :math:`\tau_j = \tau_{j+1} + a_j\times F_{j+1} + I_j\dot\Omega_j + \tfrac12 a_j\times f_j`,
    :math:`F_j = \sum_{i\ge j} f_i`.

    Parameters are read from row ``prow`` of the (·, n) parameter arrays, the link state
    from ``kin`` (rows ``_FX``, ``_FY`` are scratch), the torques go to ``out[orow]``.
    """
    n = lengths_m.shape[1]
    ax = 0.0
    ay = gravity_m_s2
    for i in range(n):
        length = lengths_m[prow, i]
        half = 0.5 * length
        w2 = kin[_RATE, i] * kin[_RATE, i]
        bx = -kin[_ACCEL, i] * kin[_UY, i] - w2 * kin[_UX, i]
        by = kin[_ACCEL, i] * kin[_UX, i] - w2 * kin[_UY, i]
        kin[_FX, i] = masses_kg[prow, i] * (ax + half * bx)
        kin[_FY, i] = masses_kg[prow, i] * (ay + half * by)
        ax += length * bx
        ay += length * by
    big_fx = 0.0
    big_fy = 0.0
    moment = 0.0
    for i in range(n - 1, -1, -1):
        hx = 0.5 * lengths_m[prow, i] * kin[_UX, i]
        hy = 0.5 * lengths_m[prow, i] * kin[_UY, i]
        fx = kin[_FX, i]
        fy = kin[_FY, i]
        moment += (
            inertias_kgm2[prow, i] * kin[_ACCEL, i]
            + hx * fy
            - hy * fx
            + 2.0 * (hx * big_fy - hy * big_fx)
        )
        big_fx += fx
        big_fy += fy
        out[orow, i] = moment


# Rows of the forward-dynamics work array (6, n) (same shape as ``kin``): link vectors
# a_i, joint positions p_i, and the linear wrenches f_i (rows _FX, _FY) of the bias sweep.
_LX, _LY, _PX, _PY = 0, 1, 2, 3


@kernel
def _forward_dynamics_rows(
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
    solve,
):
    r""":math:`\ddot\theta = I^{-1}(\tau - (C\dot\theta - \gamma))` into ``alpha_rad_s2[orow]``.

    Parameters, state and torques are (n,) arrays; ``work`` (6, n) and ``matrix`` (n, n)
    come from :func:`forward_dynamics_work`. With ``solve=False`` it stops after step 2:
    the lower triangle of ``matrix`` holds :math:`I(\theta)` and ``alpha_rad_s2[orow]``
    holds :math:`\tau - (C\dot\theta - \gamma)` (used by
    :func:`kernels.noc_matrices.mass_matrix`).

    One function body on purpose: the three steps as separate kernels cost ≈ 90 ns more per
    6R call (numba does not inline them and increments/decrements the reference count of
    every array argument around each call), about a third of the whole evaluation.

    1. **Base to tip**, trigonometry once for both the bias forces and the mass matrix:
       :math:`\phi_i = \sum_{j\le i}\theta_j`, :math:`a_i = l_i(\cos\phi_i, \sin\phi_i)` (eq. 1),
       :math:`p_1 = 0`, :math:`p_{i+1} = p_i + a_i`, and the Newton-Euler forward sweep of
       :func:`_newton_euler` at :math:`\dot\Omega = 0` (so :math:`l_i\beta_i = -\Omega_i^2 a_i`):
       :math:`A_1 = (0, g)`, :math:`f_i = m_i(A_i - \tfrac12\Omega_i^2 a_i)`,
       :math:`A_{i+1} = A_i - \Omega_i^2 a_i`.
    2. **Tip to base**, bias torques and mass matrix in the same loop. Bias:
       :math:`(C\dot\theta - \gamma)_k = b_{k+1} + a_k\times F_{k+1} + \tfrac12 a_k\times f_k`,
       :math:`F_k = \sum_{i\ge k} f_i`. Mass matrix (eq. 4 block-wise, E orthogonal), for
       :math:`j \le k`:

       .. math:: I_{jk} = \sum_{i\ge k} [I_i + m_i (c_i-p_j)\cdot(c_i-p_k)] = D_k + (p_k - p_j)\cdot h_k,

       :math:`D_k = \sum_{i\ge k}[I_i + m_i|c_i - p_k|^2]`, :math:`h_k = \sum_{i\ge k} m_i (c_i - p_k)`,
       inertia and first moment of the composite of links k..n about joint k; with
       :math:`\mathcal M_{k+1} = \sum_{i>k} m_i`:
       :math:`D_k = D_{k+1} + 2a_k\cdot h_{k+1} + \mathcal M_{k+1}l_k^2 + I_k + \tfrac14 m_k l_k^2`,
       :math:`h_k = h_{k+1} + \mathcal M_{k+1}a_k + \tfrac12 m_k a_k`. O(n²), no division;
       only ``matrix[k, j]``, ``j <= k``, is written (row k is contiguous).
    3. **Square-root-free Cholesky solve** of the SPD system, :math:`I = L D L^T` (L unit
       lower triangular, D diagonal), row by row and fused with the forward substitution:
       with :math:`w_{ij} = L_{ij} d_j`, :math:`w_{ij} = I_{ij} - \sum_{k<j} w_{ik} L_{jk}`,
       :math:`d_i = I_{ii} - \sum_{k<i} w_{ik} L_{ik}`, :math:`L_{ik} = w_{ik} / d_k`, and
       :math:`z = D^{-1}L^{-1}b`, :math:`z_i = (b_i - \sum_{k<i} w_{ik} z_k) / d_i` (as
       :math:`L_{ik} d_k z_k = w_{ik} z_k`); then :math:`L^T x = z` column-wise from the last
       row. Every inner loop runs along a contiguous row; L overwrites the strict lower
       triangle and :math:`1/d_i` the diagonal. Against :math:`LL^T` this saves n square
       roots and n divisions (≈ 50 ns of ≈ 300 ns per 6R call, measured). No allocation.
    """
    n = lengths_m.shape[0]
    # 1. base to tip
    phi = 0.0
    rate = 0.0
    acc_x = 0.0
    acc_y = gravity_m_s2
    px = 0.0
    py = 0.0
    for i in range(n):
        phi += theta_rad[i]
        rate += omega_rad_s[i]
        ax = lengths_m[i] * np.cos(phi)
        ay = lengths_m[i] * np.sin(phi)
        w2 = rate * rate
        work[_LX, i] = ax
        work[_LY, i] = ay
        work[_PX, i] = px
        work[_PY, i] = py
        work[_FX, i] = masses_kg[i] * (acc_x - 0.5 * w2 * ax)
        work[_FY, i] = masses_kg[i] * (acc_y - 0.5 * w2 * ay)
        acc_x -= w2 * ax
        acc_y -= w2 * ay
        px += ax
        py += ay
    # 2. tip to base
    big_fx = 0.0
    big_fy = 0.0
    bias = 0.0
    outer_mass = 0.0
    hx = 0.0
    hy = 0.0
    inertia = 0.0
    for kk in range(n):
        k = n - 1 - kk
        ax = work[_LX, k]
        ay = work[_LY, k]
        fx = work[_FX, k]
        fy = work[_FY, k]
        bias += 0.5 * (ax * fy - ay * fx) + ax * big_fy - ay * big_fx
        big_fx += fx
        big_fy += fy
        alpha_rad_s2[orow, k] = tau_Nm[k] - bias
        length = lengths_m[k]
        mass = masses_kg[k]
        inertia += (
            2.0 * (ax * hx + ay * hy)
            + (outer_mass + 0.25 * mass) * length * length
            + inertias_kgm2[k]
        )
        hx += (outer_mass + 0.5 * mass) * ax
        hy += (outer_mass + 0.5 * mass) * ay
        outer_mass += mass
        matrix[k, k] = inertia
        pkx = work[_PX, k]
        pky = work[_PY, k]
        for j in range(k):
            matrix[k, j] = inertia + (pkx - work[_PX, j]) * hx + (pky - work[_PY, j]) * hy
    if not solve:
        return
    # 3. LDL^T factor + forward substitution (row i holds w_ik = L_ik d_k until it is done)
    for i in range(n):
        for j in range(i):
            s = matrix[i, j]
            for k in range(j):
                s -= matrix[i, k] * matrix[j, k]
            matrix[i, j] = s
        d = matrix[i, i]
        y = alpha_rad_s2[orow, i]
        for k in range(i):
            w = matrix[i, k]
            l_ik = w * matrix[k, k]
            d -= l_ik * w
            matrix[i, k] = l_ik
            y -= w * alpha_rad_s2[orow, k]
        inv = 1.0 / d
        matrix[i, i] = inv
        alpha_rad_s2[orow, i] = y * inv
    for ii in range(n):
        i = n - 1 - ii
        x = alpha_rad_s2[orow, i]
        for k in range(i):
            alpha_rad_s2[orow, k] -= matrix[i, k] * x


@kernel
def forward_dynamics_work(n):
    """Work arrays ``(kin (6, n), matrix (n, n))`` for :func:`forward_dynamics_into`."""
    return np.zeros((_KIN_ROWS, n)), np.zeros((n, n))


@kernel
def _row(vector):
    """(n,) -> (1, n) view (``vector[None, :]`` is free; ``reshape`` costs ~20 ns in numba)."""
    return vector[None, :]


@kernel
def _newton_euler_single(
    lengths_m, masses_kg, inertias_kgm2, gravity_m_s2, theta_rad, omega_rad_s, alpha_rad_s2
):
    """:func:`_newton_euler` of one robot in one state, all arguments (n,): (n,) torques."""
    n = lengths_m.shape[0]
    kin = np.empty((_KIN_ROWS, n))
    _link_kinematics(_row(theta_rad), _row(omega_rad_s), _row(alpha_rad_s2), 0, kin)
    tau = np.empty((1, n))
    _newton_euler(
        _row(lengths_m), _row(masses_kg), _row(inertias_kgm2), 0, gravity_m_s2, kin, tau, 0
    )
    return tau[0]


@kernel
def forward_dynamics_into(
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
):
    r"""Allocation-free :func:`forward_dynamics` writing into ``alpha_rad_s2`` (n,).

    ``work`` and ``matrix`` come from :func:`forward_dynamics_work`.
    """
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
        alpha_rad_s2[None, :],  # a (1, n) view, built in place
        0,
        True,
    )


@kernel
def energies(lengths_m, masses_kg, inertias_kgm2, gravity_m_s2, theta_rad, omega_rad_s):
    r"""Kinetic and potential energy ``(kinetic_J, potential_J)`` (paper A, section 2).

    .. math:: K = \tfrac12\dot\theta^T I(\theta)\dot\theta = \tfrac12 t^T M t
              = \tfrac12\sum_i\left(I_i\Omega_i^2 + m_i|\dot c_i|^2\right),\qquad
              V = \sum_i m_i g\, y_{c_i}

    (the base joint at height 0). O(n), allocation-free.
    """
    kinetic = 0.0
    potential = 0.0
    phi = 0.0
    rate = 0.0
    vx = 0.0
    vy = 0.0
    y = 0.0
    for i in range(lengths_m.shape[0]):
        phi += theta_rad[i]
        rate += omega_rad_s[i]
        c = np.cos(phi)
        s = np.sin(phi)
        half = 0.5 * lengths_m[i]
        # ċ_i = v(p_i) + ½ l_i Ω_i E u_i
        cvx = vx - half * rate * s
        cvy = vy + half * rate * c
        kinetic += 0.5 * (inertias_kgm2[i] * rate * rate + masses_kg[i] * (cvx * cvx + cvy * cvy))
        potential += masses_kg[i] * gravity_m_s2 * (y + half * s)
        vx -= lengths_m[i] * rate * s
        vy += lengths_m[i] * rate * c
        y += lengths_m[i] * s
    return kinetic, potential


# ---------------------------------------------------------------------------------------
# Public API
# ---------------------------------------------------------------------------------------


@kernel
def inverse_dynamics(
    lengths_m, masses_kg, inertias_kgm2, gravity_m_s2, theta_rad, omega_rad_s, alpha_rad_s2
):
    r"""Joint torques :math:`\tau = I(\theta)\ddot\theta + C(\theta,\dot\theta)\dot\theta - \gamma`, eq. (2).

    Evaluated recursively as :math:`\tau = T^T(M T\ddot\theta + M\dot T\dot\theta - w_G)`
    (Newton-Euler sweeps over the lower-triangular blocks of T, O(n)).

    Parameters
    ----------
    lengths_m, masses_kg, inertias_kgm2 : (n,) float64
        Link lengths, masses and centroidal moments of inertia.
    gravity_m_s2 : float
        g >= 0; gravity acts along -y.
    theta_rad, omega_rad_s, alpha_rad_s2 : (n,) float64
        Relative joint angles, rates and accelerations.

    Returns
    -------
    tau_Nm : (n,) float64
    """
    return _newton_euler_single(
        lengths_m, masses_kg, inertias_kgm2, gravity_m_s2, theta_rad, omega_rad_s, alpha_rad_s2
    )


@kernel
def forward_dynamics(
    lengths_m, masses_kg, inertias_kgm2, gravity_m_s2, theta_rad, omega_rad_s, tau_Nm
):
    r"""Joint accelerations :math:`\ddot\theta = I^{-1}(\tau + \gamma - C\dot\theta)`, eq. (2).

    :math:`C\dot\theta - \gamma` comes from the Newton-Euler sweeps at :math:`\ddot\theta = 0`,
    I from the composite-body sums of :func:`kernels.noc_matrices.mass_matrix`, and the SPD system is solved by a
    hand-written square-root-free Cholesky (LDLᵀ). For loops use :func:`forward_dynamics_into` with
    work arrays from :func:`forward_dynamics_work` (no allocation).

    Returns
    -------
    alpha_rad_s2 : (n,) float64
    """
    work, matrix = forward_dynamics_work(lengths_m.shape[0])
    alpha = np.empty(lengths_m.shape[0])
    forward_dynamics_into(
        lengths_m,
        masses_kg,
        inertias_kgm2,
        gravity_m_s2,
        theta_rad,
        omega_rad_s,
        tau_Nm,
        work,
        matrix,
        alpha,
    )
    return alpha

r"""The NOC matrices of an n-link planar serial revolute robot, each as its own array.

Paper A (Mehrafrooz et al. 2016), section 2, eqs. (3)-(8), with the conventions and the
notation of :mod:`kernels.dynamics` (y up, gravity :math:`(0, -g)`,
:math:`E = \begin{bmatrix}0&-1\\1&0\end{bmatrix}`, relative joint angles,
:math:`a_i = l_i u_i`, joints :math:`p_i`, centres of mass :math:`c_i = p_i + \tfrac12 a_i`,
absolute rates :math:`\Omega_i`, :math:`M = \mathrm{diag}(I_i, m_i, m_i)`, gravity wrench
:math:`w_{G,i} = [0, 0, -m_i g]^T`):

* twist-shaping matrix T (3n × n), :math:`t = T\dot\theta` (eq. 4), and its rate
  :math:`\dot T` (eq. 5), dense, for tests and documentation;
* generalised inertia :math:`I(\theta) = T^T M T`, velocity product
  :math:`C(\theta,\dot\theta)\dot\theta = T^T M \dot T\dot\theta` and generalised gravity
  :math:`\gamma = T^T w_G` (eqs. 3, 8), the terms of the equation of motion (eq. 2)

.. math::  I(\theta)\ddot\theta + C(\theta,\dot\theta)\dot\theta - \gamma = \tau .

I, :math:`C\dot\theta` and :math:`\gamma` are evaluated without forming T or M, by the
building blocks of :mod:`kernels.dynamics` (the composite-body sums of its forward dynamics,
the Newton-Euler sweeps of its inverse dynamics): the same arithmetic as those kernels.
All functions take float64 arrays and are compiled with :func:`kernels._jit.kernel`.
"""

import numpy as np

from ._jit import kernel
from .dynamics import _forward_dynamics_rows, _newton_euler_single, _row, forward_dynamics_work


@kernel
def twist_shaping_matrix(lengths_m, theta_rad):
    r"""Twist-shaping matrix T (3n × n), paper A eq. (4): :math:`t = T\dot\theta`.

    Block (i, j) (rows 3i..3i+2, column j) is

    .. math:: T_{ij} = \begin{bmatrix}1\\ E\left(\sum_{k=j}^{i-1} a_k + \tfrac12 a_i\right)\end{bmatrix}
              = \begin{bmatrix}1\\ E(c_i - p_j)\end{bmatrix}\ (i\ge j),\qquad T_{ij} = 0\ (i<j).

    The twist of link i is ordered :math:`[\Omega_i, \dot c_{i,x}, \dot c_{i,y}]`. Dense; meant
    for tests and documentation, the dynamics kernels never form it.
    """
    n = lengths_m.shape[0]
    out = np.zeros((3 * n, n))
    px = np.zeros(n + 1)
    py = np.zeros(n + 1)
    phi = 0.0
    for i in range(n):
        phi += theta_rad[i]
        px[i + 1] = px[i] + lengths_m[i] * np.cos(phi)
        py[i + 1] = py[i] + lengths_m[i] * np.sin(phi)
    for i in range(n):
        cx = 0.5 * (px[i] + px[i + 1])
        cy = 0.5 * (py[i] + py[i + 1])
        for j in range(i + 1):
            out[3 * i, j] = 1.0
            out[3 * i + 1, j] = -(cy - py[j])
            out[3 * i + 2, j] = cx - px[j]
    return out


@kernel
def twist_shaping_matrix_rate(lengths_m, theta_rad, omega_rad_s):
    r"""Time derivative :math:`\dot T` (3n × n), paper A eq. (5).

    .. math:: \dot T_{ij} = \begin{bmatrix}0\\ -\left(\sum_{k=j}^{i-1}\Omega_k a_k
              + \tfrac12\Omega_i a_i\right)\end{bmatrix}\ (i\ge j),\qquad 0\ (i<j),

    with :math:`\Omega_k = \sum_{p\le k}\dot\theta_p` (since :math:`\dot a_k = \Omega_k E a_k` and
    :math:`E^2 = -1`).
    """
    n = lengths_m.shape[0]
    out = np.zeros((3 * n, n))
    # q[i] = Σ_{k<i} Ω_k a_k (prefix sums), so Σ_{k=j}^{i-1} Ω_k a_k = q[i] − q[j].
    qx = np.zeros(n + 1)
    qy = np.zeros(n + 1)
    phi = 0.0
    rate = 0.0
    for i in range(n):
        phi += theta_rad[i]
        rate += omega_rad_s[i]
        qx[i + 1] = qx[i] + rate * lengths_m[i] * np.cos(phi)
        qy[i + 1] = qy[i] + rate * lengths_m[i] * np.sin(phi)
    for i in range(n):
        hx = 0.5 * (qx[i + 1] - qx[i])
        hy = 0.5 * (qy[i + 1] - qy[i])
        for j in range(i + 1):
            out[3 * i + 1, j] = -(qx[i] - qx[j] + hx)
            out[3 * i + 2, j] = -(qy[i] - qy[j] + hy)
    return out


@kernel
def mass_matrix(lengths_m, masses_kg, inertias_kgm2, theta_rad):
    r"""Generalised inertia matrix :math:`I(\theta) = T^T M T` (n × n), paper A eq. (3).

    Evaluated without forming T or M: for :math:`j\le k`,

    .. math:: I_{jk} = \sum_{i\ge k}\left[I_i + m_i (c_i - p_j)\cdot(c_i - p_k)\right]
              = D_k + (p_k - p_j)\cdot h_k,

    with :math:`D_k`, :math:`h_k` the inertia and first moment about joint k of the composite
    body of links k..n (suffix sums from the tip, O(n²) total; see
    :func:`kernels.dynamics._forward_dynamics_rows`).
    """
    n = lengths_m.shape[0]
    work, out = forward_dynamics_work(n)
    zeros = np.zeros(n)
    _forward_dynamics_rows(
        lengths_m,
        masses_kg,
        inertias_kgm2,
        0.0,
        theta_rad,
        zeros,
        zeros,
        work,
        out,
        _row(zeros),
        0,
        False,
    )
    for k in range(n):
        for j in range(k):
            out[j, k] = out[k, j]
    return out


@kernel
def velocity_product(lengths_m, masses_kg, inertias_kgm2, theta_rad, omega_rad_s):
    r"""Velocity-product vector :math:`C(\theta,\dot\theta)\dot\theta = T^T M\dot T\dot\theta`, eq. (3).

    The planar :math:`T^T W M T\dot\theta` term of eq. (3) is zero. Evaluated as inverse
    dynamics with :math:`\ddot\theta = 0` and :math:`g = 0`; :math:`\dot T\dot\theta` has the
    linear parts :math:`-\sum_{k<i}\Omega_k^2 a_k - \tfrac12\Omega_i^2 a_i` (eq. 5).
    """
    zeros = np.zeros(lengths_m.shape[0])
    return _newton_euler_single(
        lengths_m, masses_kg, inertias_kgm2, 0.0, theta_rad, omega_rad_s, zeros
    )


@kernel
def gravity_vector(lengths_m, masses_kg, gravity_m_s2, theta_rad):
    r"""Generalised gravity force :math:`\gamma = T^T w_G`, paper A eqs. (3), (8).

    .. math:: \gamma_j = \sum_{i\ge j} (c_i - p_j)\times(0, -m_i g) = -g\sum_{i\ge j} m_i (c_i - p_j)_x

    (link inertias do not enter; zeros are used.)
    """
    zeros = np.zeros(lengths_m.shape[0])
    tau = _newton_euler_single(lengths_m, masses_kg, zeros, gravity_m_s2, theta_rad, zeros, zeros)
    return -tau

r"""Joint torques of every row of a unit-hypercube sensitivity design, scaled on the fly.

The sensitivity engine's model (issue 3): row s of SALib's unit design u is the robot
:math:`x_s = u_s\,(x_{ub} - x_{lb}) + x_{lb}` (link lengths, masses, optionally inertias),
scaled with exactly the floating-point operations of ``SALib.util.scale_samples``, so the
torques are bit-identical to :func:`kernels.dynamics.inverse_dynamics_batch` on the scaled
matrix (tested) without materialising it or its column copies.
"""

import numpy as np
from numba import prange

from ._jit import kernel
from .dynamics import _CHUNK, _newton_euler, shared_link_kinematics


@kernel(parallel=True)
def design_torques(
    unit, lower, upper, inertias_kgm2, gravity_m_s2, theta_rad, omega_rad_s, alpha_rad_s2
):
    r"""Inverse dynamics :math:`\tau_s = I_s\ddot\theta + C_s\dot\theta - \gamma_s` (paper A
    eqs. 2-8) of the robot of every design row s, in one shared state.

    ``unit`` (S, D) float64 is the design, columns l1…ln, m1…mn and, when D = 3n, I1…In;
    ``lower``, ``upper`` (D,) its bounds (m, kg, kg m²); ``inertias_kgm2`` (n,) the
    inertias used when D = 2n; gravity and the shared state (θ, θ̇, θ̈, each (n,)) as in
    :func:`kernels.dynamics.inverse_dynamics_batch`. Returns the (S, n) torques, N m.
    """
    samples, num_vars = unit.shape
    n = theta_rad.shape[0]
    if num_vars != 2 * n and num_vars != 3 * n:
        raise ValueError("unit must have 2n or 3n columns")
    if lower.shape[0] != num_vars or upper.shape[0] != num_vars:
        raise ValueError("lower and upper must have one bound per design column")
    span = upper - lower
    shared = shared_link_kinematics(theta_rad, omega_rad_s, alpha_rad_s2)
    out = np.empty((samples, n))
    n_chunks = (samples + _CHUNK - 1) // _CHUNK
    for chunk in prange(n_chunks):
        kin = shared.copy()  # per task: rows _FX, _FY are scratch
        robot = np.empty((3, 1, n))  # one sample's lengths, masses, inertias
        for i in range(n):
            robot[2, 0, i] = inertias_kgm2[i]
        for s in range(chunk * _CHUNK, min(samples, (chunk + 1) * _CHUNK)):
            for column in range(num_vars):
                robot[column // n, 0, column % n] = unit[s, column] * span[column] + lower[column]
            _newton_euler(robot[0], robot[1], robot[2], 0, gravity_m_s2, kin, out, s)
    return out

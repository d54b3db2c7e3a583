r"""Batched inverse dynamics of n-link planar serial robots: S parameter sets in one shared
state (the Sobol'/eFAST hot path, :func:`inverse_dynamics_batch`), or one robot in S states
(:func:`inverse_dynamics_batch_states`), each sample by the Newton-Euler sweeps of
:func:`kernels.dynamics.inverse_dynamics`:

.. math::  \tau_s = T^T(M_s T\ddot\theta + M_s\dot T\dot\theta - w_{G,s})
           = I_s\ddot\theta + C_s\dot\theta - \gamma_s .

Samples are split into chunks of ``_CHUNK`` run in parallel (``prange``).
"""

import numpy as np
from numba import prange

from ._jit import kernel
from .dynamics import _KIN_ROWS, _link_kinematics, _newton_euler, _row

# Samples handled by one parallel task of the batched kernels; each task allocates its
# scratch once, so the per-sample loop itself never touches the heap.
_CHUNK = 1024


@kernel
def shared_link_kinematics(theta_rad, omega_rad_s, alpha_rad_s2):
    """The (6, n) link-state work array of one state (n,) shared by a batch's samples."""
    kin = np.empty((_KIN_ROWS, theta_rad.shape[0]))
    _link_kinematics(_row(theta_rad), _row(omega_rad_s), _row(alpha_rad_s2), 0, kin)
    return kin


@kernel(parallel=True)
def inverse_dynamics_batch(
    lengths_m, masses_kg, inertias_kgm2, gravity_m_s2, theta_rad, omega_rad_s, alpha_rad_s2
):
    r"""Inverse dynamics of S robots (own parameters each) in one shared state: (S, n) torques.

    For every sample s, :math:`\tau_s = T^T(M_s T\ddot\theta + M_s\dot T\dot\theta - w_{G,s})`
    :math:`= I_s\ddot\theta + C_s\dot\theta - \gamma_s` (eqs. 2-8), by the Newton-Euler sweeps of
    :func:`inverse_dynamics`. The hot path of the Sobol/eFAST engine: the state-dependent
    trigonometry and absolute rates are computed once, samples are split into chunks of
    1024 run in parallel (``prange``), each chunk copies the (6, n) link-state work array once, and
    the per-sample work is O(n) with no heap allocation.

    Parameters
    ----------
    lengths_m, masses_kg, inertias_kgm2 : (S, n) float64
    gravity_m_s2 : float
    theta_rad, omega_rad_s, alpha_rad_s2 : (n,) float64
        The shared state.

    Returns
    -------
    tau_Nm : (S, n) float64
    """
    samples, n = lengths_m.shape
    if masses_kg.shape != (samples, n) or inertias_kgm2.shape != (samples, n):
        raise ValueError("lengths_m, masses_kg and inertias_kgm2 must have the same shape (S, n)")
    if theta_rad.shape[0] != n or omega_rad_s.shape[0] != n or alpha_rad_s2.shape[0] != n:
        raise ValueError("theta_rad, omega_rad_s, alpha_rad_s2 must have length n")
    shared = shared_link_kinematics(theta_rad, omega_rad_s, alpha_rad_s2)
    out = np.empty((samples, n))
    n_chunks = (samples + _CHUNK - 1) // _CHUNK
    for chunk in prange(n_chunks):
        kin = shared.copy()  # per task: rows _FX, _FY are scratch
        for s in range(chunk * _CHUNK, min(samples, (chunk + 1) * _CHUNK)):
            _newton_euler(lengths_m, masses_kg, inertias_kgm2, s, gravity_m_s2, kin, out, s)
    return out


@kernel(parallel=True)
def inverse_dynamics_batch_states(
    lengths_m, masses_kg, inertias_kgm2, gravity_m_s2, theta_rad, omega_rad_s, alpha_rad_s2
):
    r"""Inverse dynamics of one robot in S states: (S, n) torques (eq. 2 per state).

    Parameters
    ----------
    lengths_m, masses_kg, inertias_kgm2 : (n,) float64
    gravity_m_s2 : float
    theta_rad, omega_rad_s, alpha_rad_s2 : (S, n) float64

    Returns
    -------
    tau_Nm : (S, n) float64
    """
    samples, n = theta_rad.shape
    if omega_rad_s.shape != (samples, n) or alpha_rad_s2.shape != (samples, n):
        raise ValueError("theta_rad, omega_rad_s and alpha_rad_s2 must have the same shape (S, n)")
    if lengths_m.shape[0] != n or masses_kg.shape[0] != n or inertias_kgm2.shape[0] != n:
        raise ValueError("lengths_m, masses_kg, inertias_kgm2 must have length n")
    lengths = _row(lengths_m)
    masses = _row(masses_kg)
    inertias = _row(inertias_kgm2)
    out = np.empty((samples, n))
    n_chunks = (samples + _CHUNK - 1) // _CHUNK
    for chunk in prange(n_chunks):
        kin = np.empty((_KIN_ROWS, n))
        for s in range(chunk * _CHUNK, min(samples, (chunk + 1) * _CHUNK)):
            _link_kinematics(theta_rad, omega_rad_s, alpha_rad_s2, s, kin)
            _newton_euler(lengths, masses, inertias, 0, gravity_m_s2, kin, out, s)
    return out

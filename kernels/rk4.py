r"""Fixed-step classical Runge-Kutta (RK4) integration of the NOC forward dynamics.

State :math:`x = (\theta, \dot\theta)`, :math:`\dot x = f(x) = (\dot\theta, \ddot\theta(\theta,\dot\theta,\tau))`
with :math:`\ddot\theta` from the forward dynamics of paper A eq. 2 (NOC mass matrix +
``LDLᵀ`` for short chains, the O(n) articulated-body algorithm of :mod:`kernels.aba_planar`
for long ones) and a
constant torque vector (zero for free fall). Paper A, section 2-1, integrates with RK4 over
1 s; its step size is garbled, the project uses 1e-4 s (see ``docs/dynamics.md``).
"""

import numpy as np

from ._jit import kernel
from .aba_planar import auto_work, forward_dynamics_rows_auto
from .dynamics import energies


@kernel
def rk4_record_count(n_steps_total, every):
    """Rows a whole run of ``n_steps_total`` steps records with stride ``every`` (t = 0 included).

    Records are the global step indices k = 0, every, 2·every, … <= n_steps_total.
    """
    return n_steps_total // every + 1


@kernel
def rk4_step(
    lengths_m,
    masses_kg,
    inertias_kgm2,
    gravity_m_s2,
    torque_Nm,
    theta_rad,
    omega_rad_s,
    step_s,
    work,
    matrix,
    d_theta,
    d_omega,
    theta,
    omega,
):
    r"""One classical RK4 step of :math:`x = (\theta, \dot\theta)`, in place, allocation-free.

    .. math:: k_1 = f(x_k),\; k_2 = f(x_k + \tfrac h2 k_1),\; k_3 = f(x_k + \tfrac h2 k_2),\;
              k_4 = f(x_k + h k_3),\quad x_{k+1} = x_k + \tfrac h6(k_1 + 2k_2 + 2k_3 + k_4)

    with :math:`f(\theta,\omega) = (\omega, \ddot\theta(\theta,\omega,\tau))`. :math:`\ddot\theta` comes
    from :func:`kernels.aba_planar.forward_dynamics_rows_auto` (NOC below
    :data:`~kernels.aba_planar.ABA_MIN_LINKS` links, articulated-body algorithm from there
    on); ``work`` and ``matrix`` come from :func:`kernels.aba_planar.auto_work`; ``d_theta``,
    ``d_omega`` (4, n) hold the stage derivatives and ``theta``, ``omega`` (n,) the stage
    point. The one step of :func:`rk4_integrate` and of the batched motion kernels
    (:mod:`kernels.motion_rk4`), so they agree to the last bit.
    """
    n = lengths_m.shape[0]
    half = 0.5 * step_s
    sixth = step_s / 6.0
    for i in range(n):
        theta[i] = theta_rad[i]
        omega[i] = omega_rad_s[i]
    for stage in range(4):
        for i in range(n):
            d_theta[stage, i] = omega[i]
        forward_dynamics_rows_auto(
            lengths_m,
            masses_kg,
            inertias_kgm2,
            gravity_m_s2,
            theta,
            omega,
            torque_Nm,
            work,
            matrix,
            d_omega,
            stage,
        )
        if stage < 3:
            factor = step_s if stage == 2 else half
            for i in range(n):
                theta[i] = theta_rad[i] + factor * d_theta[stage, i]
                omega[i] = omega_rad_s[i] + factor * d_omega[stage, i]
    for i in range(n):
        theta_rad[i] += sixth * (
            d_theta[0, i] + 2.0 * d_theta[1, i] + 2.0 * d_theta[2, i] + d_theta[3, i]
        )
        omega_rad_s[i] += sixth * (
            d_omega[0, i] + 2.0 * d_omega[1, i] + 2.0 * d_omega[2, i] + d_omega[3, i]
        )


@kernel
def rk4_integrate(
    lengths_m,
    masses_kg,
    inertias_kgm2,
    gravity_m_s2,
    torque_Nm,
    theta_rad,
    omega_rad_s,
    step_s,
    n_steps,
    every,
    start_step,
    t_out,
    theta_out,
    omega_out,
    kinetic_out,
    potential_out,
):
    r"""Advance ``(theta_rad, omega_rad_s)`` in place by ``n_steps`` classical RK4 steps.

    With :math:`h` = ``step_s`` and :math:`f(\theta,\omega) = (\omega, \ddot\theta(\theta,\omega,\tau))`:

    .. math:: k_1 = f(x_k),\; k_2 = f(x_k + \tfrac h2 k_1),\; k_3 = f(x_k + \tfrac h2 k_2),\;
              k_4 = f(x_k + h k_3),\quad x_{k+1} = x_k + \tfrac h6(k_1 + 2k_2 + 2k_3 + k_4).

    A record (t = k·h, θ, θ̇, kinetic and potential energy) is written for every global
    step index k in ``start_step+1 .. start_step+n_steps`` with ``k % every == 0``, and also
    for k = 0 when ``start_step == 0``, into the output arrays from row 0. Calling it in
    chunks (passing the running ``start_step``) gives bit-identical results to one call.
    Stage and work arrays are allocated once per call; the step loop is allocation-free.

    Parameters
    ----------
    lengths_m, masses_kg, inertias_kgm2, torque_Nm : (n,) float64
    gravity_m_s2 : float
    theta_rad, omega_rad_s : (n,) float64, modified in place
    step_s : float
    n_steps, every, start_step : int
    t_out : (R,), theta_out, omega_out : (R, n), kinetic_out, potential_out : (R,) float64
        R >= the number of records of this call.

    Returns
    -------
    rows_written : int
    """
    n = lengths_m.shape[0]
    work, matrix = auto_work(n)
    d_theta = np.empty((4, n))  # stage derivatives k1..k4 of θ
    d_omega = np.empty((4, n))  # ... and of θ̇
    theta = np.empty(n)  # θ at the stage point
    omega = np.empty(n)  # θ̇ at the stage point
    rows = 0
    for k in range(start_step, start_step + n_steps + 1):
        if k > start_step:  # one RK4 step from k-1 to k
            rk4_step(
                lengths_m,
                masses_kg,
                inertias_kgm2,
                gravity_m_s2,
                torque_Nm,
                theta_rad,
                omega_rad_s,
                step_s,
                work,
                matrix,
                d_theta,
                d_omega,
                theta,
                omega,
            )
        # the initial state of a chunk is the previous chunk's last step: record it only once
        if k % every == 0 and (k > start_step or k == 0):
            t_out[rows] = k * step_s
            for i in range(n):
                theta_out[rows, i] = theta_rad[i]
                omega_out[rows, i] = omega_rad_s[i]
            kinetic_out[rows], potential_out[rows] = energies(
                lengths_m, masses_kg, inertias_kgm2, gravity_m_s2, theta_rad, omega_rad_s
            )
            rows += 1
    return rows

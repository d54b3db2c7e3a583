r"""Batched RK4 over S robots, each with its own link parameters, one robot at a time.

The motion uncertainty job's parameters come from :func:`design_parameters`; its robots are
integrated by the lane-batched :func:`kernels.motion_lanes.rk4_lanes` (SIMD lanes over
robots). :func:`rk4_batch` here is the scalar reference the lane kernel is tested and
benchmarked against, and the CUDA kernel's model (:mod:`kernels.motion_cuda`).

Row s of a unit design :math:`u` (S, D) is the robot
:math:`x_s = u_s\,(x_{ub} - x_{lb}) + x_{lb}` (link lengths, masses and, when D = 3n,
inertias), scaled with the floating-point operations of ``SALib.util.scale_samples`` as
:func:`kernels.sensitivity_model.design_torques` does; without sampled inertias each link
keeps its nominal inertia or, for a robot whose inertias default to a slender rod's,
:math:`I_i = m_i l_i^2 / 12` of the sampled mass and length. Every robot is then advanced by
the one RK4 step of :func:`kernels.rk4.rk4_step` (so S = 1 equals
:func:`kernels.rk4.rk4_integrate` to the last bit), robots in parallel (``prange``).
"""

import numpy as np
from numba import prange

from ._jit import kernel
from .aba_planar import auto_work
from .rk4 import rk4_step

#: Robots handled by one parallel task: work arrays are allocated once per task.
ROBOTS_PER_TASK = 16


@kernel
def scale_row(unit, s, lower, upper, inertias_kgm2, rod_inertias, params):
    r"""``params`` (3, n) = lengths, masses, inertias of design row s (see module docstring):
    column c is :math:`u_{sc}(ub_c - lb_c) + lb_c`; inertias from columns 2n… when D = 3n,
    else link i's is :math:`m_i l_i^2/12` where ``rod_inertias[i]`` (bool, (n,)), else
    ``inertias_kgm2[i]``."""
    n = params.shape[1]
    num_vars = unit.shape[1]
    for c in range(num_vars):
        params[c // n, c % n] = unit[s, c] * (upper[c] - lower[c]) + lower[c]
    if num_vars == 2 * n:
        for i in range(n):
            if rod_inertias[i]:
                params[2, i] = params[1, i] * params[0, i] * params[0, i] / 12.0
            else:
                params[2, i] = inertias_kgm2[i]


@kernel(parallel=True)
def design_parameters(unit, lower, upper, inertias_kgm2, rod_inertias):
    """(S, 3, n) lengths, masses and inertias of every row of ``unit`` (:func:`scale_row`)."""
    samples = unit.shape[0]
    n = inertias_kgm2.shape[0]
    params = np.empty((samples, 3, n))
    for s in prange(samples):
        scale_row(unit, s, lower, upper, inertias_kgm2, rod_inertias, params[s])
    return params


@kernel(parallel=True)
def rk4_batch(params, gravity_m_s2, torque_Nm, theta_rad, omega_rad_s, step_s, n_steps):
    r"""Advance every robot s of ``params`` (S, 3, n) by ``n_steps`` RK4 steps in place.

    ``theta_rad``, ``omega_rad_s`` (S, n) are the relative joint angles and rates; the
    torques ``torque_Nm`` (n,) and gravity are shared. Robot s takes exactly the steps of
    :func:`kernels.rk4.rk4_integrate` with lengths, masses, inertias ``params[s]``, so
    chunking in time or in robots changes no bit. Tasks of :data:`ROBOTS_PER_TASK` robots
    run in parallel; work arrays are allocated once per task, the steps allocate nothing.
    """
    samples, _, n = params.shape
    n_tasks = (samples + ROBOTS_PER_TASK - 1) // ROBOTS_PER_TASK
    for task in prange(n_tasks):
        work, matrix = auto_work(n)
        d_theta = np.empty((4, n))
        d_omega = np.empty((4, n))
        theta = np.empty(n)
        omega = np.empty(n)
        for s in range(task * ROBOTS_PER_TASK, min(samples, (task + 1) * ROBOTS_PER_TASK)):
            lengths = params[s, 0]  # views made once per robot, not per step
            masses = params[s, 1]
            inertias = params[s, 2]
            q = theta_rad[s]
            w = omega_rad_s[s]
            for _ in range(n_steps):
                rk4_step(
                    lengths,
                    masses,
                    inertias,
                    gravity_m_s2,
                    torque_Nm,
                    q,
                    w,
                    step_s,
                    work,
                    matrix,
                    d_theta,
                    d_omega,
                    theta,
                    omega,
                )

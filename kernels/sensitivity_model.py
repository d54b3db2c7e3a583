r"""Joint torques of every row of a unit-hypercube sensitivity design, scaled on the fly.

The sensitivity engine's model (issue 3): row s of SALib's unit design u is the robot
:math:`x_s = u_s\,(x_{ub} - x_{lb}) + x_{lb}` (link lengths, masses, optionally inertias),
scaled with exactly the floating-point operations of ``SALib.util.scale_samples``, so the
torques are bit-identical to :func:`kernels.dynamics_batch.inverse_dynamics_batch` on the scaled
matrix (tested) without materialising it or its column copies.

Robots are evaluated :data:`LANES` at a time as structure of arrays (issue 21, as the motion
kernel :mod:`kernels.motion_lanes`): every per-robot quantity of the Newton-Euler sweeps of
:func:`kernels.dynamics._newton_euler` is a flat array over the block's robots, each loop of
the sweeps has an innermost loop over the lanes (compiled to packed vector instructions),
and the state's quantities (trigonometry, rates, :math:`\beta_i`) are computed once per
link for the whole block. The statements and their operation order are
:func:`~kernels.dynamics._newton_euler`'s, so every torque is the same double.
"""

import numpy as np
from numba import prange

from ._jit import kernel
from .dynamics import _ACCEL, _RATE, _UX, _UY
from .dynamics_batch import shared_link_kinematics

#: Robots per block (the lanes of the innermost loops).
LANES = 128


@kernel
def _block_torques(
    unit, first, count, span, lower, inertias_kgm2, gravity_m_s2, kin, robot, force, out
):
    r"""Torques of design rows ``first .. first + count`` into ``out`` (S, n).

    ``robot`` (D·L) receives the scaled rows (column c of lane j at ``c·L + j``), ``force``
    (4·L + 2·n·L) holds the running sums and :math:`f_i`. Forward sweep
    :math:`f_i = m_i(A_i + \tfrac12 l_i\beta_i)`, :math:`A_{i+1} = A_i + l_i\beta_i`,
    :math:`A_1 = (0, g)`; backward sweep
    :math:`\tau_j = \tau_{j+1} + I_j\dot\Omega_j + h_j\times f_j + 2\,h_j\times F_{j+1}`
    with :math:`h_j = \tfrac12 a_j`, :math:`F_j = \sum_{i\ge j} f_i`
    (:func:`kernels.dynamics._newton_euler`)."""
    num_vars = unit.shape[1]
    n = kin.shape[1]
    for lane in range(LANES):
        s = first + min(lane, count - 1)  # missing lanes repeat the last row
        for column in range(num_vars):
            robot[column * LANES + lane] = unit[s, column] * span[column] + lower[column]
    ax_row, ay_row, big_fx, big_fy = 0, 1, 2, 3
    fx_base = 4 * LANES
    fy_base = fx_base + n * LANES
    for lane in range(LANES):
        force[ax_row * LANES + lane] = 0.0
        force[ay_row * LANES + lane] = gravity_m_s2
    for i in range(n):
        w2 = kin[_RATE, i] * kin[_RATE, i]
        bx = -kin[_ACCEL, i] * kin[_UY, i] - w2 * kin[_UX, i]
        by = kin[_ACCEL, i] * kin[_UX, i] - w2 * kin[_UY, i]
        length_i = max(i, 0) * LANES
        mass_i = (n + max(i, 0)) * LANES
        link_i = max(i, 0) * LANES
        for lane in range(LANES):
            length = robot[length_i + lane]
            half = 0.5 * length
            mass = robot[mass_i + lane]
            force[fx_base + link_i + lane] = mass * (force[ax_row * LANES + lane] + half * bx)
            force[fy_base + link_i + lane] = mass * (force[ay_row * LANES + lane] + half * by)
            force[ax_row * LANES + lane] += length * bx
            force[ay_row * LANES + lane] += length * by
    moment = 0  # row of the running torque; rows ax_row, ay_row are free now
    for lane in range(LANES):
        force[moment * LANES + lane] = 0.0
        force[big_fx * LANES + lane] = 0.0
        force[big_fy * LANES + lane] = 0.0
    for ii in range(n):
        i = n - 1 - ii
        ux = kin[_UX, i]
        uy = kin[_UY, i]
        accel = kin[_ACCEL, i]
        length_i = max(i, 0) * LANES
        inertia_i = (2 * n + max(i, 0)) * LANES
        link_i = max(i, 0) * LANES
        if num_vars == 3 * n:
            for lane in range(LANES):
                _torque_lane(
                    robot[inertia_i + lane],
                    robot[length_i + lane],
                    ux,
                    uy,
                    accel,
                    force,
                    fx_base + link_i,
                    fy_base + link_i,
                    lane,
                )
        else:
            inertia = inertias_kgm2[i]
            for lane in range(LANES):
                _torque_lane(
                    inertia,
                    robot[length_i + lane],
                    ux,
                    uy,
                    accel,
                    force,
                    fx_base + link_i,
                    fy_base + link_i,
                    lane,
                )
        for lane in range(count):
            out[first + lane, i] = force[moment * LANES + lane]


@kernel(inline=True)
def _torque_lane(inertia, length, ux, uy, accel, force, fx_at, fy_at, lane):
    """One lane's step of the backward sweep (rows 0: torque, 2, 3: F) at link i."""
    hx = 0.5 * length * ux
    hy = 0.5 * length * uy
    fx = force[fx_at + lane]
    fy = force[fy_at + lane]
    force[lane] += (
        inertia * accel
        + hx * fy
        - hy * fx
        + 2.0 * (hx * force[3 * LANES + lane] - hy * force[2 * LANES + lane])
    )
    force[2 * LANES + lane] += fx
    force[3 * LANES + lane] += fy


@kernel(parallel=True)
def design_torques(
    unit, lower, upper, inertias_kgm2, gravity_m_s2, theta_rad, omega_rad_s, alpha_rad_s2
):
    r"""Inverse dynamics :math:`\tau_s = I_s\ddot\theta + C_s\dot\theta - \gamma_s` (paper A
    eqs. 2-8) of the robot of every design row s, in one shared state.

    ``unit`` (S, D) float64 is the design, columns l1…ln, m1…mn and, when D = 3n, I1…In;
    ``lower``, ``upper`` (D,) its bounds (m, kg, kg m²); ``inertias_kgm2`` (n,) the
    inertias used when D = 2n; gravity and the shared state (θ, θ̇, θ̈, each (n,)) as in
    :func:`kernels.dynamics_batch.inverse_dynamics_batch`. Returns the (S, n) torques, N m.
    Blocks of :data:`LANES` rows run in parallel (``prange``), each with its own scratch.
    """
    samples, num_vars = unit.shape
    n = theta_rad.shape[0]
    if num_vars != 2 * n and num_vars != 3 * n:
        raise ValueError("unit must have 2n or 3n columns")
    if lower.shape[0] != num_vars or upper.shape[0] != num_vars:
        raise ValueError("lower and upper must have one bound per design column")
    span = upper - lower
    kin = shared_link_kinematics(theta_rad, omega_rad_s, alpha_rad_s2)
    out = np.empty((samples, n))
    n_blocks = (samples + LANES - 1) // LANES
    for block in prange(n_blocks):
        first = block * LANES
        robot = np.empty(num_vars * LANES)
        force = np.empty((4 + 2 * n) * LANES)
        _block_torques(
            unit,
            first,
            min(LANES, samples - first),
            span,
            lower,
            inertias_kgm2,
            gravity_m_s2,
            kin,
            robot,
            force,
            out,
        )
    return out

r"""Lane-batched RK4 of many robots: :data:`LANES` robots side by side in SIMD lanes.

The batched motion job integrates thousands of robots that differ only in their link
parameters. Compiled one robot at a time (:func:`kernels.motion_rk4.rk4_batch`), every
robot is scalar code: the prefix sums and the ``LDLᵀ`` solve are serial chains and
``np.sin``/``np.cos`` are calls into the C library, so the vector units stay idle. Here a
block of :data:`LANES` robots is held as **structure of arrays**: every quantity of the
algorithm (joint angle, link vector, mass-matrix entry, running sum, …) is an array over the
block's robots, and every loop of the algorithm has an innermost loop over the lanes, which
LLVM compiles to packed vector instructions (checked in the assembly, ``docs/motion.md``).
``sin``/``cos`` are :func:`kernels.lane_trig.sincos`, straight-line arithmetic within 1 ulp
of the C library's.

The algorithm and its operation order are those of the scalar kernels, statement by
statement: the NOC mass matrix + ``LDLᵀ`` of :func:`kernels.dynamics._forward_dynamics_rows`
below :data:`~kernels.aba_planar.ABA_MIN_LINKS` links, the articulated-body recursion of
:func:`kernels.aba_planar.aba_rows` from there on, and the RK4 step of
:func:`kernels.rk4.rk4_step`. The only difference is ``sincos`` (≤ 1 ulp from ``np.sin``,
``np.cos``), so a robot's trajectory equals the scalar kernel's to round-off (1 s of the
Table 1 robot: ≤ 1e-12 relative, tested).

The blocks of one call run one after the other (the kernels release the GIL: the motion
job runs ranges of whole blocks in threads, :func:`planar_tui.motion.engine.run_lanes`;
a ``prange`` over the blocks cost 4-9 s more to compile than the whole serial kernel).
Each block allocates its structure-of-arrays copy of its robots' parameters and states and
its work arrays once per call, and the steps allocate nothing. A block's missing lanes (the last block of S robots) repeat its last robot and are
not written back. A lane whose absolute angle leaves ``sincos``'s range
(:data:`~kernels.lane_trig.SINCOS_MAX_ABS`) takes ``np.sin``/``np.cos`` for it.
"""

import numpy as np

from ._jit import kernel
from .aba_planar import ABA_MIN_LINKS
from .lane_trig import SINCOS_MAX_ABS, sincos
from .motion_lanes_n6 import STATE_ROWS, rk4_step_6

#: Robots per block (SIMD lanes of the innermost loops). Measured (CPU time, 1 thread,
#: Table 1 robots) on the project's machine, a Zen 3 (AVX2) KVM guest in this session: 128
#: lanes 3-5 % faster than 64, 32 and 16 markedly slower (fixed cost per lane loop: the
#: runtime alias checks and the loop set-up are paid per loop, not per lane), 256 no better.
LANES = 128

#: Links of the chains that take the fused step (:mod:`kernels.motion_lanes_n6`).
FUSED_LINKS = 6

# How the loops over lanes are kept vectorisable (each point was found with LLVM's
# vectoriser remarks, ``--pass-remarks-missed=loop-vectorize``):
# * every scratch array is flat with compile-time strides: row r of ``acc`` is
#   ``acc[r * LANES + lane]``, row r of link i of ``work`` is ``work[base_i + r * LANES + lane]``
#   (with 2-D/3-D arrays the strides are read at run time and LLVM cannot prove that a loop
#   storing into several rows of one array never overlaps itself);
# * ``base_i = max(i, 0) * _WORK_STRIDE`` is computed outside the lane loop: the ``max``
#   shows LLVM that the index is not negative, so numba's wraparound of negative indices
#   folds away (else the index is not affine: "unsafe indirect dependence");
# * loop-invariant loads (``tau_Nm[i]``) are hoisted out of the lane loop;
# * ``sincos`` is inlined at numba's level (LLVM does not inline one numba function into
#   another, and a call keeps the loop scalar).
_ACC_ROWS = 9
# Rows of the work array (n, 9, LANES): as the scalar kernels' rows.
_LX, _LY, _PX, _PY, _FX, _FY = 0, 1, 2, 3, 4, 5  # NOC (kernels.dynamics)
_AX, _AY, _RATE, _INV_D, _U1, _U2, _BIAS, _BX, _BY = 0, 1, 2, 3, 4, 5, 6, 7, 8  # ABA
_WORK_ROWS = 9
_WORK_STRIDE = _WORK_ROWS * LANES
# Rows of the trigonometry array ``trig`` (3, LANES): phi, sin phi, cos phi of one link.
_PHI, _SIN, _COS = 0, 1, 2


@kernel
def _link_trig(theta, i, acc, row, trig):
    r"""Absolute angle :math:`\phi_i = \phi_{i-1} + \theta_i` of link i for every lane (running
    sum in ``acc[row]``) and its sine and cosine into ``trig``: :func:`kernels.lane_trig.sincos`
    in one vector loop, then, only for a lane whose angle is past its range
    (:data:`~kernels.lane_trig.SINCOS_MAX_ABS`, never met in practice), ``np.sin``/``np.cos``."""
    beyond = 0
    for lane in range(LANES):
        angle = acc[row * LANES + lane] + theta[i, lane]
        acc[row * LANES + lane] = angle
        trig[_PHI * LANES + lane] = angle
        s, c = sincos(angle)
        trig[_SIN * LANES + lane] = s
        trig[_COS * LANES + lane] = c
        if abs(angle) > SINCOS_MAX_ABS:
            beyond += 1
    if beyond:
        for lane in range(LANES):
            if abs(trig[_PHI * LANES + lane]) > SINCOS_MAX_ABS:
                trig[_SIN * LANES + lane] = np.sin(trig[_PHI * LANES + lane])
                trig[_COS * LANES + lane] = np.cos(trig[_PHI * LANES + lane])


@kernel
def _noc_lanes(params, gravity_m_s2, tau_Nm, theta, omega, work, matrix, alpha, stage, acc, trig):
    r""":func:`kernels.dynamics._forward_dynamics_rows` (NOC mass matrix + ``LDLᵀ``) for
    every lane: ``params`` (3, n, L) lengths, masses, inertias, state ``theta``, ``omega``
    (n, L), shared torques (n,), result into ``alpha[stage]`` (n, L); flat scratch ``work``
    (n·9·L), ``acc`` (9·L) and ``trig`` (3·L)."""
    n = theta.shape[0]
    phi, rate, acc_x, acc_y, px, py = 0, 1, 2, 3, 4, 5
    for lane in range(LANES):
        acc[phi * LANES + lane] = 0.0
        acc[rate * LANES + lane] = 0.0
        acc[acc_x * LANES + lane] = 0.0
        acc[acc_y * LANES + lane] = gravity_m_s2
        acc[px * LANES + lane] = 0.0
        acc[py * LANES + lane] = 0.0
    # 1. base to tip
    for i in range(n):
        base_i = max(i, 0) * _WORK_STRIDE
        _link_trig(theta, i, acc, phi, trig)
        for lane in range(LANES):
            w = acc[rate * LANES + lane] + omega[i, lane]
            acc[rate * LANES + lane] = w
            ax = params[0, i, lane] * trig[_COS * LANES + lane]
            ay = params[0, i, lane] * trig[_SIN * LANES + lane]
            w2 = w * w
            work[base_i + _LX * LANES + lane] = ax
            work[base_i + _LY * LANES + lane] = ay
            work[base_i + _PX * LANES + lane] = acc[px * LANES + lane]
            work[base_i + _PY * LANES + lane] = acc[py * LANES + lane]
            work[base_i + _FX * LANES + lane] = params[1, i, lane] * (
                acc[acc_x * LANES + lane] - 0.5 * w2 * ax
            )
            work[base_i + _FY * LANES + lane] = params[1, i, lane] * (
                acc[acc_y * LANES + lane] - 0.5 * w2 * ay
            )
            acc[acc_x * LANES + lane] -= w2 * ax
            acc[acc_y * LANES + lane] -= w2 * ay
            acc[px * LANES + lane] += ax
            acc[py * LANES + lane] += ay
    # 2. tip to base: bias torques and the lower triangle of the mass matrix
    big_fx, big_fy, bias, outer_mass, hx, hy, inertia = 0, 1, 2, 3, 4, 5, 6
    for row in range(7):
        for lane in range(LANES):
            acc[row * LANES + lane] = 0.0
    for k in range(n - 1, -1, -1):
        base_k = max(k, 0) * _WORK_STRIDE
        tau_k = tau_Nm[k]  # loaded outside the lane loop: LLVM cannot vectorise it inside
        for lane in range(LANES):
            ax = work[base_k + _LX * LANES + lane]
            ay = work[base_k + _LY * LANES + lane]
            fx = work[base_k + _FX * LANES + lane]
            fy = work[base_k + _FY * LANES + lane]
            acc[bias * LANES + lane] += (
                0.5 * (ax * fy - ay * fx)
                + ax * acc[big_fy * LANES + lane]
                - ay * acc[big_fx * LANES + lane]
            )
            acc[big_fx * LANES + lane] += fx
            acc[big_fy * LANES + lane] += fy
            alpha[stage, k, lane] = tau_k - acc[bias * LANES + lane]
            length = params[0, k, lane]
            mass = params[1, k, lane]
            acc[inertia * LANES + lane] += (
                2.0 * (ax * acc[hx * LANES + lane] + ay * acc[hy * LANES + lane])
                + (acc[outer_mass * LANES + lane] + 0.25 * mass) * length * length
                + params[2, k, lane]
            )
            acc[hx * LANES + lane] += (acc[outer_mass * LANES + lane] + 0.5 * mass) * ax
            acc[hy * LANES + lane] += (acc[outer_mass * LANES + lane] + 0.5 * mass) * ay
            acc[outer_mass * LANES + lane] += mass
            matrix[k, k, lane] = acc[inertia * LANES + lane]
        for j in range(k):
            base_j = max(j, 0) * _WORK_STRIDE
            for lane in range(LANES):
                matrix[k, j, lane] = (
                    acc[inertia * LANES + lane]
                    + (work[base_k + _PX * LANES + lane] - work[base_j + _PX * LANES + lane])
                    * acc[hx * LANES + lane]
                    + (work[base_k + _PY * LANES + lane] - work[base_j + _PY * LANES + lane])
                    * acc[hy * LANES + lane]
                )
    # 3. LDL^T factor + forward substitution, then back substitution
    d, y = 0, 1
    for i in range(n):
        for j in range(i):
            for k in range(j):
                for lane in range(LANES):
                    matrix[i, j, lane] -= matrix[i, k, lane] * matrix[j, k, lane]
        for lane in range(LANES):
            acc[d * LANES + lane] = matrix[i, i, lane]
            acc[y * LANES + lane] = alpha[stage, i, lane]
        for k in range(i):
            for lane in range(LANES):
                w = matrix[i, k, lane]
                l_ik = w * matrix[k, k, lane]
                acc[d * LANES + lane] -= l_ik * w
                matrix[i, k, lane] = l_ik
                acc[y * LANES + lane] -= w * alpha[stage, k, lane]
        for lane in range(LANES):
            inv = 1.0 / acc[d * LANES + lane]
            matrix[i, i, lane] = inv
            alpha[stage, i, lane] = acc[y * LANES + lane] * inv
    for ii in range(n):
        i = n - 1 - ii
        for k in range(i):
            for lane in range(LANES):
                alpha[stage, k, lane] -= matrix[i, k, lane] * alpha[stage, i, lane]


@kernel
def _aba_lanes(params, gravity_m_s2, tau_Nm, theta, omega, work, alpha, stage, acc, trig):
    r""":func:`kernels.aba_planar.aba_rows` (the articulated-body recursion) for every
    lane, statement by statement; arguments as :func:`_noc_lanes` (no matrix)."""
    n = theta.shape[0]
    phi, rate, w2_prev, ax_prev, ay_prev = 0, 1, 2, 3, 4
    for row in range(5):
        for lane in range(LANES):
            acc[row * LANES + lane] = 0.0
    for i in range(n):
        base_i = max(i, 0) * _WORK_STRIDE
        _link_trig(theta, i, acc, phi, trig)
        for lane in range(LANES):
            w = acc[rate * LANES + lane] + omega[i, lane]
            acc[rate * LANES + lane] = w
            ax = params[0, i, lane] * trig[_COS * LANES + lane]
            ay = params[0, i, lane] * trig[_SIN * LANES + lane]
            work[base_i + _AX * LANES + lane] = ax
            work[base_i + _AY * LANES + lane] = ay
            work[base_i + _RATE * LANES + lane] = w
            work[base_i + _BX * LANES + lane] = -(
                acc[w2_prev * LANES + lane] * acc[ax_prev * LANES + lane]
            )
            work[base_i + _BY * LANES + lane] = -(
                acc[w2_prev * LANES + lane] * acc[ay_prev * LANES + lane]
            )
            acc[w2_prev * LANES + lane] = w * w
            acc[ax_prev * LANES + lane] = ax
            acc[ay_prev * LANES + lane] = ay
    j11, j12, j22, p0, p1, p2 = 0, 1, 2, 3, 4, 5
    for row in range(6):
        for lane in range(LANES):
            acc[row * LANES + lane] = 0.0
    for i in range(n - 1, -1, -1):
        base_i = max(i, 0) * _WORK_STRIDE
        tau_i = tau_Nm[i]
        for lane in range(LANES):
            ax = work[base_i + _AX * LANES + lane]
            ay = work[base_i + _AY * LANES + lane]
            w2 = work[base_i + _RATE * LANES + lane] * work[base_i + _RATE * LANES + lane]
            mass = params[1, i, lane]
            cx = 0.5 * ax
            cy = 0.5 * ay
            je1 = acc[j12 * LANES + lane] * ax - acc[j11 * LANES + lane] * ay
            je2 = acc[j22 * LANES + lane] * ax - acc[j12 * LANES + lane] * ay
            d = params[2, i, lane] + mass * (cx * cx + cy * cy) + (ax * je2 - ay * je1)
            u1 = je1 - mass * cy
            u2 = je2 + mass * cx
            bias0 = acc[p0 * LANES + lane] + (
                ax * acc[p2 * LANES + lane] - ay * acc[p1 * LANES + lane]
            )
            bias1 = acc[p1 * LANES + lane] - mass * w2 * cx
            bias2 = acc[p2 * LANES + lane] - mass * w2 * cy
            u = tau_i - bias0
            inv_d = 1.0 / d
            work[base_i + _INV_D * LANES + lane] = inv_d
            work[base_i + _U1 * LANES + lane] = u1
            work[base_i + _U2 * LANES + lane] = u2
            work[base_i + _BIAS * LANES + lane] = u
            k1 = u1 * inv_d
            k2 = u2 * inv_d
            acc[j11 * LANES + lane] = mass + acc[j11 * LANES + lane] - u1 * k1
            acc[j12 * LANES + lane] = acc[j12 * LANES + lane] - u1 * k2
            acc[j22 * LANES + lane] = mass + acc[j22 * LANES + lane] - u2 * k2
            bx = work[base_i + _BX * LANES + lane]
            by = work[base_i + _BY * LANES + lane]
            acc[p0 * LANES + lane] = tau_i
            acc[p1 * LANES + lane] = (
                bias1 + acc[j11 * LANES + lane] * bx + acc[j12 * LANES + lane] * by + k1 * u
            )
            acc[p2 * LANES + lane] = (
                bias2 + acc[j12 * LANES + lane] * bx + acc[j22 * LANES + lane] * by + k2 * u
            )
    a0, a1, a2, ax_prev, ay_prev = 0, 1, 2, 3, 4
    for lane in range(LANES):
        acc[a0 * LANES + lane] = 0.0
        acc[a1 * LANES + lane] = 0.0
        acc[a2 * LANES + lane] = gravity_m_s2
        acc[ax_prev * LANES + lane] = 0.0
        acc[ay_prev * LANES + lane] = 0.0
    for i in range(n):
        base_i = max(i, 0) * _WORK_STRIDE
        for lane in range(LANES):
            acc[a1 * LANES + lane] = (
                acc[a1 * LANES + lane]
                - acc[a0 * LANES + lane] * acc[ay_prev * LANES + lane]
                + work[base_i + _BX * LANES + lane]
            )
            acc[a2 * LANES + lane] = (
                acc[a2 * LANES + lane]
                + acc[a0 * LANES + lane] * acc[ax_prev * LANES + lane]
                + work[base_i + _BY * LANES + lane]
            )
            acc[ax_prev * LANES + lane] = work[base_i + _AX * LANES + lane]
            acc[ay_prev * LANES + lane] = work[base_i + _AY * LANES + lane]
            qdd = (
                work[base_i + _BIAS * LANES + lane]
                - work[base_i + _U1 * LANES + lane] * acc[a1 * LANES + lane]
                - work[base_i + _U2 * LANES + lane] * acc[a2 * LANES + lane]
            ) * work[base_i + _INV_D * LANES + lane] - acc[a0 * LANES + lane]
            alpha[stage, i, lane] = qdd
            acc[a0 * LANES + lane] += qdd


@kernel
def _forward_dynamics_lanes(
    params, gravity_m_s2, tau_Nm, theta, omega, work, matrix, alpha, stage, acc, trig
):
    """The scalar kernels' choice of algorithm (:func:`kernels.aba_planar.forward_dynamics_rows_auto`)."""
    if theta.shape[0] >= ABA_MIN_LINKS:
        _aba_lanes(params, gravity_m_s2, tau_Nm, theta, omega, work, alpha, stage, acc, trig)
    else:
        _noc_lanes(
            params, gravity_m_s2, tau_Nm, theta, omega, work, matrix, alpha, stage, acc, trig
        )


@kernel
def rk4_step_lanes(params, gravity_m_s2, tau_Nm, q, w, step_s, work, matrix, dq, dw, qs, acc, trig):
    r""":func:`kernels.rk4.rk4_step` for every lane, in place on ``q``, ``w`` (n, L):

    .. math:: k_1 = f(x_k),\; k_2 = f(x_k + \tfrac h2 k_1),\; k_3 = f(x_k + \tfrac h2 k_2),\;
              k_4 = f(x_k + h k_3),\quad x_{k+1} = x_k + \tfrac h6(k_1 + 2k_2 + 2k_3 + k_4)

    with the scalar step's values and operation order; the copies are folded away: the
    first stage reads ``q``, ``w`` themselves, and the rate at stage s is its angle
    derivative, so ``dq[s]`` (s = 1, 2, 3; ``dq[0]`` is ``w``) is the stage point's rate.
    ``dq``, ``dw`` (4, n, L) stage derivatives, ``qs`` (n, L) the stage point's angles."""
    n = q.shape[0]
    half = 0.5 * step_s
    sixth = step_s / 6.0
    # The stage is always the loop's integer: a literal 0 at a call of its own made numba
    # compile the forward dynamics (and everything below it) twice, once for Literal[int](0).
    for stage in range(4):
        if stage == 0:
            _forward_dynamics_lanes(
                params, gravity_m_s2, tau_Nm, q, w, work, matrix, dw, stage, acc, trig
            )
            continue
        factor = step_s if stage == 3 else half
        for i in range(n):
            if stage == 1:
                for lane in range(LANES):
                    qs[i, lane] = q[i, lane] + factor * w[i, lane]
                    dq[stage, i, lane] = w[i, lane] + factor * dw[stage - 1, i, lane]
            else:
                for lane in range(LANES):
                    qs[i, lane] = q[i, lane] + factor * dq[stage - 1, i, lane]
                    dq[stage, i, lane] = w[i, lane] + factor * dw[stage - 1, i, lane]
        _forward_dynamics_lanes(
            params, gravity_m_s2, tau_Nm, qs, dq[stage], work, matrix, dw, stage, acc, trig
        )
    for i in range(n):
        for lane in range(LANES):
            q[i, lane] += sixth * (
                w[i, lane] + 2.0 * dq[1, i, lane] + 2.0 * dq[2, i, lane] + dq[3, i, lane]
            )
            w[i, lane] += sixth * (
                dw[0, i, lane] + 2.0 * dw[1, i, lane] + 2.0 * dw[2, i, lane] + dw[3, i, lane]
            )


@kernel
def _block_state(params, theta_rad, omega_rad_s, first, count):
    """``(flat_p, flat_q, flat_w)``: the robots ``first`` … ``first + count - 1`` of
    ``params`` (S, 3, n) and the states as structure of arrays, (3, n, LANES) parameters and
    (n, LANES) angles and rates, flat; the missing lanes repeat the last robot."""
    n = params.shape[2]
    flat_p = np.empty(3 * n * LANES)
    flat_q = np.empty(n * LANES)
    flat_w = np.empty(n * LANES)
    p = flat_p.reshape((3, n, LANES))
    q = flat_q.reshape((n, LANES))
    w = flat_w.reshape((n, LANES))
    for lane in range(LANES):
        s = first + min(lane, count - 1)
        for i in range(n):
            p[0, i, lane] = params[s, 0, i]
            p[1, i, lane] = params[s, 1, i]
            p[2, i, lane] = params[s, 2, i]
            q[i, lane] = theta_rad[s, i]
            w[i, lane] = omega_rad_s[s, i]
    return flat_p, flat_q, flat_w


@kernel
def _store_block(flat_q, flat_w, theta_rad, omega_rad_s, first, count):
    """Write the block's ``count`` real lanes back into the (S, n) states."""
    n = theta_rad.shape[1]
    for lane in range(count):
        for i in range(n):
            theta_rad[first + lane, i] = flat_q[i * LANES + lane]
            omega_rad_s[first + lane, i] = flat_w[i * LANES + lane]


@kernel
def _general_steps(flat_p, gravity_m_s2, torque_Nm, flat_q, flat_w, step_s, n_steps):
    """``n_steps`` general steps (:func:`rk4_step_lanes`) of one block (:func:`_block_state`)
    in place, its work arrays allocated once."""
    n = flat_q.shape[0] // LANES
    size = 1 if n >= ABA_MIN_LINKS else n
    p = flat_p.reshape((3, n, LANES))
    q = flat_q.reshape((n, LANES))
    w = flat_w.reshape((n, LANES))
    work = np.zeros(n * _WORK_STRIDE)
    matrix = np.zeros((size, size, LANES))
    dq = np.empty((4, n, LANES))
    dw = np.empty((4, n, LANES))
    qs = np.empty((n, LANES))
    acc = np.empty(_ACC_ROWS * LANES)
    trig = np.empty(3 * LANES)
    for _ in range(n_steps):
        rk4_step_lanes(
            p, gravity_m_s2, torque_Nm, q, w, step_s, work, matrix, dq, dw, qs, acc, trig
        )


@kernel
def _fused_steps(flat_p, gravity_m_s2, torque_Nm, flat_q, flat_w, step_s, n_steps):
    """``n_steps`` fused steps (:func:`kernels.motion_lanes_n6.rk4_step_6`) of one block of
    :data:`FUSED_LINKS`-link chains in place; a step in which a lane's angle is past
    :data:`~kernels.lane_trig.SINCOS_MAX_ABS` is redone by the general step."""
    size = flat_q.shape[0]
    state = np.empty(STATE_ROWS * LANES)
    state[:size] = flat_q
    state[size : 2 * size] = flat_w
    for _ in range(n_steps):
        if rk4_step_6(flat_p, gravity_m_s2, torque_Nm, state, step_s):
            flat_q[:] = state[:size]
            flat_w[:] = state[size : 2 * size]
            _general_steps(flat_p, gravity_m_s2, torque_Nm, flat_q, flat_w, step_s, np.int64(1))
            state[:size] = flat_q
            state[size : 2 * size] = flat_w
    flat_q[:] = state[:size]
    flat_w[:] = state[size : 2 * size]


@kernel
def rk4_lanes_general(params, gravity_m_s2, torque_Nm, theta_rad, omega_rad_s, step_s, n_steps):
    r"""Advance every robot s of ``params`` (S, 3, n) by ``n_steps`` RK4 steps in place, in
    blocks of :data:`LANES` robots (module docstring), by the general lane step
    (:func:`rk4_step_lanes`); same arguments and results (to round-off) as
    :func:`kernels.motion_rk4.rk4_batch`. Chunking in time changes no bit. The motion job's
    kernel for chains of other than :data:`FUSED_LINKS` links (it compiles without the
    fused step: :func:`rk4_lanes`)."""
    samples = params.shape[0]
    for block in range((samples + LANES - 1) // LANES):
        first = block * LANES
        count = min(LANES, samples - first)
        flat_p, flat_q, flat_w = _block_state(params, theta_rad, omega_rad_s, first, count)
        _general_steps(flat_p, gravity_m_s2, torque_Nm, flat_q, flat_w, step_s, n_steps)
        _store_block(flat_q, flat_w, theta_rad, omega_rad_s, first, count)


@kernel
def rk4_lanes(params, gravity_m_s2, torque_Nm, theta_rad, omega_rad_s, step_s, n_steps):
    r""":func:`rk4_lanes_general` where chains of :data:`FUSED_LINKS` links take the fused
    step (:func:`kernels.motion_lanes_n6.rk4_step_6`: one lane loop per RK4 stage, fused
    multiply-adds); a step in which a lane's angle is past
    :data:`~kernels.lane_trig.SINCOS_MAX_ABS` is redone by the general step. Other chains
    take the general step throughout. The fused step is the costliest kernel to compile
    (about two thirds of the motion job's cold start): the motion job calls this kernel for
    :data:`FUSED_LINKS`-link chains only."""
    samples, _, n = params.shape
    for block in range((samples + LANES - 1) // LANES):
        first = block * LANES
        count = min(LANES, samples - first)
        flat_p, flat_q, flat_w = _block_state(params, theta_rad, omega_rad_s, first, count)
        if n == FUSED_LINKS:
            _fused_steps(flat_p, gravity_m_s2, torque_Nm, flat_q, flat_w, step_s, n_steps)
        else:
            _general_steps(flat_p, gravity_m_s2, torque_Nm, flat_q, flat_w, step_s, n_steps)
        _store_block(flat_q, flat_w, theta_rad, omega_rad_s, first, count)

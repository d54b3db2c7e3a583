"""The O(n) articulated-body forward dynamics (kernels/aba_planar.py) against independent
methods: the NOC mass matrix + LDLᵀ (kernels/dynamics.py), MuJoCo's ``mj_forward`` (its own
composite-rigid-body mass matrix and sparse factorisation, benchmarks/mujoco_model.py), the
recursive Newton-Euler inverse dynamics (backward error), the 1R pendulum by hand, and
energy conservation of an RK4 free fall of a long chain (which takes this path).

Precision: for short chains all three engines agree to 1e-12 relative in θ̈; for long,
folded random chains the mass matrix is ill-conditioned (κ up to ~1e8 at n = 1000) and
every engine's θ̈ carries κ·ε of forward error, so the comparison there is in torque space
(M Δθ̈ = ID(θ̈_a) − ID(θ̈_b), relative to the size of the generalised forces), where they
agree to 1e-13, and the forward difference is checked against κ·ε.
"""

import mujoco
import numpy as np
import pytest
from planar_tui.kernels.aba_planar import ABA_MIN_LINKS, aba_forward_dynamics
from planar_tui.kernels.dynamics import energies, forward_dynamics, inverse_dynamics
from planar_tui.kernels.noc_matrices import mass_matrix
from planar_tui.kernels.rk4 import rk4_integrate

from benchmarks.mujoco_model import chain_model
from tests.test_dynamics_kernels import G, random_robot, random_state

EPS = np.finfo(float).eps


def case(n, seed):
    rng = np.random.default_rng(seed)
    robot = random_robot(rng, n)
    theta, omega, _ = random_state(rng, n)
    return robot, theta, omega, rng.normal(0.0, 3.0, n)


def mujoco_forward(robot, theta, omega, tau):
    model, data = chain_model(*robot, G)
    data.qpos[:], data.qvel[:], data.qfrc_applied[:] = theta, omega, tau
    mujoco.mj_forward(model, data)
    return data.qacc.copy()


def force_scale(robot, theta, omega, tau):
    """Size of the generalised forces at the state: max |C θ̇ − γ| + max |τ|."""
    bias = inverse_dynamics(*robot, G, theta, omega, np.zeros(len(theta)))
    return np.abs(bias).max() + np.abs(tau).max()


@pytest.mark.parametrize("n", [1, 2, 3, 6, 8, 10])
def test_short_chains_agree_with_noc_and_mujoco_to_1e12(n):
    for seed in range(3):
        robot, theta, omega, tau = case(n, 100 * n + seed)
        alpha = aba_forward_dynamics(*robot, G, theta, omega, tau)
        size = np.abs(alpha).max()
        noc = forward_dynamics(*robot, G, theta, omega, tau)
        assert np.abs(alpha - noc).max() <= 1e-12 * size
        assert np.abs(alpha - mujoco_forward(robot, theta, omega, tau)).max() <= 1e-12 * size


@pytest.mark.parametrize("n", [30, 100, 1000])
def test_long_chains_agree_with_noc_and_mujoco_in_torque_space(n):
    robot, theta, omega, tau = case(n, 7 + n)
    alpha = aba_forward_dynamics(*robot, G, theta, omega, tau)
    scale = force_scale(robot, theta, omega, tau)
    # backward error of the recursion itself: it reproduces τ to round-off
    residual = inverse_dynamics(*robot, G, theta, omega, alpha) - tau
    assert np.abs(residual).max() <= 1e-14 * scale
    # κ(M) by an SVD: ~1 s at n = 1000 on a busy machine, so only for the shorter chains
    kappa = np.linalg.cond(mass_matrix(*robot, theta)) if n <= 100 else None
    for other in (
        forward_dynamics(*robot, G, theta, omega, tau),
        mujoco_forward(robot, theta, omega, tau),
    ):
        torque_gap = inverse_dynamics(*robot, G, theta, omega, alpha - other) - inverse_dynamics(
            *robot, G, theta, omega, np.zeros(n)
        )  # = M (α − α_other)
        assert np.abs(torque_gap).max() <= 1e-12 * scale
        if kappa is not None:
            assert np.abs(alpha - other).max() <= 100 * kappa * EPS * np.abs(alpha).max()


def test_one_link_pendulum_by_hand():
    """θ̈ = (τ − m g (l/2) cos θ) / (I + m l²/4), any rate."""
    length, mass, inertia, theta, tau = 0.7, 1.3, 0.02, 0.4, 0.9
    expected = (tau - mass * G * 0.5 * length * np.cos(theta)) / (inertia + mass * length**2 / 4)
    alpha = aba_forward_dynamics(
        np.array([length]),
        np.array([mass]),
        np.array([inertia]),
        G,
        np.array([theta]),
        np.array([3.0]),
        np.array([tau]),
    )
    assert alpha[0] == pytest.approx(expected, rel=1e-15)


def test_a_long_free_falling_chain_keeps_its_energy():
    """RK4 at 1e-4 s for 0.2 s of a 20-link chain (which takes the O(n) path): the energy
    drift is RK4's truncation error, far below the energy exchanged."""
    n = 20
    assert n >= ABA_MIN_LINKS
    robot = random_robot(np.random.default_rng(5), n)
    theta, omega = np.zeros(n), np.zeros(n)
    steps = 2000
    records = [np.zeros(steps + 1), np.zeros((steps + 1, n)), np.zeros((steps + 1, n))]
    kinetic, potential = np.zeros(steps + 1), np.zeros(steps + 1)
    rk4_integrate(
        *robot, G, np.zeros(n), theta, omega, 1e-4, steps, 1, 0, *records, kinetic, potential
    )
    total = kinetic + potential
    assert kinetic[-1] > 1.0  # it fell
    assert np.abs(total - total[0]).max() <= 1e-8 * kinetic.max()
    assert energies(*robot, G, theta, omega)[0] == pytest.approx(kinetic[-1], rel=1e-15)


LONG_CHAIN_ON_THE_CUDA_SIMULATOR = """
import json, numpy as np
from planar_tui.kernels import aba_planar, motion_cuda, motion_rk4
n = 9
rng = np.random.default_rng(8)
unit = rng.random((3, 2 * n))
lower = np.concatenate([np.full(n, 0.10), np.full(n, 0.30)])
upper = lower + np.concatenate([np.full(n, 0.02), np.full(n, 0.05)])
inertias = np.full(n, 1e-3); rod = np.ones(n, dtype=bool)
theta = np.tile(np.linspace(0.1, -0.2, n), (3, 1)); omega = np.zeros((3, n))
torque = np.linspace(0.5, 0.05, n)
batch = motion_cuda.CudaBatch(unit, lower, upper, inertias, rod, theta, omega, 9.81, torque)
batch.advance(1e-3, 6)
params = motion_rk4.design_parameters(unit, lower, upper, inertias, rod)
motion_rk4.rk4_batch(params, 9.81, torque, theta, omega, 1e-3, 6)
print(json.dumps({"aba": bool(aba_planar.uses_aba(n)), "matrix": list(batch.matrix.shape),
                  "error": float(np.abs(batch.angles() - theta).max()),
                  "moved": float(np.abs(theta - np.linspace(0.1, -0.2, n)).max())}))
"""


def test_the_cuda_kernel_takes_the_o_n_path_for_long_chains_on_the_simulator():
    """A 9-link chain on numba's CUDA simulator (a fresh process: the simulator must be on
    before numba.cuda is imported) equals the CPU kernel and holds no n × n matrix."""
    import json
    import os
    import subprocess
    import sys

    env = {**os.environ, "NUMBA_ENABLE_CUDASIM": "1"}
    done = subprocess.run(
        [sys.executable, "-c", LONG_CHAIN_ON_THE_CUDA_SIMULATOR],
        env=env,
        capture_output=True,
        text=True,
        check=True,
    )
    report = json.loads(done.stdout.strip().splitlines()[-1])
    assert report["aba"]
    assert report["matrix"] == [3, 1, 1]
    assert report["moved"] > 1e-4
    assert report["error"] <= 1e-13

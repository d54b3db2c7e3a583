"""NOC dynamics and RK4 against MuJoCo, an independent engine (MJCF from benchmarks/mujoco_model.py).

MuJoCo computes inverse dynamics with its own recursive algorithms in spatial (6-D)
coordinates; its RK4 (``integrator="RK4"``) is the classical tableau on (qpos, qvel), so with
no damping, armature or contacts both trajectories agree to round-off.
"""

import mujoco
import numpy as np
import pytest
from planar_tui.kernels.dynamics import inverse_dynamics
from planar_tui.kernels.noc_matrices import gravity_vector, mass_matrix, velocity_product
from planar_tui.kernels.rk4 import rk4_integrate, rk4_record_count

from benchmarks.mujoco_model import chain_model, mujoco_inverse, set_chain_parameters
from tests.test_dynamics_kernels import G, random_robot, random_state, table1_robot


@pytest.mark.parametrize("n", [1, 2, 3, 6, 10])
def test_inverse_dynamics_matches_mj_inverse(n):
    """Random parameters and states: max |Δτ| / max |τ| <= 1e-9."""
    rng = np.random.default_rng(200 + n)
    model, data = chain_model(*random_robot(rng, n), G)
    worst = 0.0
    for _ in range(4):  # parameter sets, written into the same compiled model
        robot = random_robot(rng, n)
        set_chain_parameters(model, *robot)
        for _ in range(10):
            theta, omega, alpha = random_state(rng, n)
            expected = mujoco_inverse(model, data, theta, omega, alpha)
            tau = inverse_dynamics(*robot, G, theta, omega, alpha)
            worst = max(worst, np.abs(tau - expected).max() / np.abs(expected).max())
    assert worst <= 1e-9


def test_mass_matrix_and_bias_match_mujoco():
    rng = np.random.default_rng(300)
    robot = random_robot(rng, 6)
    model, data = chain_model(*robot, G)
    theta, omega, _ = random_state(rng, 6)
    data.qpos[:] = theta
    data.qvel[:] = omega
    mujoco.mj_forward(model, data)
    full = np.zeros((6, 6))
    mujoco.mj_fullM(model, data, full)
    np.testing.assert_allclose(mass_matrix(*robot, theta), full, rtol=1e-12, atol=1e-14)
    bias = velocity_product(*robot, theta, omega) - gravity_vector(robot[0], robot[1], G, theta)
    np.testing.assert_allclose(bias, data.qfrc_bias, rtol=1e-11, atol=1e-12)


def test_table1_torque_run_matches_mujoco_rk4():
    """Paper A Table 1 torques, RK4 at 1e-4 s for 1 s: |θ - θ_MuJoCo| <= 1e-8 rad at every step."""
    lengths, masses, inertias, torque = table1_robot()
    steps = 10_000
    model, data = chain_model(lengths, masses, inertias, G, timestep_s=1e-4)
    data.qfrc_applied[:] = torque
    reference = np.empty((steps + 1, 6))
    reference[0] = data.qpos
    for k in range(1, steps + 1):
        mujoco.mj_step(model, data)
        reference[k] = data.qpos

    rows = rk4_record_count(steps, 1)
    t_out, theta_out, omega_out = np.zeros(rows), np.zeros((rows, 6)), np.zeros((rows, 6))
    theta, omega = np.zeros(6), np.zeros(6)
    rk4_integrate(
        lengths,
        masses,
        inertias,
        G,
        torque,
        theta,
        omega,
        1e-4,
        steps,
        1,
        0,
        t_out,
        theta_out,
        omega_out,
        np.zeros(rows),
        np.zeros(rows),
    )
    assert np.abs(theta_out - reference).max() <= 1e-8
    np.testing.assert_allclose(omega, data.qvel, rtol=0, atol=1e-6)
    assert np.abs(theta_out[-1]).max() > 0.3  # the arm really moved

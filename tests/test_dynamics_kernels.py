"""NOC dynamics and RK4 kernels against independent methods.

Oracles: the dense NOC products T^T M T, T^T M Tdot, T^T w_G built in numpy from eqs. (4)-(8);
finite differences of centre-of-mass positions written out here; the 2R Lagrange equations
written out by hand; conservation of energy and the power balance dE/dt = θ̇ᵀτ.
"""

import csv

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from planar_tui.kernels.dynamics import (
    energies,
    forward_dynamics,
    inverse_dynamics,
)
from planar_tui.kernels.dynamics_batch import inverse_dynamics_batch, inverse_dynamics_batch_states
from planar_tui.kernels.noc_matrices import (
    gravity_vector,
    mass_matrix,
    twist_shaping_matrix,
    twist_shaping_matrix_rate,
    velocity_product,
)
from planar_tui.kernels.rk4 import rk4_integrate, rk4_record_count

from tests.conftest import REFERENCE

G = 9.81


def random_robot(rng, n):
    lengths = rng.uniform(0.1, 0.6, n)
    masses = rng.uniform(0.2, 3.0, n)
    inertias = masses * lengths**2 / 12.0 * rng.uniform(0.3, 2.0, n)
    return lengths, masses, inertias


def random_state(rng, n):
    return rng.uniform(-np.pi, np.pi, n), rng.normal(0.0, 2.0, n), rng.normal(0.0, 5.0, n)


def table1_robot():
    with open(REFERENCE / "paper_6r_simulation.csv", newline="") as handle:
        rows = list(csv.DictReader(handle))
    column = lambda key: np.array([float(row[key]) for row in rows])  # noqa: E731
    return column("length_m"), column("mass_kg"), column("inertia_kgm2"), column("torque_Nm")


def com_positions(lengths, theta):
    """Centres of mass (n, 2), from plain geometry (relative angles, COM at mid-link)."""
    phi = np.cumsum(theta)
    links = lengths[:, None] * np.column_stack([np.cos(phi), np.sin(phi)])
    joints = np.vstack([np.zeros(2), np.cumsum(links, axis=0)[:-1]])
    return joints + 0.5 * links


def dense_noc(lengths, masses, inertias, theta, omega):
    """(T, Tdot, M, w_G) as dense numpy arrays, eqs. (4), (5), (7), (8)."""
    n = len(lengths)
    big_t = twist_shaping_matrix(lengths, theta)
    big_t_dot = twist_shaping_matrix_rate(lengths, theta, omega)
    big_m = np.diag(np.column_stack([inertias, masses, masses]).ravel())
    wrench = np.column_stack([np.zeros(n), np.zeros(n), -masses * G]).ravel()
    return big_t, big_t_dot, big_m, wrench


@pytest.mark.parametrize("n", [1, 2, 3, 6, 10])
def test_kernels_equal_dense_noc_products(n):
    rng = np.random.default_rng(100 + n)
    lengths, masses, inertias = random_robot(rng, n)
    for _ in range(5):
        theta, omega, alpha = random_state(rng, n)
        big_t, big_t_dot, big_m, wrench = dense_noc(lengths, masses, inertias, theta, omega)
        tau_dense = big_t.T @ (big_m @ big_t @ alpha + big_m @ big_t_dot @ omega - wrench)
        tau = inverse_dynamics(lengths, masses, inertias, G, theta, omega, alpha)
        np.testing.assert_allclose(tau, tau_dense, rtol=0, atol=1e-12 * np.abs(tau_dense).max())
        np.testing.assert_allclose(
            mass_matrix(lengths, masses, inertias, theta),
            big_t.T @ big_m @ big_t,
            rtol=1e-13,
            atol=1e-15,
        )
        np.testing.assert_allclose(
            velocity_product(lengths, masses, inertias, theta, omega),
            big_t.T @ big_m @ big_t_dot @ omega,
            rtol=1e-12,
            atol=1e-13,
        )
        np.testing.assert_allclose(
            gravity_vector(lengths, masses, G, theta), big_t.T @ wrench, rtol=1e-12, atol=1e-13
        )


def test_twist_shaping_matrix_maps_rates_to_link_twists():
    """T θ̇ = [Ω_i, ċ_i] with ċ_i by central differences of the COM positions (eq. 4, E = +90°)."""
    rng = np.random.default_rng(7)
    lengths, _, _ = random_robot(rng, 5)
    theta, omega, _ = random_state(rng, 5)
    twist = (twist_shaping_matrix(lengths, theta) @ omega).reshape(5, 3)
    h = 1e-6
    com_rate = (
        com_positions(lengths, theta + h * omega) - com_positions(lengths, theta - h * omega)
    ) / (2 * h)
    np.testing.assert_allclose(twist[:, 0], np.cumsum(omega), rtol=1e-14)
    np.testing.assert_allclose(twist[:, 1:], com_rate, rtol=0, atol=1e-8)
    upper = np.triu(np.ones((5, 5), dtype=bool), k=1)
    assert (
        not twist_shaping_matrix(lengths, theta).reshape(5, 3, 5).transpose(1, 0, 2)[:, upper].any()
    )


def test_twist_shaping_matrix_rate_is_time_derivative():
    rng = np.random.default_rng(8)
    lengths, _, _ = random_robot(rng, 6)
    theta, omega, _ = random_state(rng, 6)
    h = 1e-6
    numeric = (
        twist_shaping_matrix(lengths, theta + h * omega)
        - twist_shaping_matrix(lengths, theta - h * omega)
    ) / (2 * h)
    np.testing.assert_allclose(
        twist_shaping_matrix_rate(lengths, theta, omega), numeric, rtol=0, atol=1e-8
    )


def lagrange_2r(lengths, masses, inertias, theta, omega, alpha):
    """The textbook 2R equations (relative angles, COM at mid-link, y up), by hand."""
    l1, _ = lengths
    lc1, lc2 = lengths / 2
    m1, m2 = masses
    i1, i2 = inertias
    c2 = np.cos(theta[1])
    m11 = i1 + i2 + m1 * lc1**2 + m2 * (l1**2 + lc2**2 + 2 * l1 * lc2 * c2)
    m12 = i2 + m2 * (lc2**2 + l1 * lc2 * c2)
    m22 = i2 + m2 * lc2**2
    h = -m2 * l1 * lc2 * np.sin(theta[1])
    g1 = (m1 * lc1 + m2 * l1) * G * np.cos(theta[0]) + m2 * lc2 * G * np.cos(theta[0] + theta[1])
    g2 = m2 * lc2 * G * np.cos(theta[0] + theta[1])
    tau1 = m11 * alpha[0] + m12 * alpha[1] + h * omega[1] ** 2 + 2 * h * omega[0] * omega[1] + g1
    tau2 = m12 * alpha[0] + m22 * alpha[1] - h * omega[0] ** 2 + g2
    return np.array([tau1, tau2])


def test_inverse_dynamics_2r_closed_form():
    rng = np.random.default_rng(9)
    for _ in range(20):
        lengths, masses, inertias = random_robot(rng, 2)
        theta, omega, alpha = random_state(rng, 2)
        expected = lagrange_2r(lengths, masses, inertias, theta, omega, alpha)
        tau = inverse_dynamics(lengths, masses, inertias, G, theta, omega, alpha)
        np.testing.assert_allclose(tau, expected, rtol=1e-12, atol=1e-12)


@pytest.mark.slow
def test_forward_inverts_inverse():
    rng = np.random.default_rng(10)
    for n in (1, 2, 3, 6, 10):
        lengths, masses, inertias = random_robot(rng, n)
        theta, omega, alpha = random_state(rng, n)
        tau = inverse_dynamics(lengths, masses, inertias, G, theta, omega, alpha)
        back = forward_dynamics(lengths, masses, inertias, G, theta, omega, tau)
        np.testing.assert_allclose(back, alpha, rtol=0, atol=1e-10 * max(1.0, np.abs(alpha).max()))


def test_batches_equal_single_state_loops():
    rng = np.random.default_rng(11)
    n, samples = 6, 2500  # more than two chunks of 1024
    lengths = rng.uniform(0.1, 0.6, (samples, n))
    masses = rng.uniform(0.2, 3.0, (samples, n))
    inertias = rng.uniform(1e-3, 0.1, (samples, n))
    theta, omega, alpha = random_state(rng, n)
    batch = inverse_dynamics_batch(lengths, masses, inertias, G, theta, omega, alpha)
    loop = np.array(
        [
            inverse_dynamics(lengths[s], masses[s], inertias[s], G, theta, omega, alpha)
            for s in range(samples)
        ]
    )
    np.testing.assert_allclose(batch, loop, rtol=1e-12, atol=1e-12)

    states = rng.uniform(-3, 3, (3, samples, n))
    batch = inverse_dynamics_batch_states(lengths[0], masses[0], inertias[0], G, *states)
    loop = np.array(
        [
            inverse_dynamics(
                lengths[0], masses[0], inertias[0], G, states[0, s], states[1, s], states[2, s]
            )
            for s in range(samples)
        ]
    )
    np.testing.assert_allclose(batch, loop, rtol=1e-12, atol=1e-12)


def test_batch_rejects_mismatched_shapes():
    ones = np.ones((4, 3))
    with pytest.raises(ValueError, match="same shape"):
        inverse_dynamics_batch(ones, np.ones((4, 2)), ones, G, np.ones(3), np.ones(3), np.ones(3))


def test_energies_by_hand():
    rng = np.random.default_rng(12)
    lengths, masses, inertias = random_robot(rng, 4)
    theta, omega, _ = random_state(rng, 4)
    kinetic, potential = energies(lengths, masses, inertias, G, theta, omega)
    assert kinetic == pytest.approx(
        0.5 * omega @ mass_matrix(lengths, masses, inertias, theta) @ omega, rel=1e-13
    )
    assert potential == pytest.approx(G * masses @ com_positions(lengths, theta)[:, 1], rel=1e-13)


@st.composite
def robots_in_states(draw):
    """(rng, robot, state) with 1..8 links, from a drawn seed."""
    n = draw(st.integers(1, 8))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    return rng, random_robot(rng, n), random_state(rng, n)


@settings(deadline=None, max_examples=25)
@given(case=robots_in_states())
def test_mass_matrix_symmetric_positive_definite(case):
    _, (lengths, masses, inertias), (theta, _, _) = case
    matrix = mass_matrix(lengths, masses, inertias, theta)
    np.testing.assert_array_equal(matrix, matrix.T)
    assert np.linalg.eigvalsh(matrix).min() > 0.0


@settings(deadline=None, max_examples=25)
@given(case=robots_in_states())
def test_power_balance(case):
    """d/dt (K + V) = θ̇ᵀτ along the forward dynamics (central difference in time)."""
    rng, (lengths, masses, inertias), (theta, omega, _) = case
    tau = rng.normal(0.0, 3.0, len(lengths))
    alpha = forward_dynamics(lengths, masses, inertias, G, theta, omega, tau)
    h = 1e-6

    def total_energy(sign):
        return sum(
            energies(
                lengths, masses, inertias, G, theta + sign * h * omega, omega + sign * h * alpha
            )
        )

    power = (total_energy(1) - total_energy(-1)) / (2 * h)
    scale = 1.0 + np.abs(omega) @ np.abs(tau) + np.abs(omega) @ np.abs(omega) * masses.sum()
    assert abs(power - omega @ tau) <= 1e-6 * scale


def run_rk4(robot, torque, theta0, omega0, step_s, n_steps, every=1, chunk=None):
    lengths, masses, inertias = robot
    n = len(lengths)
    rows = rk4_record_count(n_steps, every)
    out = (np.zeros(rows), np.zeros((rows, n)), np.zeros((rows, n)), np.zeros(rows), np.zeros(rows))
    theta, omega = theta0.copy(), omega0.copy()
    chunk = chunk or n_steps
    written = 0
    for start in range(0, n_steps, chunk):
        steps = min(chunk, n_steps - start)
        written += rk4_integrate(
            lengths,
            masses,
            inertias,
            G,
            torque,
            theta,
            omega,
            step_s,
            steps,
            every,
            start,
            *(a[written:] for a in out),
        )
    assert written == rows
    return out, theta, omega


def test_rk4_chunked_equals_one_shot_and_records():
    rng = np.random.default_rng(13)
    robot = random_robot(rng, 4)
    theta0, omega0, _ = random_state(rng, 4)
    torque = rng.normal(0.0, 0.5, 4)
    whole, theta_a, omega_a = run_rk4(robot, torque, theta0, omega0, 1e-3, 1000, every=7)
    chunked, theta_b, omega_b = run_rk4(
        robot, torque, theta0, omega0, 1e-3, 1000, every=7, chunk=300
    )
    for a, b in zip(whole, chunked, strict=True):
        np.testing.assert_array_equal(a, b)
    np.testing.assert_array_equal(theta_a, theta_b)
    np.testing.assert_array_equal(omega_a, omega_b)
    np.testing.assert_array_equal(whole[0], np.arange(0, 1001, 7) * 1e-3)
    np.testing.assert_array_equal(whole[1][0], theta0)
    assert (
        rk4_record_count(1000, 7) == 143
        and rk4_record_count(10, 10) == 2
        and rk4_record_count(10, 1) == 11
    )


def test_rk4_fourth_order_convergence():
    """Halving the step divides the final-state error by about 2^4 = 16."""
    rng = np.random.default_rng(14)
    robot = random_robot(rng, 2)
    theta0, omega0, _ = random_state(rng, 2)
    torque = rng.normal(0.0, 0.5, 2)
    finals = [
        run_rk4(robot, torque, theta0, omega0, 0.2 / steps, steps)[1]
        for steps in (20, 40, 80, 1280)
    ]
    errors = [np.abs(final - finals[-1]).max() for final in finals[:3]]
    ratios = errors[0] / errors[1], errors[1] / errors[2]
    assert all(12.0 < r < 20.0 for r in ratios), ratios


def test_table1_free_fall_conserves_energy():
    """Paper A free fall, RK4 step 1e-4 s over 1 s: |E(t) - E(0)| <= 1e-9 J at every step."""
    lengths, masses, inertias, _ = table1_robot()
    zeros = np.zeros(6)
    (_, _, _, kinetic, potential), _, _ = run_rk4(
        (lengths, masses, inertias), zeros, zeros, zeros, 1e-4, 10_000
    )
    energy = kinetic + potential
    assert energy[0] == 0.0
    assert np.abs(energy - energy[0]).max() <= 1e-9
    assert potential.min() < -1.0  # it really fell

"""Both sides of the switch to the O(n) articulated-body algorithm (kernels/aba_planar.py,
``ABA_MIN_LINKS = 7``): chains of 6 and 7 links (and around) through
:func:`forward_dynamics_rows_auto` with :func:`auto_work`'s arrays, as ``rk4_step`` calls
it, against an independent solve (the NOC mass matrix of :mod:`kernels.noc_matrices` and
the Newton-Euler bias, solved by ``numpy.linalg.solve``), and the promise of the docs
(README, "Forward dynamics of long chains"; docs/dynamics.md, "Crossover"): chains of at
most 6 links keep the NOC ``LDLᵀ``, so their results keep every bit."""

import numpy as np
import pytest
from planar_tui.kernels.aba_planar import (
    ABA_MIN_LINKS,
    aba_forward_dynamics,
    auto_work,
    forward_dynamics_rows_auto,
    uses_aba,
)
from planar_tui.kernels.dynamics import forward_dynamics, inverse_dynamics
from planar_tui.kernels.noc_matrices import mass_matrix

from tests.test_dynamics_kernels import G, random_robot, random_state, table1_robot


def auto(robot, theta, omega, tau):
    """θ̈ by the switch, into row 1 of a 3-row output (as the batch kernels use it)."""
    n = len(theta)
    work, matrix = auto_work(n)
    alpha = np.full((3, n), np.nan)
    forward_dynamics_rows_auto(*robot, G, theta, omega, tau, work, matrix, alpha, 1)
    assert np.isnan(alpha[[0, 2]]).all()  # no other row written
    return alpha[1]


def numpy_solve(robot, theta, omega, tau):
    """θ̈ = M(θ)⁻¹ (τ − bias), M from the composite-body sums, bias = ID(θ, θ̇, 0)."""
    bias = inverse_dynamics(*robot, G, theta, omega, np.zeros(len(theta)))
    return np.linalg.solve(mass_matrix(*robot, theta), tau - bias)


def test_the_switch_sits_at_seven_links_in_each_place_that_chooses():
    assert ABA_MIN_LINKS == 7
    assert not uses_aba(6) and uses_aba(7)
    assert auto_work(6)[0].shape == (9, 6) and auto_work(6)[1].shape == (6, 6)
    assert auto_work(7)[0].shape == (9, 7) and auto_work(7)[1].shape == (1, 1)


@pytest.mark.parametrize("n", [1, 5, 6, 7, 8])
def test_each_side_of_the_switch_equals_a_numpy_solve_and_its_own_algorithm(n):
    """≤ 6 links: the NOC LDLᵀ bit for bit; ≥ 7: the articulated-body recursion bit for
    bit; both within 1e-12 of an independent solve."""
    for seed in range(3):
        rng = np.random.default_rng(1000 * n + seed)
        robot = random_robot(rng, n)
        theta, omega, _ = random_state(rng, n)
        tau = rng.normal(0.0, 3.0, n)
        alpha = auto(robot, theta, omega, tau)
        reference = numpy_solve(robot, theta, omega, tau)
        assert np.abs(alpha - reference).max() <= 1e-12 * np.abs(reference).max()
        own = (aba_forward_dynamics if n >= 7 else forward_dynamics)(*robot, G, theta, omega, tau)
        assert np.array_equal(alpha, own)


#: θ̈ of the paper's Table 1 6R (tests/data/reference/paper_6r_simulation.csv: lengths,
#: masses, inertias, torques) at the state of the test below, computed at commit 0b9a7df by
#: the NOC mass matrix + LDLᵀ (kernels.dynamics.forward_dynamics), before any change to
#: the switch: the bits the bundled presets' simulations rest on.
TABLE1_ALPHA_HEX = (
    "0x1.5be723e4147fcp+2",
    "-0x1.3905096c23bb8p+5",
    "0x1.4af2f60d339e6p+3",
    "0x1.1501a7ec5e331p+4",
    "0x1.85021850ecc61p+4",
    "-0x1.aa72a1449ab09p+4",
)


def test_the_table1_six_link_robot_keeps_every_bit():
    """The stored values are right (within 1e-12 of a numpy solve), and the switch, the
    NOC forward dynamics give exactly those bits."""
    lengths, masses, inertias, tau = table1_robot()
    robot = (lengths, masses, inertias)
    theta = np.radians([10.0, -35.0, 60.0, 20.0, -80.0, 45.0])
    omega = np.array([0.5, -1.0, 1.5, 0.25, -0.75, 2.0])
    stored = np.array([float.fromhex(text) for text in TABLE1_ALPHA_HEX])
    reference = numpy_solve(robot, theta, omega, tau)
    assert np.abs(stored - reference).max() <= 1e-12 * np.abs(reference).max()
    assert np.array_equal(auto(robot, theta, omega, tau), stored)
    assert np.array_equal(forward_dynamics(*robot, G, theta, omega, tau), stored)

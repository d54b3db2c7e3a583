r"""Closed-form oracle: Sobol' indices of the torques in the singular posture.

Independent of the code under test. With all joint angles 0 and zero acceleration the
velocity terms produce no torque and

.. math:: \tau_i = g \sum_{k \ge i} m_k \Big(\sum_{j=i}^{k-1} l_j + \tfrac12 l_k\Big)
               = g \sum_{i \le j \le k} c_{jk}\, l_j m_k,\quad c_{jk} = 1\ (j<k),\ \tfrac12\ (j=k),

a bilinear polynomial in independent uniform inputs :math:`l_j = L_j + \delta_j`,
:math:`m_k = M_k + \varepsilon_k`, :math:`\delta_j \sim U(\pm a)`, :math:`\varepsilon_k \sim
U(\pm b)`, :math:`\mathrm{Var}\,\delta = a^2/3`, :math:`\mathrm{Var}\,\varepsilon = b^2/3`. Its
ANOVA terms are :math:`\delta_j \alpha_j` with :math:`\alpha_j = g\sum_k c_{jk} M_k`,
:math:`\varepsilon_k \beta_k` with :math:`\beta_k = g\sum_j c_{jk} L_j`, and
:math:`g c_{jk}\delta_j\varepsilon_k`, so

.. math:: V_{l_j} = \alpha_j^2 a^2/3,\quad V_{m_k} = \beta_k^2 b^2/3,\quad
          V_{jk} = g^2 c_{jk}^2 (a^2/3)(b^2/3),

:math:`S_{l_j} = V_{l_j}/V`, :math:`S_{T,l_j} = (V_{l_j} + \sum_k V_{jk})/V` and likewise for
:math:`m_k`, with V the sum of all terms.

Criterion of issue 3: |S − exact| <= 0.01 for both methods, and within 3 × the reported
confidence half-width for Sobol'. eFAST's bootstrap half-widths (SALib #649) are not error
bars (they can be ~0 where eFAST's interference bias is 0.002): for eFAST only the
absolute bound is required, as docs/sensitivity.md explains.
"""

import numpy as np
import pytest

from planar_tui.dynamics.robot import SerialRobot
from planar_tui.sensitivity.engine import analyse, build_problem, evaluate, unit_design

ROBOTS = {
    "2R": ([0.303, 0.214], [1.126, 0.796]),
    "3R": ([0.303, 0.303, 0.175], [1.126, 1.126, 0.650]),
    "6R": ([0.303] * 6, [1.126] * 6),
}


def singular_indices(lengths_m, masses_kg, tol_length_m, tol_mass_kg, gravity_m_s2=9.81):
    """Exact (S1, ST), each (n torques, 2n inputs) ordered l1..ln, m1..mn."""
    lengths = np.asarray(lengths_m, dtype=float)
    masses = np.asarray(masses_kg, dtype=float)
    n = len(lengths)
    var_l = tol_length_m**2 / 3.0
    var_m = tol_mass_kg**2 / 3.0
    first = np.zeros((n, 2 * n))
    total = np.zeros((n, 2 * n))
    for i in range(n):
        c = np.zeros((n, n))  # c[j, k]: coefficient of l_j m_k in tau_i / g
        for k in range(i, n):
            c[i:k, k] = 1.0
            c[k, k] = 0.5
        alpha = gravity_m_s2 * c @ masses
        beta = gravity_m_s2 * c.T @ lengths
        v_l = alpha**2 * var_l
        v_m = beta**2 * var_m
        v_lm = (gravity_m_s2 * c) ** 2 * var_l * var_m
        variance = v_l.sum() + v_m.sum() + v_lm.sum()
        first[i] = np.concatenate([v_l, v_m]) / variance
        total[i] = np.concatenate([v_l + v_lm.sum(axis=1), v_m + v_lm.sum(axis=0)]) / variance
    return first, total


def test_oracle_is_a_variance_decomposition():
    """Sanity of the oracle itself against brute-force Monte Carlo of the polynomial."""
    lengths, masses = ROBOTS["3R"]
    first, total = singular_indices(lengths, masses, 1e-3, 1e-2)
    assert np.all(total >= first - 1e-15)
    rng = np.random.default_rng(1)
    draws = 400_000
    ls = np.array(lengths) + rng.uniform(-1e-3, 1e-3, (draws, 3))
    m = np.array(masses) + rng.uniform(-1e-2, 1e-2, (draws, 3))
    tau1 = 9.81 * (m[:, 0] * ls[:, 0] / 2 + m[:, 1] * (ls[:, 0] + ls[:, 1] / 2))
    tau1 += 9.81 * m[:, 2] * (ls[:, 0] + ls[:, 1] + ls[:, 2] / 2)
    # first-order index of m3 by conditioning on bins of m3 (independent estimator)
    bins = np.digitize(m[:, 2], np.linspace(masses[2] - 1e-2, masses[2] + 1e-2, 41))
    means = np.array([tau1[bins == b].mean() for b in np.unique(bins)])
    weights = np.array([(bins == b).mean() for b in np.unique(bins)])
    s_m3 = np.sum(weights * (means - tau1.mean()) ** 2) / tau1.var()
    assert s_m3 == pytest.approx(first[0, 5], abs=0.01)


@pytest.mark.parametrize("robot", list(ROBOTS))
@pytest.mark.parametrize("tol_mass_kg", [1e-3, 1e-2])
@pytest.mark.parametrize(("method", "samples"), [("sobol", 4096), ("efast", 2000)])
def test_singular_indices_match_closed_form(robot, tol_mass_kg, method, samples):
    lengths, masses = ROBOTS[robot]
    n = len(lengths)
    model = SerialRobot(tuple(lengths), tuple(masses), (0.1,) * n)
    problem = build_problem(model, 1e-3, tol_mass_kg)
    design = unit_design(method, problem.num_vars, samples, 42)
    torques = evaluate(problem, design, model, np.zeros(n), np.ones(n), np.zeros(n))
    s1, s1_conf, st, st_conf = analyse(method, torques, 2 * n, 42)
    exact_first, exact_total = singular_indices(lengths, masses, 1e-3, tol_mass_kg)
    assert np.abs(s1 - exact_first).max() <= 0.01
    assert np.abs(st - exact_total).max() <= 0.01
    if method == "sobol":
        assert np.all(np.abs(s1 - exact_first) <= 3 * s1_conf + 1e-12)
        assert np.all(np.abs(st - exact_total) <= 3 * st_conf + 1e-12)


def test_torques_are_nearly_linear_so_first_equals_total():
    """At these tolerances S_T − S_1 (the interaction share) is below 1e-4."""
    for lengths, masses in ROBOTS.values():
        for tol_mass in (1e-3, 1e-2):
            first, total = singular_indices(lengths, masses, 1e-3, tol_mass)
            assert np.abs(total - first).max() < 1e-4

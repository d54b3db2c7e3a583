"""The polynomial chaos engine (:mod:`planar_tui.sensitivity.pce`) against closed forms.

- a linear model: degree 1 is exact, S1 = ST = a_i² / Σ a² to 1e-12;
- the bilinear gravity torques of a 4R in its singular posture with wide tolerances (the
  interactions matter): S1, ST and the second-order indices of the exact ANOVA
  (``tests/test_sensitivity_oracle.singular_indices``; the second-order terms
  g² c_jk² Var l_j Var m_k / V derived below);
- the 1-link zero-gravity motion θ(T) = τT²/(2(I + m l²/4)) (not a polynomial): S1, ST
  against Gauss-Legendre quadrature (``tests/test_motion_job.exact_moments``) within 0.01
  at the default ``pce_samples``;
- the basis is orthonormal (quadrature), OMP recovers a sparse model's exact terms, the
  bootstrap equals refits on explicitly repeated rows, a discontinuous model fails the
  LOO check with its one line; aggregated indices against their definition (Gamboa et
  al. 2014) by quadrature.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from planar_tui.dynamics.robot import SerialRobot
from planar_tui.sensitivity import pce, pce_analysis, pce_indices
from planar_tui.sensitivity.aggregate import aggregated_indices
from planar_tui.sensitivity.engine import build_problem, evaluate
from planar_tui.sensitivity.failed_runs import FailedRuns, check_failed_runs, failure_corner
from tests.test_motion_job import CASES, DL, DM, L0, M0, exact_moments, theta_closed_form
from tests.test_sensitivity_oracle import singular_indices

SEED = 42


def test_total_degree_indices_are_every_multi_index_once():
    for d, p in ((1, 4), (3, 3), (12, 2)):
        indices = pce.total_degree_indices(d, p)
        assert len(indices) == math.comb(d + p, p)
        assert len({tuple(row) for row in indices}) == len(indices)
        assert indices.sum(axis=1).max() == p and indices.min() == 0
        assert np.all(np.diff(indices.sum(axis=1)) >= 0)  # graded, the constant first


def test_legendre_basis_is_orthonormal_under_the_uniform_law():
    x, w = np.polynomial.legendre.leggauss(12)
    u = (x + 1.0) / 2.0
    table = pce.legendre_table(u[:, None], 6)[:, 0]  # (12 nodes, 7 degrees)
    gram = table.T @ (table * (w / 2.0)[:, None])
    assert np.abs(gram - np.eye(7)).max() <= 1e-13
    assert table[:, 2] == pytest.approx(math.sqrt(5.0) * (3 * x**2 - 1) / 2, abs=1e-14)


def test_linear_model_is_exact_at_degree_one():
    d = 6
    a = np.array([1.0, -2.0, 0.5, 0.0, 3.0, 0.25])
    unit = pce.pce_unit_design(d, pce.default_pce_samples(d), SEED)
    y = 4.0 + (2.0 * unit - 1.0) @ a
    indices, (fit,) = pce.pce_indices(unit, y, SEED)
    exact = a**2 / (a**2).sum()
    assert fit.degree == 1
    assert np.abs(indices[0, 0] - exact).max() <= 1e-12
    assert np.abs(indices[2, 0] - exact).max() <= 1e-12
    assert fit.loo_error[0] <= 1e-20
    assert fit.mean[0] == pytest.approx(4.0, abs=1e-12)
    assert fit.variance[0] == pytest.approx((a**2).sum() / 3.0, rel=1e-12)
    assert indices[[1, 3]].max() <= 1e-10  # every resample fits it exactly too


def test_omp_finds_the_terms_of_a_sparse_model_beside_an_output_it_cannot_fit():
    unit = pce.pce_unit_design(4, 256, SEED)
    indices = pce.total_degree_indices(4, 3)
    psi = pce.basis_matrix(unit, indices)
    wanted = {0: 1.5, 7: 3.0, 20: -0.7}  # the constant and two other terms
    y = sum(c * psi[:, j] for j, c in wanted.items())
    step = np.where(unit[:, 0] + unit[:, 3] > 1.0, 1.0, 0.0)
    alone = pce.omp_path(psi, y[:, None])
    assert set(alone.terms.tolist()) == set(wanted)  # exactly its terms when alone
    for outputs in (y[:, None], np.stack([step, y], axis=1)):
        path = pce.omp_path(psi, outputs)
        t = outputs.shape[1] - 1  # the sparse model's column
        k = path.term_counts[t]
        assert set(wanted) <= set(path.terms[:k].tolist())  # (the step's terms may come first)
        got = dict(zip(path.terms[:k].tolist(), path.coefficients[:k, t], strict=True))
        assert all(got[j] == pytest.approx(wanted.get(j, 0.0), abs=1e-12) for j in got)
        assert np.all(path.coefficients[k:, t] == 0.0)
        assert path.loo_error[t] <= 1e-20
    assert path.loo_error[0] > 0.01  # the step stays badly fitted, alone


def four_r_gravity(tol_length_m, tol_mass_kg):
    lengths, masses = [0.3, 0.25, 0.2, 0.15], [1.2, 0.9, 0.6, 0.3]
    robot = SerialRobot(tuple(lengths), tuple(masses), (0.05,) * 4)
    problem = build_problem(robot, tol_length_m, tol_mass_kg)
    zeros = np.zeros(4)

    def torques(unit):
        return evaluate(problem, np.ascontiguousarray(unit), robot, zeros, zeros, zeros)

    return lengths, masses, torques


def test_bilinear_4r_gravity_torques_match_the_exact_anova():
    """Wide tolerances (±0.1 m, ±0.25 kg) so that ST − S1 reaches a few percent."""
    lengths, masses, torques = four_r_gravity(0.1, 0.25)
    d = 8
    unit = pce.pce_unit_design(d, pce.default_pce_samples(d), SEED)
    indices, fits = pce.pce_indices(unit, torques(unit), SEED)
    first, total = singular_indices(lengths, masses, 0.1, 0.25)
    assert np.abs(indices[0] - first).max() <= 1e-9
    assert np.abs(indices[2] - total).max() <= 1e-9
    assert (total - first).max() > 0.02  # the interactions are not negligible here
    # second order: g² c_jk² Var l_j Var m_k / V for the pair (l_j, m_k), 0 otherwise
    var_l, var_m = 0.1**2 / 3.0, 0.25**2 / 3.0
    for i, fit in enumerate(fits):
        second = pce.second_order_indices(fit.indices, fit.coefficients)[0]
        c = np.zeros((4, 4))
        for k in range(i, 4):
            c[i:k, k] = 1.0
            c[k, k] = 0.5
        pair = (9.81 * c) ** 2 * var_l * var_m / fit.variance[0]
        expected = np.zeros((d, d))
        expected[:4, 4:] = pair
        expected[4:, :4] = pair.T
        assert np.abs(second - expected).max() <= 1e-9
        assert indices[0, i].sum() + second.sum() / 2 == pytest.approx(1.0, abs=1e-9)


@pytest.mark.parametrize("case", CASES)
def test_one_link_motion_matches_quadrature_at_the_default_samples(case):
    inertia, tolerance_inertia = CASES[case]
    d = 2 if tolerance_inertia is None else 3
    unit = pce.pce_unit_design(d, pce.default_pce_samples(d), SEED)
    x = 2.0 * unit - 1.0
    args = [L0 + DL * x[:, 0], M0 + DM * x[:, 1]]
    args.append(inertia if d == 2 else inertia + tolerance_inertia * x[:, 2])
    indices, (fit,) = pce.pce_indices(unit, theta_closed_form(*args), SEED)
    _, variance, _, first, total = exact_moments(inertia, tolerance_inertia)
    assert np.abs(indices[0, 0] - np.array(first) / variance).max() <= 0.01
    assert np.abs(indices[2, 0] - np.array(total) / variance).max() <= 0.01
    assert fit.variance[0] == pytest.approx(variance, rel=0.01)
    assert fit.loo_error[0] < 1e-3


def test_bootstrap_equals_refits_of_the_wild_resamples():
    unit = pce.pce_unit_design(3, 128, SEED)
    smooth = np.exp(unit @ np.array([1.0, 0.5, 0.2]))
    y = np.stack([smooth, np.sin(3 * unit[:, 0]) * unit[:, 2], unit[:, 1]], axis=1)
    fit = pce.fit_pce(unit, y)
    assert len(set(fit.term_counts.tolist())) == 3  # each output on its own terms
    resamples = 5
    half_first, half_total = pce.bootstrap_halfwidths(fit, y, 7, resamples)
    signs = np.random.default_rng(7).integers(0, 2, size=(len(unit), resamples)) * 2.0 - 1.0
    fitted = fit.basis @ fit.coefficients
    firsts, totals = [], []
    for b in range(resamples):
        resampled = fitted + (y - fitted) * signs[:, b : b + 1]
        coefficients = np.zeros_like(fit.coefficients)
        for t, k in enumerate(fit.term_counts):
            coefficients[:k, t] = np.linalg.lstsq(fit.basis[:, :k], resampled[:, t], rcond=None)[0]
        first, total = pce_indices.indices_from_coefficients(fit.indices, coefficients)
        firsts.append(first)
        totals.append(total)
    z = 1.959963984540054
    assert half_first == pytest.approx(z * np.std(firsts, axis=0, ddof=1), rel=1e-6, abs=1e-15)
    assert half_total == pytest.approx(z * np.std(totals, axis=0, ddof=1), rel=1e-6, abs=1e-15)
    assert half_total[:2].min() > 0.0 and half_total[2].max() <= 1e-12  # u2 alone: exact


def test_a_discontinuous_model_fails_the_loo_check_with_one_line():
    unit = pce.pce_unit_design(3, 64, SEED)
    y = np.where(unit[:, 0] + unit[:, 1] > 1.0, 1.0, 0.0) + unit[:, 2]
    _, fits = pce.pce_indices(unit, y, SEED, num_resamples=0)
    assert fits[0].loo_error[0] > 0.01
    with pytest.raises(pce.PceError) as raised:
        pce_analysis.check_loo(fits, ["tau1"], 0.01, 64)
    message = str(raised.value)
    assert "\n" not in message
    assert (
        "leave-one-out error" in message and "of tau1 exceeds pce_max_loo_error = 0.01" in message
    )
    assert "raise pce_samples (now 64) or pce_max_loo_error" in message
    pce_analysis.check_loo(fits, ["tau1"], 1.0, 64)  # a looser bound accepts it


def test_an_output_without_variance_has_zero_indices():
    unit = pce.pce_unit_design(2, 64, SEED)
    y = np.stack([np.full(64, 3.0), unit[:, 0]], axis=1)
    indices, fits = pce.pce_indices(unit, y, SEED, num_resamples=4)
    assert np.all(indices[:, 0] == 0.0)
    assert fits[0].loo_error[0] == 0.0
    assert indices[2, 1] == pytest.approx([1.0, 0.0], abs=1e-12)


AGGREGATE_TIMES = np.array([0.2, 0.7, 1.3, 2.0])


def aggregate_model(x):
    """Y_t = sin(t) x1 + t x2² + t² x1 x3 + x3 at :data:`AGGREGATE_TIMES`, x (..., 3) in
    [-1, 1]: (T, ...)."""
    t = AGGREGATE_TIMES.reshape((-1,) + (1,) * (x.ndim - 1))
    return np.sin(t) * x[..., 0] + t * x[..., 1] ** 2 + t**2 * x[..., 0] * x[..., 2] + x[..., 2]


def aggregate_by_quadrature():
    """``(first, total, variance)`` of :func:`aggregate_model` under x uniform on [-1, 1]:
    Σ_t Var E[Y_t | x_i], Σ_t E Var[Y_t | x_~i] (3,) and Var Y_t (T,), by 3-D
    Gauss-Legendre quadrature (exact: degree ≤ 4 per input)."""
    model = aggregate_model
    nodes, w = np.polynomial.legendre.leggauss(6)
    w = w / 2.0
    grid = np.stack(np.meshgrid(nodes, nodes, nodes, indexing="ij"), axis=-1)
    values = model(grid)  # (T, 6, 6, 6)
    weights = np.einsum("i,j,k->ijk", w, w, w)
    mean = np.einsum("tijk,ijk->t", values, weights)
    centred = values - mean[:, None, None, None]
    variance = np.einsum("tijk,ijk->t", centred**2, weights)
    first_num, total_num = np.zeros(3), np.zeros(3)
    for a in range(3):
        others = tuple(1 + i for i in range(3) if i != a)
        given = (values * weights).sum(axis=others) / w  # E[Y_t | x_a] (T, 6)
        first_num[a] = ((given - mean[:, None]) ** 2 @ w).sum()
        inner = np.moveaxis(values, 1 + a, -1) @ w  # E[Y_t | x_~a]
        total_num[a] = np.einsum(
            "tijk,ijk->", (values - np.expand_dims(inner, 1 + a)) ** 2, weights
        )
    return first_num, total_num, variance


def test_aggregated_indices_match_their_definition_by_quadrature():
    """S_agg,i = Σ_t Var E[Y_t | x_i] / Σ_t Var Y_t and the total analogue of
    :func:`aggregate_model`, by quadrature, against the PCE's per-time indices aggregated."""
    first_num, total_num, variance = aggregate_by_quadrature()
    unit = pce.pce_unit_design(3, 128, SEED)
    y = aggregate_model(2.0 * unit - 1.0).T  # (S, T)
    indices, (fit,) = pce.pce_indices(unit, y, SEED, shared=True, num_resamples=0)
    assert fit.variance == pytest.approx(variance, rel=1e-10)
    aggregated = aggregated_indices(indices[[0, 2]], fit.variance)
    assert aggregated[0] == pytest.approx(first_num / variance.sum(), abs=1e-10)
    assert aggregated[1] == pytest.approx(total_num / variance.sum(), abs=1e-10)
    # the definition is not the plain mean of the per-time indices
    assert np.abs(indices[2].mean(axis=0) - aggregated[1]).max() > 0.01


def test_aggregated_indices_of_outputs_without_variance_are_zero():
    assert np.all(aggregated_indices(np.ones((2, 3)), np.zeros(2)) == 0.0)
    with pytest.raises(ValueError, match="non-negative"):
        aggregated_indices(np.ones((2, 3)), np.array([1.0, -1.0]))


def test_failed_runs_are_counted_located_and_refused_unless_allowed():
    unit = pce.pce_unit_design(3, 128, SEED)
    y = unit[:, :1] + unit[:, 1:2] ** 2
    corner = (unit[:, 0] > 0.8) & (unit[:, 2] < 0.3)  # l1 high and I1 low fail
    y[corner] = np.nan
    names = ("l1", "m1", "I1")
    count = int(corner.sum())
    assert 0 < count < 20
    with pytest.raises(FailedRuns) as raised:
        check_failed_runs(y, unit, names, 0.0, can_drop=True)
    message = str(raised.value)
    assert message.startswith(f"{count} of 128 model runs failed (NaN or divergence), from ")
    assert "from l1 high, I1 low: set allow_failed_runs ≥ " in message and "\n" not in message
    needed = float(message.split("≥ ")[1].split()[0])
    assert needed >= count / 128
    with pytest.raises(FailedRuns, match="only the pce method can drop failed runs"):
        check_failed_runs(y, unit, names, 1.0, can_drop=False)
    keep, note = check_failed_runs(y, unit, names, needed, can_drop=True)
    assert np.array_equal(keep, ~corner) and note.endswith("dropped from the PCE fit")
    indices, (fit,) = pce.pce_indices(unit[keep], y[keep], SEED, num_resamples=0)
    assert np.isfinite(indices).all() and fit.loo_error[0] < 1e-8
    assert check_failed_runs(y[keep], unit[keep], names, 0.0, can_drop=False)[1] == ""
    assert failure_corner(unit, np.ones(128, bool), names) == "spread over the inputs' ranges"


def test_trajectory_indices_of_the_one_link_motion_match_quadrature_at_every_time():
    """θ(t) = τt²/(2(I + m l²/4)) at 11 times: its indices are the same at every t > 0
    (θ(t) ∝ t²), equal to the quadrature's, and so are their aggregates; t = 0 does not vary.
    The second output, 2θ(t) (another unit scale), gives the same; ``overall`` is their mean."""
    unit = pce.pce_unit_design(2, pce.default_pce_samples(2), SEED)
    x = 2.0 * unit - 1.0
    theta_end = theta_closed_form(L0 + DL * x[:, 0], M0 + DM * x[:, 1], CASES["l-m"][0])
    times = np.linspace(0.0, 1.0, 11)
    theta = theta_end[:, None] * times[None, :] ** 2
    outputs = np.stack([theta, 2.0 * theta], axis=2)  # (S, K, M)
    result = pce_analysis.trajectory_indices(unit, outputs, SEED, num_resamples=10)
    _, variance, _, first, total = exact_moments(*CASES["l-m"])
    exact = np.array([first, total]) / variance  # (2, D)
    assert np.all(result.indices[:, 0] == 0.0) and np.all(result.variance[0] == 0.0)
    for index, row in ((0, 0), (2, 1)):
        assert np.abs(result.indices[index, 1:] - exact[row]).max() <= 0.01
    assert np.abs(result.aggregated - exact[None]).max() <= 0.01
    assert result.overall == pytest.approx(result.aggregated.mean(axis=0))
    assert result.variance[1:, 1] == pytest.approx(4 * result.variance[1:, 0], rel=1e-9)
    assert result.loo_error.max() < 1e-3


def test_job_indices_check_failed_runs_and_the_loo_error():
    unit = pce.pce_unit_design(2, 128, SEED)
    y = np.stack([unit[:, 0] + 2 * unit[:, 1], unit[:, 0] * unit[:, 1]], axis=1)
    indices, loo, note = pce_analysis.job_indices(
        unit, y, SEED, ("l1", "m1"), ("tau1", "tau2"), 0.01
    )
    assert note == "" and loo.max() < 1e-20
    assert indices[2, 0] == pytest.approx([0.2, 0.8], abs=1e-12)
    y[:3] = np.inf
    with pytest.raises(FailedRuns) as raised:
        pce_analysis.job_indices(unit, y, SEED, ("l1", "m1"), ("tau1", "tau2"), 0.01)
    assert raised.value.key == "allow_failed_runs"
    _, _, note = pce_analysis.job_indices(unit, y, SEED, ("l1", "m1"), ("tau1", "tau2"), 0.01, 0.05)
    assert note.startswith("3 of 128 model runs failed")
    y[:, 0] = unit[:, 0] + 2 * unit[:, 1]
    y[:, 1] = np.where(unit[:, 0] > 0.5, 1.0, 0.0)  # a step: no polynomial fits it
    with pytest.raises(pce.PceError) as raised:
        pce_analysis.job_indices(unit, y, SEED, ("l1", "m1"), ("tau1", "tau2"), 0.01)
    assert raised.value.key == "pce_samples" and "of tau2 exceeds" in raised.value.problem

"""The PCE's corrected leave-one-out error and the model it selects, against a direct
computation: on a small design each point is left out in turn, the chosen terms refitted
on the others by ``numpy.linalg.lstsq`` and the point predicted (no hat matrix, no QR of
the OMP); the correction factor T(k, N) = N / (N - k) (1 + tr((Ψᵀ Ψ)⁻¹)) from
``numpy.linalg.inv`` (Blatman & Sudret 2011, eq. 17; Chapelle et al. 2002)."""

from __future__ import annotations

import numpy as np
import pytest

from planar_tui.sensitivity import pce

SEED = 42


def direct_loo(psi_terms: np.ndarray, y: np.ndarray) -> float:
    """Corrected relative LOO error of the least-squares fit of ``y`` (S,) on the columns
    ``psi_terms`` (S, k), by S refits each leaving one point out."""
    s_rows, k = psi_terms.shape
    errors = np.empty(s_rows)
    for i in range(s_rows):
        keep = np.arange(s_rows) != i
        c, *_ = np.linalg.lstsq(psi_terms[keep], y[keep], rcond=None)
        errors[i] = y[i] - psi_terms[i] @ c
    correction = s_rows / (s_rows - k) * (1.0 + np.trace(np.linalg.inv(psi_terms.T @ psi_terms)))
    return correction * (errors @ errors) / ((y - y.mean()) @ (y - y.mean()))


def design():
    unit = pce.pce_unit_design(2, 40, SEED)
    smooth = np.exp(unit[:, 0]) * np.sin(3.0 * unit[:, 1])
    kink = np.abs(unit[:, 0] - 0.4) + 0.3 * unit[:, 1]
    return unit, np.stack([smooth, kink], axis=1)


def test_the_corrected_loo_error_and_coefficients_equal_direct_refits():
    unit, y = design()
    psi = pce.basis_matrix(unit, pce.total_degree_indices(2, 4))
    path = pce.omp_path(psi, y)
    assert path.term_counts.min() >= 3 and path.term_counts.max() < 20
    for t in range(2):
        k = path.term_counts[t]
        chosen = psi[:, path.terms[:k]]
        assert path.loo_error[t] == pytest.approx(direct_loo(chosen, y[:, t]), rel=1e-9)
        c, *_ = np.linalg.lstsq(chosen, y[:, t], rcond=None)
        np.testing.assert_allclose(path.coefficients[:k, t], c, rtol=0, atol=1e-10)


def test_each_output_keeps_the_prefix_with_the_least_direct_loo_error():
    """Every prefix of the path (up to the longest kept) by direct refits: the output
    with fewer terms keeps the least of them, the other the least up to its own."""
    unit, y = design()
    psi = pce.basis_matrix(unit, pce.total_degree_indices(2, 4))
    path = pce.omp_path(psi, y)
    assert path.term_counts[0] != path.term_counts[1]
    for t in range(2):
        errors = [
            direct_loo(psi[:, path.terms[:k]], y[:, t]) for k in range(1, len(path.terms) + 1)
        ]
        k = path.term_counts[t]
        assert int(np.argmin(errors[:k])) + 1 == k
        assert errors[k - 1] <= min(errors)


def test_fit_pce_selects_the_degree_and_exactly_the_terms_of_a_sparse_cubic():
    """A cubic with three non-constant terms: degrees 1 and 2 leave an error, degree 3
    fits it exactly (LOO below ENOUGH_LOO), so the fit stops there with its four terms."""
    unit = pce.pce_unit_design(3, 128, SEED)
    wanted = {(0, 0, 0): 0.5, (3, 0, 0): 1.0, (1, 2, 0): -0.8, (0, 0, 1): 0.3}
    indices = np.array(list(wanted))
    y = pce.basis_matrix(unit, indices) @ np.array(list(wanted.values()))
    degrees: list[int] = []
    fit = pce.fit_pce(unit, y, on_degree=degrees.append)
    assert degrees == [1, 2, 3] and fit.degree == 3
    got = dict(zip(map(tuple, fit.indices.tolist()), fit.coefficients[:, 0], strict=True))
    assert set(got) == set(wanted)
    assert all(got[key] == pytest.approx(value, abs=1e-12) for key, value in wanted.items())
    assert fit.loo_error[0] <= pce.ENOUGH_LOO


def test_an_output_whose_loo_error_is_never_finite_refuses_the_fit():
    """Its squares overflow, so no prefix of the path has a finite LOO error for it: the
    fit is refused rather than the output given no terms, even when another output fits."""
    unit, y = design()
    psi = pce.basis_matrix(unit, pce.total_degree_indices(2, 2))
    huge = np.stack([y[:, 0], 1e300 * y[:, 1]], axis=1)
    with (
        np.errstate(over="ignore", invalid="ignore"),
        pytest.raises(pce.PceError, match="cannot fit"),
    ):
        pce.omp_path(psi, huge)
    assert pce.omp_path(psi, y[:, :1]).term_counts[0] >= 1  # the other alone: fitted


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_fit_pce_keeps_the_degree_of_least_loo_and_stops_two_degrees_after_it(seed):
    """Noise (no degree fits it): each degree's LOO error is its own OMP path's (checked
    against direct refits above); the fit keeps the first degree of least error and tries
    exactly two more after it (the rule of :func:`fit_pce`'s docstring)."""
    unit = pce.pce_unit_design(2, 64, SEED)
    y = np.random.default_rng(seed).normal(size=64)
    tried: list[int] = []
    fit = pce.fit_pce(unit, y, on_degree=tried.append)
    errors = [
        float(
            pce.omp_path(
                pce.basis_matrix(unit, pce.total_degree_indices(2, p)), y[:, None]
            ).loo_error[0]
        )
        for p in tried
    ]
    best = int(np.argmin(errors))
    assert tried == list(range(1, best + 4))
    assert fit.degree == best + 1
    assert fit.loo_error[0] == errors[best]


def test_fit_pce_reaches_degree_eight_when_every_degree_improves():
    """One input, y = Σ_{p=0}^{8} ψ_p / (p + 1): each degree p < 8 leaves the terms above
    it (the LOO error falls degree by degree), degree 8 (``MAX_DEGREE``) fits it exactly.
    The fit tries every degree up to 8 and recovers the nine coefficients."""
    assert pce.MAX_DEGREE == 8
    unit = pce.pce_unit_design(1, 64, SEED)
    indices = np.arange(9)[:, None]
    wanted = 1.0 / np.arange(1, 10)
    y = pce.basis_matrix(unit, indices) @ wanted
    tried: list[int] = []
    fit = pce.fit_pce(unit, y, on_degree=tried.append)
    assert tried == list(range(1, 9)) and fit.degree == 8
    got = dict(zip(fit.indices[:, 0].tolist(), fit.coefficients[:, 0], strict=True))
    assert sorted(got) == list(range(9))
    np.testing.assert_allclose([got[p] for p in range(9)], wanted, rtol=0, atol=1e-10)


def test_second_order_indices_of_several_outputs_by_hand():
    """Three outputs on six terms of three inputs: S_ij = c_ij² / Σ_{α≠0} c_α² (the
    terms of exactly inputs {i, j}; a term of all three inputs counts in the variance
    only), symmetric, zero diagonal; an output without variance gets zeros."""
    indices = np.array([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 2, 1), (0, 0, 1), (1, 1, 1)])
    coefficients = np.array(
        [[5.0, 1.0, 2.0, 3.0, 1.0, 1.0], [0.0, 2.0, 0.0, 1.0, 0.0, 0.0], [7.0, 0, 0, 0, 0, 0]]
    ).T
    expected = np.zeros((3, 3, 3))
    expected[0, 0, 1] = expected[0, 1, 0] = 4.0 / 16.0
    expected[0, 1, 2] = expected[0, 2, 1] = 9.0 / 16.0
    expected[1, 1, 2] = expected[1, 2, 1] = 1.0 / 5.0
    got = pce.second_order_indices(indices, coefficients)
    assert got.shape == (3, 3, 3)
    np.testing.assert_allclose(got, expected, rtol=1e-15, atol=0)


def test_fit_pce_stops_at_degree_eight_while_the_error_still_falls():
    """The same with a ψ_9 term: degree 8 still improves on 7 but leaves ψ_9; no degree
    above ``MAX_DEGREE`` is tried."""
    unit = pce.pce_unit_design(1, 64, SEED)
    y = pce.basis_matrix(unit, np.arange(10)[:, None]) @ (1.0 / np.arange(1, 11))
    tried: list[int] = []
    fit = pce.fit_pce(unit, y, on_degree=tried.append)
    assert tried == list(range(1, 9)) and fit.degree == 8
    assert fit.loo_error[0] > pce.ENOUGH_LOO


def test_the_path_stops_once_the_loo_error_is_below_enough_loo():
    """y = 1 + ψ_(1,0) + 1e-5 ψ_(0,2): after the constant and ψ_(1,0) the relative LOO
    error is about 1e-10 (the left-out term's share), below ``ENOUGH_LOO``: the output
    counts as fitted and the path stops there, without the 1e-5 term."""
    unit, _ = design()
    indices = pce.total_degree_indices(2, 3)
    psi = pce.basis_matrix(unit, indices)
    position = {key: i for i, key in enumerate(map(tuple, indices.tolist()))}
    y = 1.0 + psi[:, position[(1, 0)]] + 1e-5 * psi[:, position[(0, 2)]]
    path = pce.omp_path(psi, y[:, None])
    assert path.terms.tolist() == [position[(0, 0)], position[(1, 0)]]
    assert path.term_counts.tolist() == [2]
    loo = direct_loo(psi[:, path.terms], y)
    assert 1e-12 < loo <= pce.ENOUGH_LOO
    assert path.loo_error[0] == pytest.approx(loo, rel=1e-6)

"""The jitted Sobol' kernel (kernels/sensitivity_estimators.py) on outputs where each of
its guards matters, against SALib (``tests/salib_reference.py``) on the same samples:
an output whose A and B values are all equal (its half-widths are 0, as SALib's ``np.ptp``
test makes them), and one whose A and B values differ only at a row that some bootstrap
resample draws but the last one does not (the rows drawn by *any* resample count)."""

import numpy as np
import pytest

from planar_tui.sensitivity.estimators import sobol_bootstrap_rows, sobol_indices
from tests.salib_reference import salib_sobol_indices

D = 2
N = 8
STEP = D + 2
SEED = 5
PROBLEM = {"num_vars": D, "names": ["a", "b"], "bounds": [[0.0, 1.0]] * D}


def ab_rows_varying(rng):
    """N (D + 2) outputs, 0 at every A and B row, 1000 + N(0, 1) at the A_B rows.

    Standardised, the A and B values are all about -1: a resample's variance of them,
    mean of squares less the squared mean, is then a rounding error of about 1e-15, above
    the kernel's ``eps`` guard, so only the ``np.ptp`` test keeps the half-widths at 0."""
    outputs = np.zeros((N * STEP, 1))
    for k in range(N):
        outputs[k * STEP + 1 : k * STEP + 1 + D, 0] = 1000.0 + rng.normal(size=D)
    return outputs


@pytest.mark.filterwarnings("ignore:Constant values encountered")  # SALib's, expected
def test_equal_a_and_b_values_give_zero_half_widths_as_salib():
    outputs = ab_rows_varying(np.random.default_rng(3))
    ours = sobol_indices(outputs, D, SEED)
    assert np.array_equal(ours, salib_sobol_indices(PROBLEM, outputs, SEED))
    assert np.all(ours[[1, 3]] == 0.0)


def test_a_row_drawn_by_an_earlier_resample_only_still_makes_the_output_vary():
    rows = sobol_bootstrap_rows(N, SEED)
    drawn_last = set(rows[-1].tolist())
    (k, *_) = [k for k in range(N) if k not in drawn_last]
    assert any(k in resample for resample in rows[:-1].tolist())
    outputs = ab_rows_varying(np.random.default_rng(3))
    outputs[k * STEP, 0] = 1.0  # A of row k: the only A or B value that differs
    ours = sobol_indices(outputs, D, SEED)
    np.testing.assert_allclose(ours, salib_sobol_indices(PROBLEM, outputs, SEED), atol=1e-12)
    assert np.all(ours[[1, 3]] > 0.1)


def test_resamples_in_chunks_give_the_same_bytes_as_one_pass(monkeypatch):
    """``sobol_indices``' promise: chunks of resamples (here 3 a kernel call, forced by a
    small ``SUMS_PER_CALL``) change nothing but the ``on_chunk`` reports, which add to 1."""
    from planar_tui.kernels import sensitivity_estimators as kernel

    outputs = np.random.default_rng(4).normal(size=(N * STEP, 2))
    one_pass = sobol_indices(outputs, D, SEED)
    terms_per_resample = N * (2 * D + 4)  # one output column at a time
    monkeypatch.setattr(kernel, "SUMS_PER_CALL", 3 * terms_per_resample)
    fractions: list[float] = []
    chunked = sobol_indices(outputs, D, SEED, on_chunk=fractions.append)
    assert np.array_equal(chunked, one_pass)
    resamples = len(sobol_bootstrap_rows(N, SEED))
    assert len(fractions) == 2 * -(-resamples // 3)
    assert sum(fractions) == pytest.approx(1.0, rel=1e-12)


@pytest.mark.parametrize("sums_per_call", [None, 3 * N * (2 * D + 4) * 100])
def test_columns_in_blocks_equal_each_column_alone(monkeypatch, sums_per_call):
    """Output columns analysed in blocks (all of them in one kernel call, or blocks of 3
    columns forced by a small ``SUMS_PER_CALL``) give each column's indices and
    half-widths as that column analysed alone, to round-off; the ``on_chunk`` reports
    still add to 1."""
    from planar_tui.kernels import sensitivity_estimators as kernel

    rng = np.random.default_rng(6)
    outputs = rng.normal(size=(N * STEP, 8)) * rng.uniform(0.1, 10.0, size=8)
    outputs[:, 2] = 3.0  # an output without variance: indices and half-widths 0 as alone
    alone = np.concatenate(
        [sobol_indices(outputs[:, t : t + 1], D, SEED) for t in range(8)], axis=1
    )
    if sums_per_call is not None:
        monkeypatch.setattr(kernel, "SUMS_PER_CALL", sums_per_call)
    fractions: list[float] = []
    blocks = sobol_indices(outputs, D, SEED, on_chunk=fractions.append)
    np.testing.assert_allclose(blocks, alone, rtol=1e-13, atol=1e-15)
    assert len(fractions) == (1 if sums_per_call is None else 3)
    assert sum(fractions) == pytest.approx(1.0, rel=1e-12)

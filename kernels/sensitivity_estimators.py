r"""Jitted Sobol' first-order and total indices with bootstrap confidence half-widths.

These are the estimators of ``SALib.analyze.sobol`` (Saltelli et al. 2010, the defaults of
SALib >= 1.4), rewritten so the bootstrap, 99 % of SALib's analysis time, no longer
dominates. SALib stays the reference: ``tests/`` checks that the point estimates equal
SALib's on the same samples to 1e-12 and, given SALib's bootstrap index matrix, that the
confidence half-widths do too.

With the model outputs of a Saltelli design without second order (rows in blocks of
``D + 2``: :math:`A`, :math:`A_B^{(1)} \dots A_B^{(D)}`, :math:`B`), first standardised as
:math:`y \leftarrow (y - \bar y)/\sigma_y` over all rows (as SALib does),

.. math::
    S_j = \frac{\tfrac1N\sum_k B_k\,(A_{B,k}^{(j)} - A_k)}{\operatorname{Var}[A \cup B]},
    \qquad
    S_{Tj} = \frac{\tfrac1{2N}\sum_k (A_k - A_{B,k}^{(j)})^2}{\operatorname{Var}[A \cup B]},

(paper A eqs. 18 and 34 estimated by Monte Carlo), the population variance taken over the
2N values of A and B. The bootstrap recomputes both on the rows ``r[:, b]`` of resample b
and reports :math:`z_{(1+c)/2}\,\mathrm{sd}_b` (``ddof = 1``).

**Bootstrap as one matrix product.** Every bootstrap sum is :math:`\sum_k c_{bk} g_k` with
:math:`c_{bk}` the number of times row k is drawn in resample b and :math:`g_k` a per-row
term: :math:`A_k, B_k, A_k^2, B_k^2, B_k(A_{B,k}^{(j)} - A_k), (A_k - A_{B,k}^{(j)})^2`. So the
R resamples of an output are ``counts (R, N) @ terms (N, 2D + 4)``: a dense product
streaming each term row once per group of resamples, SIMD over the terms, instead of
R N (D + 2) random gathers (4× faster here; not numpy's BLAS, whose threads stall
on a busy 2-core machine); each resample's variance is then
:math:`\overline{y^2} - \bar y^2` over its 2N values of A and B (standardised, so no
cancellation). The point estimates keep the two-pass variance of SALib.
"""

import numpy as np
from numba import prange

from ._jit import kernel

_EPS = np.finfo(np.float64).eps
#: Per-row terms before the 2D input terms: A, B, A², B².
_LEAD = 4
#: Resamples summed together in one pass over the term rows.
_GROUP = 10


@kernel
def _standardise_into(outputs, t, out):
    """``out[q] = (y_q - mean y) / sd y`` of column t (population sd, two-pass, as SALib).

    Only the centring changes the indices: S1 and ST (and each resample's) are ratios of
    sums homogeneous of degree 2 in y, so the scale cancels and the sd normalised by
    N - 1 instead would change them by round-off only; N is kept to be SALib's."""
    rows_total = outputs.shape[0]
    mean = 0.0
    for q in range(rows_total):
        mean += outputs[q, t]
    mean /= rows_total
    acc = 0.0
    for q in range(rows_total):
        d = outputs[q, t] - mean
        acc += d * d
    sd = np.sqrt(acc / rows_total)
    for q in range(rows_total):
        out[q] = (outputs[q, t] - mean) / sd


@kernel
def _sample_sums(y, step, first, total):
    """One pass over the N row blocks ``[A, A_B^1 … A_B^D, B]`` of standardised outputs y.

    Accumulates the Saltelli-2010 numerators ``first[j] = Σ B (A_B^j - A)`` and
    ``total[j] = Σ (A - A_B^j)²`` for every input j in place and returns the population
    variance of the 2N values of A and B (two-pass, as ``np.var``).
    """
    n = y.shape[0] // step
    num_vars = step - 2
    total_ab = 0.0
    for k in range(n):
        total_ab += y[k * step] + y[k * step + step - 1]
    mean = total_ab / (2 * n)
    for j in range(num_vars):
        first[j] = 0.0
        total[j] = 0.0
    acc = 0.0
    for k in range(n):
        base = k * step
        a = y[base]
        b = y[base + step - 1]
        acc += (a - mean) * (a - mean) + (b - mean) * (b - mean)
        for j in range(num_vars):
            ab = y[base + 1 + j]
            first[j] += b * (ab - a)
            total[j] += (a - ab) * (a - ab)
    return acc / (2 * n)


@kernel
def _ratio(numerator, n, variance, scale):
    """``scale × numerator / n / variance`` (``scale`` 1 for S1, ½ for ST), 0 when the
    variance is <= eps. ``scale`` is a float, not a bool: a literal ``True``/``False``
    argument made numba compile this twice (``1.0 × x`` is ``x`` exactly)."""
    if variance <= _EPS:
        return 0.0
    return scale * (numerator / n / variance)


@kernel(parallel=True)
def sobol_point_and_terms(outputs, num_vars):
    r"""Point estimates and per-row bootstrap terms of every output column.

    Parameters
    ----------
    outputs : (N (D + 2), n_out) float64
        Model outputs of a Saltelli/Sobol' design with ``calc_second_order=False``.
    num_vars : int
        D, the number of inputs.

    Returns
    -------
    point : (2, n_out, D) float64
        S1 and ST.
    terms : (n_out, N, 2 D + 4) float64
        The per-row terms g of the standardised outputs: A, B, A², B², then
        B (A_B^j - A) and (A - A_B^j)² for j = 1 … D.
    """
    rows_total, n_out = outputs.shape
    step = num_vars + 2
    n_base = rows_total // step
    n_terms = 2 * num_vars + _LEAD
    standard = np.empty((n_out, rows_total))
    first = np.empty((n_out, num_vars))
    total = np.empty((n_out, num_vars))
    point = np.zeros((2, n_out, num_vars))
    for t in prange(n_out):
        # int64 as in sobol_point (a prange index is uint64: a second compilation)
        _standardise_into(outputs, np.int64(t), standard[t])
        variance = _sample_sums(standard[t], step, first[t], total[t])
        for j in range(num_vars):
            point[0, t, j] = _ratio(first[t, j], n_base, variance, 1.0)
            point[1, t, j] = _ratio(total[t, j], n_base, variance, 0.5)
    terms = np.empty((n_out, n_base, n_terms))  # per output: (N, 2D + 4), cache-sized
    for k in prange(n_base):
        base = k * step
        for t in range(n_out):
            a = standard[t, base]
            b = standard[t, base + step - 1]
            row = terms[t, k]
            row[0] = a
            row[1] = b
            row[2] = a * a
            row[3] = b * b
            for j in range(num_vars):
                ab = standard[t, base + 1 + j]
                row[_LEAD + j] = b * (ab - a)
                row[_LEAD + num_vars + j] = (a - ab) * (a - ab)
    return point, terms


@kernel
def sobol_point(outputs, num_vars):
    """S1 and ST (2, n_out, D) of every output column: the point estimates of
    :func:`sobol_point_and_terms` without its bootstrap terms, serial (for many small
    calls, one per recorded time, where starting threads costs more than the sums)."""
    rows_total, n_out = outputs.shape
    step = num_vars + 2
    n_base = rows_total // step
    standard = np.empty(rows_total)
    first = np.empty(num_vars)
    total = np.empty(num_vars)
    point = np.zeros((2, n_out, num_vars))
    for t in range(n_out):
        _standardise_into(outputs, t, standard)
        variance = _sample_sums(standard, step, first, total)
        for j in range(num_vars):
            point[0, t, j] = _ratio(first[j], n_base, variance, 1.0)
            point[1, t, j] = _ratio(total[j], n_base, variance, 0.5)
    return point


@kernel(parallel=True)
def bootstrap_sums(terms, counts):
    r"""``sums[t, b] = counts[b] @ terms[t]``: :math:`\sum_k c_{bk} g_k` for the resamples
    of ``counts`` (R', N) (any subset of rows of the full counts: each resample's sum is
    independent of the others).

    Tasks of ``_GROUP`` resamples per output, so each term row is read once per group;
    branch-free multiply-adds over the contiguous terms. Returns (n_out, R', 2 D + 4)."""
    n_out, n_base, n_terms = terms.shape
    n_res = counts.shape[0]
    sums = np.zeros((n_out, n_res, n_terms))
    n_groups = (n_res + _GROUP - 1) // _GROUP
    for task in prange(n_out * n_groups):
        t = task // n_groups
        b0 = (task % n_groups) * _GROUP
        b1 = min(n_res, b0 + _GROUP)
        acc = sums[t]
        for k in range(n_base):
            row = terms[t, k]
            for b in range(b0, b1):
                c = counts[b, k]
                for f in range(n_terms):
                    acc[b, f] += c * row[f]
    return sums


@kernel
def varying_outputs(terms, counts):
    """Whether the A and B values of the rows drawn at least once by ``counts`` (R, N) are
    not all equal, per output (SALib's ``np.ptp != 0`` test; half-widths are 0 otherwise)."""
    n_out, n_base = terms.shape[0], terms.shape[1]
    drawn = np.zeros(n_base, dtype=np.bool_)
    for b in range(counts.shape[0]):
        for k in range(n_base):
            drawn[k] = drawn[k] or counts[b, k] != 0.0
    varying = np.zeros(n_out, dtype=np.bool_)
    for t in range(n_out):
        lo = np.inf
        hi = -np.inf
        for k in range(n_base):
            if drawn[k]:
                lo = min(lo, terms[t, k, 0], terms[t, k, 1])
                hi = max(hi, terms[t, k, 0], terms[t, k, 1])
        varying[t] = hi - lo != 0.0
    return varying


def resample_counts(resample_rows: np.ndarray, n_base: int) -> np.ndarray:
    """(R, N) float64: how many times resample b draws row k, from (R, N) row indices."""
    n_res = resample_rows.shape[0]
    flat = resample_rows + n_base * np.arange(n_res)[:, None]
    return np.bincount(flat.ravel(), minlength=n_res * n_base).reshape(n_res, n_base) * 1.0


#: Multiply-adds of bootstrap sums per kernel call of :func:`sobol_first_total` (~20 ms).
SUMS_PER_CALL = 1 << 25


def sobol_first_total(outputs, num_vars, counts, z_value, on_chunk=None):
    r"""Sobol' S1, ST and their bootstrap half-widths for every output column.

    ``outputs`` and ``num_vars`` as in :func:`sobol_point_and_terms`; ``counts`` (R, N)
    float64, how many times resample b draws row k (:func:`resample_counts` of SALib's
    bootstrap rows ``default_rng(seed).integers(N, size=(N, R))``, transposed); ``z_value``
    is :math:`z_{(1+c)/2}` of the confidence level c. The bootstrap sums are taken in
    calls of about ``SUMS_PER_CALL`` multiply-adds (a subset of the resamples each);
    ``on_chunk(fraction)`` runs after each.

    Returns
    -------
    indices : (4, n_out, D) float64
        S1, S1 half-width, ST, ST half-width.
    """
    outputs = np.ascontiguousarray(outputs, dtype=np.float64)
    n_base = outputs.shape[0] // (num_vars + 2)
    point, terms = sobol_point_and_terms(outputs, num_vars)
    n_res = counts.shape[0]
    per_resample = max(1, terms.size)
    step = max(1, min(n_res, SUMS_PER_CALL // per_resample))
    sums = np.empty((terms.shape[0], n_res, terms.shape[2]))
    for b0 in range(0, n_res, step):
        b1 = min(n_res, b0 + step)
        sums[:, b0:b1] = bootstrap_sums(terms, counts[b0:b1])
        if on_chunk is not None:
            on_chunk((b1 - b0) / n_res)
    varying = varying_outputs(terms, counts)
    del terms
    sums = sums.transpose(1, 0, 2)  # (R, n_out, 2D + 4)
    mean = (sums[..., 0] + sums[..., 1]) / (2 * n_base)
    variance = (sums[..., 2] + sums[..., 3]) / (2 * n_base) - mean * mean
    shape = (*variance.shape, num_vars)
    ok = np.broadcast_to((variance > _EPS)[..., None], shape)
    denominator = np.broadcast_to(variance[..., None], shape)
    first = np.zeros(shape)
    total = np.zeros(shape)
    np.divide(sums[..., _LEAD : _LEAD + num_vars] / n_base, denominator, out=first, where=ok)
    np.divide(sums[..., _LEAD + num_vars :] / n_base, denominator, out=total, where=ok)
    total *= 0.5
    result = np.zeros((4, outputs.shape[1], num_vars))
    result[0], result[2] = point
    if counts.shape[0] > 1:
        varying = varying[:, None]
        result[1] = np.where(varying, z_value * first.std(axis=0, ddof=1), 0.0)
        result[3] = np.where(varying, z_value * total.std(axis=0, ddof=1), 0.0)
    return result

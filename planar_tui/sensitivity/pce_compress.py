r"""Many outputs of one design on a few principal components, for the PCE: a path's every
effort at every step (thousands of columns, smooth in time) spans a handful of directions.

With :math:`\mu` the outputs' means and :math:`D = \mathrm{diag}(\|y_t - \mu_t\|)` their
spreads, the scaled centred outputs :math:`X = (Y - 1\mu^T)D^{-1}` (S, T) are written

.. math:: Y = 1\mu^T + Z L^T + E,\qquad Z = U_r\ (S, r),\quad L = D X^T U_r\ (T, r),

:math:`U_r` the leading eigenvectors of :math:`XX^T` (orthonormal columns), r the fewest
for which every output keeps all but ``tolerance`` of its own variance,
:math:`\|E_t\|^2 \le \varepsilon \|y_t - \mu_t\|^2` (checked on the residual itself).
Every least-squares quantity of the regression is then linear in the columns of Z: an
output's coefficients on a set of terms are :math:`c_t = R^{-1}Q^T(1\mu_t + Z L_t^T)`, its
residual :math:`(I - QQ^T)Z L_t^T`, its summed squared leave-one-out residuals
:math:`L_t G L_t^T` with :math:`G = \tilde Z^T\tilde Z`, :math:`\tilde Z` the residuals of
Z divided row-wise by :math:`1 - h_i`; the OMP's score of a column
:math:`\sum_t w_t (\psi_j^T r_t)^2 = a_j^T (L^T W L) a_j` with :math:`a_j = \psi_j^T(I -
QQ^T)Z`. So :func:`~planar_tui.sensitivity.pce.omp_path` runs on r columns instead of T and
reproduces, output by output, the fit of the T columns (each its own number of terms and
LOO error) up to the discarded variance; Sobol' indices, quadratic in an output's
coefficients, follow from them exactly (:func:`bootstrap_compressed` for the half-widths).
"""

from __future__ import annotations

from dataclasses import dataclass
from statistics import NormalDist

import numpy as np

from planar_tui.sensitivity.pce_indices import indices_from_coefficients

#: Variance an output may lose to the compression, relative to its own: an amplitude of
#: 1e-10, which moves a LOO error ε by about 2 (ε 1e-20)^½ (a torque's rounding is ~1e-13).
TOLERANCE = 1e-20
#: Eigenvalues a pass keeps, relative to its largest; passes at most.
PASS_RATIO = 1e-8
MAX_PASSES = 6
#: Fewer outputs than this are fitted as they are (nothing to gain).
MIN_OUTPUTS = 64
#: Outputs per block of the bootstrap's (outputs, terms, resamples) arrays (memory).
BLOCK_OUTPUTS = 256


@dataclass(frozen=True)
class Compressed:
    """Outputs (S, T) as ``mean`` (T,) + ``scores`` (S, r, orthonormal columns) @
    ``loadings`` (T, r)ᵀ."""

    mean: np.ndarray
    scores: np.ndarray
    loadings: np.ndarray

    @property
    def spread(self) -> np.ndarray:
        """Σ_s (y_st − μ_t)² of every output (the scores are orthonormal)."""
        return np.einsum("tr,tr->t", self.loadings, self.loadings)


def compress(y: np.ndarray, tolerance: float = TOLERANCE) -> Compressed | None:
    """The compression of ``y`` (S, T) (module doc), or ``None`` where it would not pay:
    fewer than :data:`MIN_OUTPUTS` outputs, non-finite values, nothing varying, or more
    than min(S, T) / 4 components needed. The components come in passes: the eigenvectors
    of the residual's :math:`XX^T` down to ``PASS_RATIO`` of its largest eigenvalue (those
    it resolves), then the same on what they leave (a Gram matrix alone stops at
    √ε of the leading amplitude), until every output's residual is within ``tolerance``."""
    s_rows, t_out = y.shape
    if t_out < MIN_OUTPUTS or not np.isfinite(y).all():
        return None
    mean = y.mean(axis=0)
    centred = y - mean
    norms = np.sqrt(np.einsum("st,st->t", centred, centred))
    varies = norms > 0.0
    if not varies.any():
        return None
    scaled = centred[:, varies] / norms[varies]
    limit = max(1, min(s_rows, t_out) // 4)
    scores = np.empty((s_rows, 0))
    residual = scaled
    for _ in range(MAX_PASSES):
        values, vectors = np.linalg.eigh(residual @ residual.T)
        found = vectors[:, values >= PASS_RATIO * values[-1]]
        for _ in range(2):  # orthogonal to the components found before
            found = found - scores @ (scores.T @ found)
            found = np.linalg.qr(found)[0]
        scores = np.hstack([scores, found])
        if scores.shape[1] > limit:
            return None
        residual = scaled - scores @ (scores.T @ scaled)
        if np.einsum("st,st->t", residual, residual).max() <= tolerance:
            loadings = np.zeros((t_out, scores.shape[1]))
            loadings[varies] = (scores.T @ scaled * norms[varies]).T
            return Compressed(mean, scores, loadings)
    return None


def leave_out_sums(residual, hat, loadings) -> np.ndarray:
    """Σ_s (r_st / (1 − h_s))² of every output from the residuals of the scores."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        scaled = residual / (1.0 - hat)[:, None]
        gram = scaled.T @ scaled
        return ((loadings @ gram) * loadings).sum(axis=1)


def mixing(loadings, weight) -> np.ndarray:
    """:math:`L^T W L` (r, r): Σ_t w_t (ψ_j^T r_t)² of a column is :math:`a_j^T (L^T W L)
    a_j`, a_j its correlations with the scores' residuals."""
    return loadings.T @ (loadings * weight[:, None])


def bootstrap_compressed(fit, compressed: Compressed, seed: int, num_resamples: int, conf_level):
    r"""``z σ`` of S1 and ST (each (T, D)) over the wild bootstrap of
    :func:`~planar_tui.sensitivity.pce.bootstrap_halfwidths` (the same Rademacher signs
    :math:`v_b`), output t refitted on its own first :math:`k_t` terms: its shift
    :math:`R_k^{-1}Q_k^T(e_t \odot v_b)` with :math:`e_t = E^{(k)} L_t^T`,
    :math:`E^{(k)} = (I - Q_kQ_k^T)Z`, is :math:`\Delta^{(k)} L_t^T`,
    :math:`\Delta^{(k)} = R_k^{-1}W^{(k)}`, where
    :math:`W^{(k)}_{jib} = \sum_s Q_{sj}E^{(k)}_{si}v_{sb}` is updated term by term
    (:math:`E^{(k)} = E^{(k-1)} - q_k (q_k^T Z)`)."""

    q, scores, loadings = fit.q, compressed.scores, compressed.loadings
    s_rows, k_terms = q.shape
    rank = scores.shape[1]
    signs = np.random.default_rng(seed).integers(0, 2, size=(s_rows, num_resamples)) * 2.0 - 1.0
    t_out = loadings.shape[0]
    first_sd = np.zeros((t_out, fit.indices.shape[1]))
    total_sd = np.zeros_like(first_sd)
    # W^(0)_{jib} = Σ_s Q_sj Z_si v_sb, then the terms' updates
    w = np.stack([(q * scores[:, i, None]).T @ signs for i in range(rank)], axis=1)
    on_terms = q.T @ scores  # (k, r): q_kᵀ Z
    for k in range(1, k_terms + 1):
        w -= ((q * q[:, k - 1, None]).T @ signs)[:, None, :] * on_terms[k - 1][None, :, None]
        outputs = np.flatnonzero(fit.term_counts == k)
        if not len(outputs):
            continue
        delta = (fit.r_inv[:k, :k] @ w[:k].reshape(k, -1)).reshape(k, rank, num_resamples)
        for start in range(0, len(outputs), BLOCK_OUTPUTS):
            block = outputs[start : start + BLOCK_OUTPUTS]
            shift = np.tensordot(delta, loadings[block], axes=([1], [1]))  # (k, B, T_block)
            shift = shift.transpose(1, 0, 2)
            coefficients = fit.coefficients[None, :k, block] + shift
            first, total = indices_from_coefficients(fit.indices[:k], coefficients)
            first_sd[block] = first.std(axis=0, ddof=1)
            total_sd[block] = total.std(axis=0, ddof=1)
    z = NormalDist().inv_cdf(0.5 + conf_level / 2.0)
    return z * first_sd, z * total_sd

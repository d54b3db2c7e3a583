r"""Aggregated Sobol' indices of a vector output (a trajectory, several torques).

The generalised indices of Gamboa, Janon, Klein & Lagnoux (2014) for an output
:math:`Y = (Y_1, \dots, Y_T)` weight each component's index by its variance:

.. math:: S^{agg}_i = \frac{\mathrm{tr}\,\mathrm{Cov}(E[Y \mid X_i])}{\mathrm{tr}\,\mathrm{Cov}(Y)}
          = \frac{\sum_t \mathrm{Var}(Y_t)\, S_{i}(Y_t)}{\sum_t \mathrm{Var}(Y_t)},

and the same weighting of the total indices :math:`S_{T,i}(Y_t)`. Components without
variance weigh nothing; an output none of whose components varies has zero indices.
Components should share a unit (one joint's angle at every time; torques in N m): the
weights are variances, so mixing radians and metres weighs them arbitrarily.
"""

from __future__ import annotations

import numpy as np


def aggregated_indices(indices: np.ndarray, variances: np.ndarray) -> np.ndarray:
    """Variance-weighted mean over the components: ``indices`` (..., T, D) of the T
    components (S1 or ST, or a stack of them), ``variances`` (T,) ≥ 0; returns (..., D)."""
    weights = np.asarray(variances, dtype=np.float64)
    if np.any(weights < 0.0) or not np.all(np.isfinite(weights)):
        raise ValueError("variances must be finite and non-negative")
    total = weights.sum()
    if total == 0.0:
        return np.zeros(np.shape(indices)[:-2] + np.shape(indices)[-1:])
    return np.einsum("...td,t->...d", np.asarray(indices, dtype=np.float64), weights / total)


def trajectory_aggregates(indices: np.ndarray, variances: np.ndarray):
    """``(aggregated (M, 2, D), overall (2, D))`` of M outputs recorded at K times:
    ``indices`` (2, K, M, D) their S1 and ST at every time, ``variances`` (K, M) their
    variances there (over independent uniform runs). ``aggregated[m]`` weighs output m's
    times by its variances (:func:`aggregated_indices`); ``overall`` weighs every output's
    trajectory after scaling it to unit total variance (so that radians and metres weigh
    alike): the mean of the ``aggregated`` of the outputs that vary (zeros if none does)."""
    indices = np.asarray(indices, dtype=np.float64)
    variances = np.asarray(variances, dtype=np.float64)
    m_outputs = indices.shape[2]
    aggregated = np.stack(
        [aggregated_indices(indices[:, :, m], variances[:, m]) for m in range(m_outputs)]
    )
    varies = variances.sum(axis=0) > 0.0
    overall = aggregated[varies].mean(axis=0) if varies.any() else np.zeros(aggregated.shape[1:])
    return aggregated, overall

r"""Sobol' indices from a sparse polynomial chaos expansion (PCE), fitted on a few hundred
model runs.

The inputs are independent and uniform on their tolerance boxes; on the unit hypercube
:math:`u \in [0, 1]^D` the orthonormal basis is the product of shifted Legendre polynomials

.. math:: \Psi_\alpha(u) = \prod_{d=1}^{D} \psi_{\alpha_d}(u_d),\qquad
          \psi_k(u) = \sqrt{2k+1}\,P_k(2u - 1),\qquad E[\Psi_\alpha\Psi_\beta] = \delta_{\alpha\beta},

over the multi-indices of total degree :math:`|\alpha| \le p`. A model output is
approximated by :math:`Y \approx \sum_{\alpha \in A} c_\alpha \Psi_\alpha` with a sparse set A
chosen by orthogonal matching pursuit (OMP, Pati et al. 1993; for several outputs at once
the simultaneous OMP of Tropp et al. 2006, one shared set) on a scrambled Sobol' design,
each OMP step refitted by least squares. The number of terms and the degree p are chosen
by the **corrected leave-one-out error** (Blatman & Sudret 2011, Chapelle et al. 2002)

.. math:: \varepsilon_{LOO} = \frac{T(k, N)}{N\,\widehat{\mathrm{Var}}\,Y}
          \sum_{i=1}^{N} \Big(\frac{y_i - \hat y_i}{1 - h_i}\Big)^2,\qquad
          T(k, N) = \frac{N}{N - k}\Big(1 + \frac{\mathrm{tr}\,C_{emp}^{-1}}{N}\Big),

:math:`h_i` the diagonal of the hat matrix, :math:`C_{emp} = \Psi_A^T\Psi_A / N` (from the
QR factors kept by the OMP: :math:`h_i = \sum_k Q_{ik}^2`, :math:`\mathrm{tr}\,C_{emp}^{-1} =
N\,\|R^{-1}\|_F^2`). The indices follow from the coefficients (Sudret 2008):

.. math:: V = \sum_{\alpha \ne 0} c_\alpha^2,\quad
          S_i = \frac{1}{V}\sum_{\alpha \in A_i} c_\alpha^2,\quad
          S_{T,i} = \frac{1}{V}\sum_{\alpha_i > 0} c_\alpha^2,\quad
          S_{ij} = \frac{1}{V}\sum_{\alpha \in A_{ij}} c_\alpha^2,

:math:`A_i` the multi-indices with :math:`\alpha_i` the only non-zero entry, :math:`A_{ij}`
those whose non-zero entries are exactly i and j. Confidence half-widths: ``z σ`` (as
SALib reports its own) over a wild bootstrap of the regression (:func:`bootstrap_halfwidths`).
Several outputs share one OMP path and each keeps the prefix of it with its own least LOO
error (:func:`omp_path`). Many outputs (a path's every effort at every step) are fitted on their
principal components (:mod:`.pce_compress`): the same fit, output by output.

Pure NumPy (the basis by the three-term recurrence, the regression by Gram-Schmidt): no
import beyond NumPy, and SciPy's ``qmc.Sobol`` only to draw a design the first time (then
the persistent :mod:`.design_cache`). Why not Chaospy or OpenTURNS: ``docs/sensitivity.md``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from statistics import NormalDist

import numpy as np

from planar_tui.sensitivity.design_cache import cached_design, sampler_versions
from planar_tui.sensitivity.pce_compress import (
    Compressed,
    bootstrap_compressed,
    compress,
    leave_out_sums,
    mixing,
)
from planar_tui.sensitivity.pce_indices import indices_from_coefficients

#: Bootstrap resamples and confidence level (SALib's defaults, as for Sobol').
NUM_RESAMPLES = 100
CONF_LEVEL = 0.95
#: Highest degree tried, and the largest candidate basis (terms) a degree may have.
MAX_DEGREE = 8
MAX_CANDIDATES = 1000
#: OMP stops after this many steps in which the mean of the outputs' best LOO errors has
#: not fallen by ``PROGRESS`` (relative) since the last progress (and at N / 2 terms).
PATIENCE_STEPS = 30
PROGRESS = 0.01
#: A LOO error below this is good enough: no more terms or degrees are tried (an index's
#: error is then about 2 (S ε)^½ ≤ 2e-4).
ENOUGH_LOO = 1e-8


class PceError(ValueError):
    """The expansion cannot stand behind its indices (LOO error too large, too few runs):
    ``problem``, what to do (``expected``) and the preset ``key`` to change; ``str`` is the
    line ``problem: expected``."""

    def __init__(self, problem: str, expected: str = "", key: str = "pce_samples"):
        self.problem, self.expected, self.key = problem, expected, key
        super().__init__(f"{problem}: {expected}" if expected else problem)


def default_pce_samples(num_vars: int) -> int:
    """Model runs of a PCE by default: ``max(128, 64 D)``, the quadratic basis (``(D+1)(D+2)/2``
    terms) fitted with at least five runs per term up to D = 24 (768 runs for D = 12)."""
    return max(128, 64 * num_vars)


def total_degree_indices(num_vars: int, degree: int) -> np.ndarray:
    """Multi-indices α ∈ ℕ^D with |α| ≤ degree, graded (degree 0, then 1, …; within a
    degree, lexicographically decreasing), shape (C(D + p, p), D)."""
    rows: list[tuple[int, ...]] = []

    def fill(prefix: tuple[int, ...], left: int, slots: int) -> None:
        if slots == 0:
            if left == 0:
                rows.append(prefix)
            return
        for first in range(left, -1, -1):
            fill((*prefix, first), left - first, slots - 1)

    for total in range(degree + 1):
        fill((), total, num_vars)
    return np.array(rows, dtype=np.int64).reshape(-1, num_vars)


def legendre_table(unit: np.ndarray, degree: int) -> np.ndarray:
    r"""Orthonormal shifted Legendre values :math:`\psi_k(u) = \sqrt{2k+1}P_k(2u-1)`,
    shape (S, D, degree + 1), by Bonnet's recurrence
    :math:`(k+1)P_{k+1}(x) = (2k+1)xP_k(x) - kP_{k-1}(x)`."""
    x = 2.0 * np.asarray(unit, dtype=np.float64) - 1.0
    table = np.empty((*x.shape, degree + 1))
    table[..., 0] = 1.0
    if degree >= 1:
        table[..., 1] = x
    for k in range(1, degree):
        table[..., k + 1] = ((2 * k + 1) * x * table[..., k] - k * table[..., k - 1]) / (k + 1)
    table *= np.sqrt(2.0 * np.arange(degree + 1) + 1.0)
    return table


def basis_matrix(unit: np.ndarray, indices: np.ndarray) -> np.ndarray:
    """Ψ (S, P): every basis polynomial of ``indices`` (P, D) at every row of ``unit``."""
    degree = int(indices.max(initial=0))
    table = legendre_table(unit, degree)
    psi = np.ones((table.shape[0], indices.shape[0]))
    for d in range(indices.shape[1]):
        column = indices[:, d]
        if column.any():
            psi *= table[:, d, column]
    return psi


@dataclass(frozen=True)
class OmpPath:
    """One OMP path and each output's best model on it: the path's terms (columns of Ψ,
    the constant first, in the order chosen), the coefficients (k, T) of every output on
    its own first ``term_counts[t]`` terms (zeros after), and its corrected LOO error (T,);
    the QR factors of the terms' basis values, Q (S, k) and R⁻¹ (k, k)."""

    terms: np.ndarray
    coefficients: np.ndarray
    term_counts: np.ndarray
    loo_error: np.ndarray
    q: np.ndarray
    r_inv: np.ndarray


def omp_path(psi: np.ndarray, y: np.ndarray | Compressed, max_terms: int | None = None) -> OmpPath:
    """Simultaneous OMP over the columns of ``psi`` (S, P; column 0 the constant) for the
    outputs ``y`` (S, T; or their principal components,
    :class:`~planar_tui.sensitivity.pce_compress.Compressed`: the same path, output by
    output, on r columns), stopped at ``max_terms`` (default N / 2), after
    ``PATIENCE_STEPS`` steps without progress (``PROGRESS``) of the mean of the outputs'
    best LOO errors, or once every
    output's is below ``ENOUGH_LOO``. Each output keeps the prefix of the path with its
    least corrected LOO error (the QR is nested, so every prefix's least-squares fit is
    at hand): an output that no polynomial fits does not spoil the others.

    Each step adds the column with the largest :math:`\\sum_t (\\psi_j^T r_t)^2 /
    (\\|\\psi_j\\|^2 \\|y_t - \\bar y_t\\|^2)` over the outputs not yet fitted (r_t the
    residual of output t) to an incremental QR factorisation (classical Gram-Schmidt,
    re-orthogonalised once); residuals, hat diagonal, :math:`R^{-1}` and correlations are
    updated in O(S P) per step."""
    s_rows, p_cols = psi.shape
    limit = min(p_cols, max(2, s_rows // 2)) if max_terms is None else min(max_terms, p_cols)
    if isinstance(y, Compressed):  # the residuals of the scores, mapped by the loadings
        mean, residual, loadings = y.mean, y.scores.copy(), y.loadings
        spread = y.spread
    else:
        mean, loadings = y.mean(axis=0), None
        residual = y - mean
        spread = np.einsum("st,st->t", residual, residual)
    t_out = len(mean)
    varies = spread > 0.0
    weight = np.where(varies, 1.0 / np.where(varies, spread, 1.0), 0.0)
    scoring = weight if loadings is None else mixing(loadings, weight)
    norms = np.sqrt(np.einsum("sp,sp->p", psi, psi))
    usable = norms > 0.0
    q = np.empty((s_rows, limit))
    r_inv = np.zeros((limit, limit))
    projections = np.empty((limit, residual.shape[1]))  # Q^T (y − 1 μ^T), or Q^T Z
    sums = np.empty(limit)  # Q^T 1
    correlation = psi.T @ residual  # ψ_j^T r_t, kept up to date
    hat = np.zeros(s_rows)
    r_inv_norm2 = 0.0
    chosen: list[int] = []
    best_loo = np.full(t_out, math.inf)
    best_terms = np.zeros(t_out, dtype=np.int64)
    stale, reference = 0, math.inf
    column = 0  # the constant first
    while len(chosen) < limit:
        k = len(chosen)
        v = psi[:, column].copy()
        coefficients_r = np.zeros(k)
        for _ in range(2):  # CGS2
            if k:
                projection = q[:, :k].T @ v
                v -= q[:, :k] @ projection
                coefficients_r += projection
        rho = math.sqrt(float(v @ v))
        usable[column] = False
        if rho <= 1e-10 * norms[column]:  # dependent on the chosen terms: never again
            column = _next_column(correlation, norms, usable, scoring)
            if column < 0:
                break
            continue
        v /= rho
        q[:, k] = v
        # R⁻¹ of [[R, r], [0, ρ]] = [[R⁻¹, −R⁻¹ r / ρ], [0, 1/ρ]]
        r_inv[:k, k] = -(r_inv[:k, :k] @ coefficients_r) / rho
        r_inv[k, k] = 1.0 / rho
        r_inv_norm2 += float(r_inv[: k + 1, k] @ r_inv[: k + 1, k])
        projections[k], sums[k] = v @ residual, v.sum()
        residual -= np.outer(v, projections[k])
        correlation -= np.outer(psi.T @ v, projections[k])
        hat += v * v
        chosen.append(column)
        if s_rows > k + 1:
            loo = _corrected_loo(residual, hat, spread, s_rows, k + 1, r_inv_norm2, loadings)
            better = loo < best_loo
            best_loo = np.where(better, loo, best_loo)
            best_terms = np.where(better, k + 1, best_terms)
            score = float(best_loo[varies].mean()) if varies.any() else 0.0
            if score < (1.0 - PROGRESS) * reference:  # progress: patience starts again
                reference, stale = score, 0
            else:
                stale += 1
            fitted = (best_loo <= ENOUGH_LOO) & (weight > 0.0)  # fitted: serve the rest
            if fitted.any():
                weight = np.where(fitted, 0.0, weight)
                scoring = weight if loadings is None else mixing(loadings, weight)
        if stale >= PATIENCE_STEPS or not weight.any():  # (every output fitted: a shortcut,
            break  # _next_column returns -1 then too)
        column = _next_column(correlation, norms, usable, scoring)
        if column < 0:
            break
    if not chosen or best_terms.min() == 0:
        raise PceError(f"{s_rows} runs cannot fit even the constant term", "more runs")
    terms = int(best_terms.max())
    # Q^T y_t, zero past output t's terms (R⁻¹ upper triangular: its k_t-block acts alone)
    on_outputs = projections[:terms] if loadings is None else projections[:terms] @ loadings.T
    on_outputs += np.outer(sums[:terms], mean)
    on_outputs[np.arange(terms)[:, None] >= best_terms[None, :]] = 0.0
    coefficients = r_inv[:terms, :terms] @ on_outputs
    return OmpPath(
        np.array(chosen[:terms]),
        coefficients,
        best_terms,
        best_loo,
        q[:, :terms].copy(),
        r_inv[:terms, :terms].copy(),
    )


def _next_column(correlation, norms, usable, weight) -> int:
    """The usable column most correlated with the residuals, or -1. ``weight``: 1 / spread
    of the outputs still to fit, or, where the correlations are the scores', its
    :func:`~.pce_compress.mixing` matrix."""
    if not usable.any():
        return -1
    if weight.ndim == 1:
        score = (correlation**2) @ weight
    else:
        score = ((correlation @ weight) * correlation).sum(axis=1)
    score = np.where(usable, score / np.where(usable, norms, 1.0) ** 2, -1.0)
    column = int(score.argmax())
    return column if score[column] > 0.0 else -1


def _corrected_loo(residual, hat, spread, s_rows: int, terms: int, r_inv_norm2, loadings=None):
    """Corrected relative LOO error of every output (0 for one that does not vary;
    ``loadings``: the residuals are the scores', :func:`~.pce_compress.leave_out_sums`)."""
    if loadings is not None:
        sum_squares = leave_out_sums(residual, hat, loadings)
    else:
        with np.errstate(divide="ignore", invalid="ignore"):
            leave_out = residual / (1.0 - hat)[:, None]
        sum_squares = np.einsum("st,st->t", leave_out, leave_out)
    correction = s_rows / (s_rows - terms) * (1.0 + r_inv_norm2)
    safe = np.where(spread > 0.0, spread, 1.0)
    loo = np.where(spread > 0.0, correction * sum_squares / safe, 0.0)
    return np.where(np.isfinite(loo), loo, math.inf)


@dataclass(frozen=True)
class PceFit:
    """A fitted expansion of one output group: degree, multi-indices of its terms (k, D),
    coefficients (k, T) on the orthonormal basis (output t uses the first
    ``term_counts[t]`` terms, zeros after), corrected LOO error per output (T,), and the
    design rows' basis values of the terms (S, k) and their QR factors Q (S, k), R⁻¹ (k, k),
    kept for the bootstrap, with the outputs' principal components where they were fitted
    on them (``compressed``)."""

    degree: int
    indices: np.ndarray
    coefficients: np.ndarray
    term_counts: np.ndarray
    loo_error: np.ndarray
    basis: np.ndarray
    q: np.ndarray
    r_inv: np.ndarray
    compressed: Compressed | None = None

    @property
    def mean(self) -> np.ndarray:
        """The expansion's mean of every output (the constant term's coefficient)."""
        constant = ~self.indices.any(axis=1)
        return self.coefficients[constant].sum(axis=0)

    @property
    def variance(self) -> np.ndarray:
        """The expansion's variance of every output, Σ_{α≠0} c_α²."""
        varying = self.indices.any(axis=1)
        return (self.coefficients[varying] ** 2).sum(axis=0)


def fit_pce(
    unit: np.ndarray,
    y: np.ndarray,
    max_degree: int = MAX_DEGREE,
    on_degree: Callable[[int], None] | None = None,
    compressed: bool = True,
) -> PceFit:
    """The sparse expansion of the outputs ``y`` (S, T) on the unit design ``unit`` (S, D)
    with the least mean corrected LOO error over degrees 1, 2, …: a degree is tried while
    its candidate basis stays under ``MAX_CANDIDATES`` terms and the error keeps falling
    (it stops after two degrees without improvement, or once it is below ``ENOUGH_LOO``);
    ``on_degree(p)`` runs after each degree (it may raise to cancel). With ``compressed``
    many outputs are fitted on their principal components
    (:func:`~planar_tui.sensitivity.pce_compress.compress`: the same fit up to the variance
    it drops, 1e-12 of each output's)."""
    unit = np.asarray(unit, dtype=np.float64)
    y = np.asarray(y, dtype=np.float64).reshape(unit.shape[0], -1)
    components = compress(y) if compressed else None
    num_vars = unit.shape[1]
    best: tuple[float, PceFit] | None = None
    worse = 0
    for degree in range(1, max_degree + 1):
        indices = total_degree_indices(num_vars, degree)
        if degree > 1 and len(indices) > MAX_CANDIDATES:
            break
        psi = basis_matrix(unit, indices)
        path = omp_path(psi, y if components is None else components)
        varies = np.ptp(y, axis=0) > 0.0
        score = float(path.loo_error[varies].mean()) if varies.any() else 0.0
        fit = PceFit(
            degree,
            indices[path.terms],
            path.coefficients,
            path.term_counts,
            path.loo_error,
            psi[:, path.terms],
            path.q,
            path.r_inv,
            components,
        )
        if on_degree is not None:
            on_degree(degree)
        if best is None or score < best[0]:
            best, worse = (score, fit), 0
        else:
            worse += 1
        if worse >= 2 or best[0] <= ENOUGH_LOO:
            break
    assert best is not None
    return best[1]


def second_order_indices(indices: np.ndarray, coefficients: np.ndarray) -> np.ndarray:
    """S_ij (T, D, D), symmetric, zero diagonal: the variance share of the terms whose
    inputs are exactly {i, j}."""
    active = indices > 0
    pairs = active.sum(axis=1) == 2
    energy = coefficients[pairs] ** 2
    variance = (coefficients[active.any(axis=1)] ** 2).sum(axis=0)
    result = np.zeros((coefficients.shape[1], indices.shape[1], indices.shape[1]))
    for row, term in zip(energy, active[pairs], strict=True):
        i, j = np.flatnonzero(term)
        result[:, i, j] += row
        result[:, j, i] += row
    safe = np.where(variance > 0.0, variance, 1.0)
    return result / safe[:, None, None]


def bootstrap_halfwidths(
    fit: PceFit,
    y: np.ndarray,
    seed: int,
    num_resamples: int = NUM_RESAMPLES,
    conf_level: float = CONF_LEVEL,
):
    r"""``z σ`` of S1 and ST (each (T, D)) over a wild bootstrap of the regression (Wu
    1986): resample b keeps the design and replaces output t by
    :math:`\hat y_t + e_t \odot v_b` (:math:`e_t` its residuals, :math:`v_b` Rademacher
    signs from ``default_rng(seed)``), refitted on its own terms by least squares. With
    :math:`\Psi = QR` (the terms' basis values, factored by the OMP; the QR of a prefix of
    columns is the prefix of the QR) the refit is :math:`c_b = c + R^{-1}Q^T(e \odot v_b)`,
    two matrix products for all outputs and resamples instead of R T least-squares fits;
    exact models get zero half-widths, as they should. A fit on principal components:
    :func:`~planar_tui.sensitivity.pce_compress.bootstrap_compressed`."""
    if fit.compressed is not None:
        return bootstrap_compressed(fit, fit.compressed, seed, num_resamples, conf_level)
    y = np.asarray(y, dtype=np.float64).reshape(fit.basis.shape[0], -1)
    s_rows = fit.basis.shape[0]
    signs = np.random.default_rng(seed).integers(0, 2, size=(s_rows, num_resamples)) * 2.0 - 1.0
    q = fit.q
    residuals = y - fit.basis @ fit.coefficients  # (S, T)
    t_out = y.shape[1]
    # Q^T (e_t ⊙ v_b) for every output and resample, one product per term j
    # ((q_j ⊙ e)^T v: no S × T × B array), rows past k_t zeroed; then R⁻¹ (upper
    # triangular: on a zero-padded column it acts as its k_t × k_t block)
    k = len(fit.r_inv)
    shift = np.empty((k, t_out, num_resamples))
    for j in range(k):
        shift[j] = (q[:, j, None] * residuals).T @ signs
    shift[np.arange(k)[:, None] >= fit.term_counts[None, :]] = 0.0
    shift = (fit.r_inv @ shift.reshape(k, -1)).reshape(k, t_out, num_resamples)
    coefficients = fit.coefficients[None] + np.moveaxis(shift, 2, 0)  # (B, k, T)
    first, total = indices_from_coefficients(fit.indices, coefficients)
    z = NormalDist().inv_cdf(0.5 + conf_level / 2.0)
    return z * first.std(axis=0, ddof=1), z * total.std(axis=0, ddof=1)


def pce_indices(
    unit: np.ndarray,
    outputs: np.ndarray,
    seed: int,
    shared: bool = False,
    num_resamples: int = NUM_RESAMPLES,
    on_output: Callable[[float], None] | None = None,
):
    """(4, T, D) S1, S1 half-width, ST, ST half-width of every column of ``outputs`` (S, T),
    and the fits: one per column, or one shared by all columns when ``shared`` (the
    simultaneous OMP: a trajectory's outputs). ``on_output(fraction)`` runs after each fit."""
    outputs = np.asarray(outputs, dtype=np.float64).reshape(unit.shape[0], -1)
    groups = [slice(None)] if shared else [slice(t, t + 1) for t in range(outputs.shape[1])]
    result = np.empty((4, outputs.shape[1], unit.shape[1]))
    fits = []
    for group in groups:
        fit = fit_pce(unit, outputs[:, group])
        result[0, group], result[2, group] = indices_from_coefficients(
            fit.indices, fit.coefficients
        )
        if num_resamples > 1:
            result[1, group], result[3, group] = bootstrap_halfwidths(
                fit, outputs[:, group], seed, num_resamples
            )
        else:
            result[[1, 3], group] = 0.0
        fits.append(fit)
        if on_output is not None:
            on_output(1.0 / len(groups))
    return result, fits


def pce_unit_design(num_vars: int, samples: int, seed: int) -> np.ndarray:
    """The first ``samples`` points of a scrambled Sobol' sequence in D dimensions
    (``scipy.stats.qmc.Sobol(D, scramble=True, seed=seed)``, drawn as the next power of
    two so that SciPy's balance warning does not apply), read-only, kept on disk."""

    def draw() -> np.ndarray:
        from scipy.stats import qmc

        engine = qmc.Sobol(d=num_vars, scramble=True, seed=seed)
        return engine.random_base2(max(0, math.ceil(math.log2(samples))))[:samples]

    key = f"v1_pce_D{num_vars}_N{samples}_seed{seed}_{sampler_versions()}"
    design = cached_design(key, (samples, num_vars), draw)
    design.setflags(write=False)
    return design

r"""Sobol' and eFAST indices from model outputs, fast (SALib, the reference they equal,
runs in ``tests/salib_reference.py``).

:func:`sobol_indices` runs the jitted Saltelli-2010 estimators of
:mod:`kernels.sensitivity_estimators` with the bootstrap rows SALib would draw
(``default_rng(seed).integers(N, size=(N, R))``), so its S1, ST *and* confidence
half-widths equal ``SALib.analyze.sobol.analyze(..., seed=seed)`` to round-off.

:func:`efast_indices` is ``SALib.analyze.fast`` vectorised over outputs and bootstrap
resamples (one real FFT per batch instead of one ``np.fft.fft`` per resample). With
:math:`S_p = |\hat y_k / N|^2`, :math:`V = 2\sum_{k=1}^{\lceil N/2\rceil-1} S_k`,

.. math::  S_1 = \frac{2\sum_{p=1}^{M} S_{p\omega}}{V},\qquad
           S_T = 1 - \frac{2\sum_{k=1}^{\lfloor\omega/2\rfloor} S_k}{V}

(paper A eqs. 38-40, Saltelli, Tarantola & Chan 1999), ω = ⌊(N-1)/2M⌋. The bootstrap
takes R cyclic windows of half the curve starting at the positions SALib's
``np.random.seed(seed); np.random.randint`` would draw. **Those eFAST confidence
half-widths are unreliable** (SALib issue #649: a half window is not a search curve of the
sampled frequencies); they are reported, labelled as such, never used to judge accuracy.

Both return arrays of shape (4, n_out, D): S1, S1 half-width, ST, ST half-width.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable
from functools import lru_cache
from statistics import NormalDist

import numpy as np

#: FFT input samples per eFAST task (a group of bootstrap windows): ~10-40 ms.
FFT_SAMPLES_PER_TASK = 1 << 20
#: Bootstrap resamples and confidence level: SALib's defaults.
NUM_RESAMPLES = 100
CONF_LEVEL = 0.95


def _z_value(conf_level: float) -> float:
    return NormalDist().inv_cdf(0.5 + conf_level / 2.0)


def sobol_bootstrap_rows(n_base: int, seed: int, num_resamples: int = NUM_RESAMPLES):
    """SALib's bootstrap rows, transposed to (R, N)."""
    rows = np.random.default_rng(seed).integers(n_base, size=(n_base, num_resamples))
    return np.ascontiguousarray(rows.T)


@lru_cache(maxsize=8)
def sobol_bootstrap_counts(n_base: int, seed: int, num_resamples: int = NUM_RESAMPLES):
    """(R, N) draw counts of :func:`sobol_bootstrap_rows` (read-only, cached per process:
    every job with the same N and seed shares them)."""
    from planar_tui.kernels.sensitivity_estimators import resample_counts

    counts = resample_counts(sobol_bootstrap_rows(n_base, seed, num_resamples), n_base)
    counts.setflags(write=False)
    return counts


def sobol_indices(
    outputs,
    num_vars: int,
    seed: int,
    num_resamples=NUM_RESAMPLES,
    conf_level=CONF_LEVEL,
    on_chunk: Callable[[float], None] | None = None,
):
    """S1, ST and bootstrap half-widths of every column of ``outputs`` (Saltelli design,
    no second order, N (D + 2) rows). ``seed`` > 0, as SALib's ``analyze`` treats 0 as none.

    Output columns in blocks, each one kernel call of all its resamples' bootstrap sums
    (``counts`` (R, N) @ terms (N, 2D + 4) for every column at once) within about
    ``SUMS_PER_CALL`` multiply-adds (one column a call when a column alone is more, its
    resamples then in chunks). Columns and resamples are independent, so the estimates are
    those of one pass over all of them; ``on_chunk(fraction)`` runs after each call."""
    from planar_tui.kernels import sensitivity_estimators as estimators

    outputs = np.asarray(outputs, dtype=np.float64)
    n_base = outputs.shape[0] // (num_vars + 2)
    n_out = outputs.shape[1]
    counts = sobol_bootstrap_counts(n_base, seed, num_resamples)
    per_column = n_base * (2 * num_vars + 4) * counts.shape[0]
    width = max(1, estimators.SUMS_PER_CALL // max(1, per_column))
    result = np.empty((4, n_out, num_vars))
    for start in range(0, n_out, width):
        stop = min(n_out, start + width)
        share = (stop - start) / n_out
        block_chunk = None if on_chunk is None else (lambda f, s=share: on_chunk(f * s))
        result[:, start:stop] = estimators.sobol_first_total(
            np.ascontiguousarray(outputs[:, start:stop]),
            num_vars,
            counts,
            _z_value(conf_level),
            block_chunk,
        )
    return result


def _fourier_orders(curves, m_harmonics: int):
    """eFAST S1 and ST of search curves ``curves`` (..., N) (SALib ``compute_orders``).

    The power :math:`|\\hat y_k|^2` is left unscaled: the factors 2 and 1/N² of
    :math:`S_k` cancel in both ratios. Sums of squares are taken over the (re, im) pairs
    of the spectrum viewed as reals (``einsum``, no temporary power array)."""
    n = curves.shape[-1]
    omega = (n - 1) // (2 * m_harmonics)
    spectrum = np.fft.rfft(curves, axis=-1)
    pairs = spectrum[..., 1 : math.ceil(n / 2)].view(np.float64)  # re, im of k = 1, 2 ...
    variance = np.einsum("...i,...i->...", pairs, pairs)
    low = pairs[..., : 2 * (omega // 2)]
    rest = np.einsum("...i,...i->...", low, low)
    harmonics = spectrum[..., np.arange(1, m_harmonics + 1) * omega]
    first = (harmonics.real**2 + harmonics.imag**2).sum(axis=-1)
    return first / variance, 1.0 - rest / variance


def efast_point_indices(outputs, num_vars: int, m_harmonics: int = 4) -> np.ndarray:
    """(2, n_out, D) eFAST S1 and ST of every column of ``outputs`` (``fast_sampler``
    design: D blocks of N rows), without the bootstrap: the same orders
    :func:`efast_indices` reports (one FFT per curve, all curves at once)."""
    outputs = np.asarray(outputs, dtype=np.float64)
    n_curve = outputs.shape[0] // num_vars
    curves = np.ascontiguousarray(outputs.reshape(num_vars, n_curve, -1).transpose(0, 2, 1))
    first, total = _fourier_orders(curves, m_harmonics)  # (D, n_out) each
    return np.stack([first.T, total.T])


def _worker_count() -> int:
    """CPUs this process may run on."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1


def efast_indices(
    outputs,
    num_vars: int,
    seed: int,
    m_harmonics=4,
    num_resamples=NUM_RESAMPLES,
    conf_level=CONF_LEVEL,
    on_chunk: Callable[[float], None] | None = None,
):
    """eFAST S1, ST and (unreliable, see module docstring) bootstrap half-widths of every
    column of ``outputs`` (``fast_sampler`` design: D blocks of N rows).

    Tasks of one (input, output) curve and a group of its bootstrap windows (about
    ``FFT_SAMPLES_PER_TASK`` samples; the curve's own orders with its first group) run on
    a thread pool: NumPy's FFT releases the GIL. Each task writes its own cells, so the
    result does not depend on the scheduling; ``on_chunk(fraction)`` runs after each
    round of one task per worker."""
    from concurrent.futures import ThreadPoolExecutor

    outputs = np.asarray(outputs, dtype=np.float64)
    n_curve = outputs.shape[0] // num_vars
    n_out = outputs.shape[1]
    starts = np.random.RandomState(seed).randint(0, n_curve, size=num_vars * num_resamples)
    starts = starts.reshape(num_vars, num_resamples)
    window = math.ceil(n_curve * 0.5)
    group = max(1, FFT_SAMPLES_PER_TASK // window)
    groups = range(0, num_resamples, group)
    result = np.zeros((4, n_out, num_vars))
    boot = np.empty((2, n_out, num_vars, num_resamples))  # S1, ST of every window

    def one_task(task: int) -> None:
        curve_index, b0 = divmod(task, len(groups))
        i, t = divmod(curve_index, n_out)
        b0 *= group
        curve = outputs[i * n_curve : (i + 1) * n_curve, t]
        if b0 == 0:
            result[0, t, i], result[2, t, i] = _fourier_orders(curve, m_harmonics)
        # cyclic windows of the curve = slices of the curve repeated once
        doubled = np.concatenate([curve, curve[: window - 1]])
        chosen = starts[i, b0 : b0 + group]
        windows = np.lib.stride_tricks.sliding_window_view(doubled, window)[chosen]
        b1 = b0 + len(chosen)
        boot[0, t, i, b0:b1], boot[1, t, i, b0:b1] = _fourier_orders(windows, m_harmonics)

    tasks = range(num_vars * n_out * len(groups))
    workers = min(_worker_count(), len(tasks))
    with ThreadPoolExecutor(max_workers=workers) as pool:
        for start in range(0, len(tasks), workers):  # one task per worker between checks
            batch = tasks[start : start + workers]
            list(pool.map(one_task, batch))
            if on_chunk is not None:
                on_chunk(len(batch) / len(tasks))
    z = _z_value(conf_level)
    for t in range(n_out):
        for i in range(num_vars):
            result[1, t, i] = z * boot[0, t, i].std(ddof=1)
            result[3, t, i] = z * boot[1, t, i].std(ddof=1)
    return result

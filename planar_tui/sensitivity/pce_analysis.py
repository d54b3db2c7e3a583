"""A job's PCE analysis, on :mod:`planar_tui.sensitivity.pce`'s expansions: one group of
outputs with terms shared (:func:`job_indices`: failed runs checked, the LOO error bounded),
or a trajectory, one expansion per output over its times with the indices aggregated over
it (:func:`trajectory_indices`, Gamboa et al. 2014)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from planar_tui.sensitivity.aggregate import trajectory_aggregates
from planar_tui.sensitivity.failed_runs import check_failed_runs
from planar_tui.sensitivity.pce import NUM_RESAMPLES, PceError, pce_indices


def check_loo(fits, names, max_loo_error: float, samples: int, key_samples="pce_samples"):
    """Raise :class:`PceError` naming the worst output when a LOO error exceeds
    ``max_loo_error``; ``names`` labels the outputs in the fits' order (a fit's
    ``loo_error`` flattened in C order: a trajectory's (K, M) time by time)."""
    errors = np.concatenate([np.ravel(fit.loo_error) for fit in fits])
    worst = int(np.argmax(errors))
    if errors[worst] > max_loo_error:
        raise PceError(
            f"PCE leave-one-out error {errors[worst]:.3g} of {names[worst]} exceeds "
            f"pce_max_loo_error = {max_loo_error:g}",
            f"raise {key_samples} (now {samples}) or pce_max_loo_error",
            key_samples,
        )


@dataclass(frozen=True)
class TrajectoryIndices:
    """PCE indices of M outputs recorded at K times, from one set of runs.

    ``indices`` (4, K, M, D): S1, its half-width, ST, its half-width at every time;
    ``loo_error`` and ``variance`` (K, M); ``aggregated`` (M, 2, D): S1 and ST of each
    output over its whole trajectory (:func:`~planar_tui.sensitivity.aggregate.aggregated_indices`);
    ``overall`` (2, D): over all outputs, each output's trajectory first scaled to unit
    total variance (so that radians and metres weigh alike)."""

    indices: np.ndarray
    loo_error: np.ndarray
    variance: np.ndarray
    aggregated: np.ndarray
    overall: np.ndarray


def trajectory_indices(
    unit: np.ndarray,
    outputs: np.ndarray,
    seed: int,
    num_resamples: int = NUM_RESAMPLES,
    on_output: Callable[[float], None] | None = None,
) -> TrajectoryIndices:
    """Indices of ``outputs`` (S, K, M) at every time and aggregated: one expansion per
    output with terms shared over its K times (:func:`pce_indices` with ``shared``)."""
    _, k_times, m_outputs = outputs.shape
    indices = np.empty((4, k_times, m_outputs, unit.shape[1]))
    loo = np.empty((k_times, m_outputs))
    variance = np.empty((k_times, m_outputs))
    for m in range(m_outputs):
        result, (fit,) = pce_indices(unit, outputs[:, :, m], seed, True, num_resamples)
        indices[:, :, m] = result
        loo[:, m], variance[:, m] = fit.loo_error, fit.variance
        if on_output is not None:
            on_output(1.0 / m_outputs)
    aggregated, overall = trajectory_aggregates(indices[[0, 2]], variance)
    return TrajectoryIndices(indices, loo, variance, aggregated, overall)


def job_indices(
    unit: np.ndarray,
    outputs: np.ndarray,
    seed: int,
    input_names,
    output_names,
    max_loo_error: float,
    allow_failed_runs: float = 0.0,
    num_resamples: int = NUM_RESAMPLES,
) -> tuple[np.ndarray, np.ndarray, str]:
    """A job's PCE analysis of ``outputs`` (S, T): failed runs checked (and dropped when
    ``allow_failed_runs`` allows), one expansion with terms shared by the T outputs, its
    LOO errors checked against ``max_loo_error``. Returns the (4, T, D) indices, the LOO
    error of every output (T,) and a note (``""`` or the dropped runs' line); raises
    :class:`PceError` or :class:`~planar_tui.sensitivity.failed_runs.FailedRuns`."""
    outputs = np.asarray(outputs, dtype=np.float64).reshape(len(unit), -1)
    keep, note = check_failed_runs(outputs, unit, input_names, allow_failed_runs, True)
    result, (fit,) = pce_indices(unit[keep], outputs[keep], seed, True, num_resamples)
    check_loo([fit], list(output_names), max_loo_error, len(unit))
    return result, fit.loo_error, note

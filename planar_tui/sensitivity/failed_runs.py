"""Failed model runs (a NaN, an infinity, a diverged simulation): counted, located, refused.

A run fails when any of its outputs is not finite. The failures are reported with the
region of the inputs they come from: each input on which every failed run lies in the
same half of its range (``high`` above the nominal value, ``low`` below) names a side of
the tolerance corner. Only a PCE can drop failed runs (its regression takes any rows);
Sobol' and eFAST designs lose their structure without them.
"""

from __future__ import annotations

import math

import numpy as np


class FailedRuns(ValueError):
    """Too many failed model runs (or any, for a method that cannot drop them):
    ``problem`` and ``expected``; ``str`` is the line ``problem: expected``."""

    def __init__(self, problem: str, expected: str):
        self.problem, self.expected, self.key = problem, expected, "allow_failed_runs"
        super().__init__(f"{problem}: {expected}")


def failed_rows(outputs: np.ndarray) -> np.ndarray:
    """(S,) True for every run (row of ``outputs`` (S, ...)) with a non-finite output."""
    values = np.asarray(outputs).reshape(len(outputs), -1)
    return ~np.isfinite(values).all(axis=1)


def failure_corner(unit: np.ndarray, failed: np.ndarray, names) -> str:
    """Where the failed rows of the unit design lie: ``"l1 high, m2 low"`` (the inputs on
    which they all share a half of the range), or ``"spread over the inputs' ranges"``."""
    rows = np.asarray(unit)[failed]
    sides = []
    for j, name in enumerate(names):
        if np.all(rows[:, j] > 0.5):
            sides.append(f"{name} high")
        elif np.all(rows[:, j] < 0.5):
            sides.append(f"{name} low")
    return ", ".join(sides) if sides else "spread over the inputs' ranges"


def check_failed_runs(
    outputs: np.ndarray, unit: np.ndarray, names, allow_fraction: float, can_drop: bool
) -> tuple[np.ndarray, str]:
    """The rows to keep and a note (``""`` when none failed); raises :class:`FailedRuns`
    with one line when the failed fraction exceeds ``allow_fraction`` or when the method
    cannot drop runs (``can_drop`` false)."""
    failed = failed_rows(outputs)
    count = int(failed.sum())
    if count == 0:
        return ~failed, ""
    total = len(failed)
    where = f"{count} of {total} model runs failed (NaN or divergence), from {failure_corner(unit, failed, names)}"
    if not can_drop:
        raise FailedRuns(where, "only the pce method can drop failed runs")
    if count > allow_fraction * total:
        needed = math.ceil(count / total * 1e4) / 1e4
        raise FailedRuns(where, f"set allow_failed_runs ≥ {needed:g} to drop them")
    return ~failed, f"{where}: dropped from the PCE fit"

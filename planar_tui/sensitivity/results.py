r"""Result records, the paper's "sensitivity percent", and the CSV table.

Paper A prints, per torque, a percentage per input summing to 100 %. Its eqs. 18 and 39 and
the 0.4-1.2 % eFAST entries of inputs a torque cannot depend on (only a total-index
estimator yields those) say it normalised **total** indices; the comparison in
``docs/sensitivity.md`` confirms it. So by default

.. math:: P_j = 100\,\frac{\max(S_{Tj}, 0)}{\sum_k \max(S_{Tk}, 0)},

and ``percent_of = "S1"`` normalises first-order indices instead (negative estimates of
either are clipped to 0 first).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from planar_tui.csvio import CsvTable

#: The index columns of a sensitivity-shaped CSV, after the columns that say which output.
INDEX_COLUMNS = ("parameter", "method", "S1", "S1_conf", "ST", "ST_conf", "percent")
CSV_HEADER = ("robot", "posture", "speed_rad_s", "torque", *INDEX_COLUMNS)


@dataclass(frozen=True)
class Analysis:
    """The indices of one method at one posture and speed: arrays (4, n, D).

    ``outputs`` names the n outputs in tables (default ``τ1 … τn``, the torques) and
    ``context`` replaces "posture · speed" in a table's title (e.g. ``t = 1 s`` for the
    motion job, whose analyses share a time instead of a posture and speed); ``runs`` the
    model runs the method made, ``loo_error`` a PCE's leave-one-out error per output.
    ``defined`` (n,) says which outputs have indices at all: one that does not vary over
    the robots (the motion job's angles at t = 0) has no variance to apportion, its
    indices are undefined (zeros in ``indices``, empty cells in a CSV); ``None``: all."""

    method: str
    posture: str
    speed_rad_s: float
    names: tuple[str, ...]
    indices: np.ndarray
    percent: np.ndarray  # (n, D)
    outputs: tuple[str, ...] = ()
    context: str = ""
    runs: int = 0
    loo_error: np.ndarray | None = None  # (n,) for a PCE
    defined: np.ndarray | None = None  # (n,) bool

    def is_defined(self, k: int) -> bool:
        """Whether output ``k`` has indices (see ``defined``)."""
        return self.defined is None or bool(self.defined[k])

    def output_labels(self) -> tuple[str, ...]:
        """The n outputs' row labels: ``outputs``, or the torques ``τ1 … τn``."""
        return self.outputs or tuple(f"τ{i + 1}" for i in range(self.indices.shape[1]))


def sensitivity_percent(indices: np.ndarray, percent_of: str = "ST") -> np.ndarray:
    """(n, D) percentages: the chosen index clipped at 0, normalised per torque to 100."""
    chosen = np.clip(indices[2 if percent_of == "ST" else 0], 0.0, None)
    totals = chosen.sum(axis=1, keepdims=True)
    return np.divide(100.0 * chosen, totals, out=np.zeros_like(chosen), where=totals > 0)


def grouped(analyses: Sequence[Analysis], key: Callable[[Analysis], Any]) -> dict:
    """The analyses by ``key`` (e.g. posture and speed), in run order."""
    groups: dict[Any, list[Analysis]] = {}
    for analysis in analyses:
        groups.setdefault(key(analysis), []).append(analysis)
    return groups


def index_rows(group: Sequence[Analysis]) -> Iterator[tuple[int, tuple]]:
    """The :data:`INDEX_COLUMNS` cells of a group of analyses sharing their inputs (one
    per method): per output ``k``, parameter and method, ``(k, cells)``. A NaN half-width
    (not computed: point estimates only) is an empty cell, and so is every index of an
    output without indices (:attr:`Analysis.defined`)."""
    for k in range(group[0].indices.shape[1]):
        for j, name in enumerate(group[0].names):
            for a in group:
                if not a.is_defined(k):
                    yield k, (name, a.method, "", "", "", "", "")
                    continue
                s1, s1_conf, st, st_conf = (float(v) for v in a.indices[:, k, j])
                yield (
                    k,
                    (
                        name,
                        a.method,
                        s1,
                        _conf_cell(s1_conf),
                        st,
                        _conf_cell(st_conf),
                        float(a.percent[k, j]),
                    ),
                )


def _conf_cell(half_width: float) -> float | str:
    return "" if math.isnan(half_width) else half_width


def run_cells(analyses: Sequence[Analysis]) -> Callable[[str, int], tuple]:
    """The cells after the index columns of (method, output k): ``runs``, and ``loo_error``
    when a PCE is among ``analyses`` (empty for the other methods and for an output without
    indices)."""
    by_method = {a.method: a for a in analyses}
    with_loo = any(a.loo_error is not None for a in analyses)

    def cells(method: str, k: int) -> tuple:
        analysis = by_method[method]
        if not with_loo:
            return (analysis.runs,)
        loo = analysis.loo_error
        if loo is None or not analysis.is_defined(k):
            return analysis.runs, ""
        return analysis.runs, float(loo[k])

    return cells


def run_columns(analyses: Sequence[Analysis]) -> tuple[str, ...]:
    """``("runs",)``, plus ``"loo_error"`` when a PCE is among ``analyses``."""
    with_loo = any(a.loo_error is not None for a in analyses)
    return ("runs", "loo_error") if with_loo else ("runs",)


def csv_table(robot_label: str, analyses: list[Analysis]) -> CsvTable:
    """One row per posture × speed × torque × parameter × method, in run order; the
    :func:`run_columns` last."""
    rows = []
    for (posture, speed), group in grouped(analyses, _posture_speed).items():
        extra = run_cells(group)
        for torque, cells in index_rows(group):
            rows.append(
                (robot_label, posture, float(speed), torque + 1, *cells, *extra(cells[1], torque))
            )
    return CsvTable(CSV_HEADER + run_columns(analyses), rows)


def _posture_speed(analysis: Analysis) -> tuple[str, float]:
    return analysis.posture, analysis.speed_rad_s


#: The header of a table of indices against time (the motion job's, a path's).
TIME_INDICES_HEADER = ("output", "t_s", *INDEX_COLUMNS)


def time_indices_table(analyses: Sequence[Analysis], names: Sequence[str]) -> CsvTable:
    """One row per time × output × parameter × method, the time in the analyses'
    ``speed_rad_s`` slot; the :func:`run_columns` last."""
    rows = []
    for t_s, group in grouped(analyses, lambda a: a.speed_rad_s).items():
        extra = run_cells(group)
        for k, cells in index_rows(group):
            rows.append((names[k], float(t_s), *cells, *extra(cells[1], k)))
    return CsvTable(TIME_INDICES_HEADER + run_columns(analyses), rows)


#: The header of an aggregated-indices table (the motion job's, a path's).
AGGREGATED_HEADER = ("output", "parameter", "method", "S1", "ST", "percent", "runs")


def aggregated_rows(label: str, names: Sequence[str], method: str, first, total, runs: int):
    """The :data:`AGGREGATED_HEADER` rows of one aggregate (``first``, ``total``: (D,)
    aggregated S1 and ST of output ``label``), one per input; ``percent`` of ST as in
    :func:`sensitivity_percent`."""
    share = sensitivity_percent(np.stack([first, first, total, total])[:, None], "ST")[0]
    return [
        (label, name, method, float(first[j]), float(total[j]), float(share[j]), runs)
        for j, name in enumerate(names)
    ]

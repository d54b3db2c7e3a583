"""The motion job's indices per time, its CSV tables, terminal view and sweep figures.

Indices come from the sensitivity package's estimators
(:func:`planar_tui.sensitivity.engine.analyse`: Sobol' with SALib's bootstrap, eFAST) on
the outputs of each method's robots at each time of ``at_s``, and their point estimates
(:func:`~planar_tui.sensitivity.engine.point_indices`) at every other recorded time, with
the aggregated indices over each trajectory (:func:`index_trajectories`). An output that
does not vary over those robots (a joint that cannot move, a time-0 angle) has no index:
its indices are undefined, empty cells in the indices CSV (``Analysis.defined``; zeros in
the arrays, and at ``at_s`` a note), never a NaN or a warning.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from planar_tui.csvio import CsvTable
from planar_tui.motion.engine import output_labels
from planar_tui.sensitivity import engine
from planar_tui.sensitivity.aggregate import trajectory_aggregates
from planar_tui.sensitivity.results import (
    Analysis,
    aggregated_rows,
    sensitivity_percent,
    time_indices_table,
)

#: The band's statistics, in CSV column order.
BAND_STATISTICS = ("mean", "std", "p5", "p50", "p95")


def band_header(names: Sequence[str]) -> tuple[str, ...]:
    """``t_s``, then per output ``NAME_mean, NAME_std, NAME_p5, NAME_p50, NAME_p95``."""
    return ("t_s", *(f"{name}_{stat}" for name in names for stat in BAND_STATISTICS))


def band_table(t_s: np.ndarray, band: np.ndarray, names: Sequence[str]) -> CsvTable:
    """The band CSV: one row per recorded time; ``band`` is (R, 5, n_out)."""
    columns = band.transpose(0, 2, 1).reshape(len(t_s), -1)  # per output its 5 statistics
    return CsvTable(band_header(names), np.column_stack([t_s, columns]))


def indices_table(analyses: Sequence, names: Sequence[str]) -> CsvTable:
    """The indices CSV: one row per time × output × parameter × method (the time is the
    analyses' ``speed_rad_s`` slot, see :func:`analyse_times`)."""
    return time_indices_table(analyses, names)


def analyse_times(design, at_outputs, spec, problem, labels, methods, progress):
    """``(analyses, notes)``: an :class:`~planar_tui.sensitivity.results.Analysis` per time
    of ``at_outputs`` ({step: (S, n_out)}) and index method; outputs without variance over
    a method's robots have no indices (``defined`` false, zeros in the arrays) and a
    note."""

    analyses, notes = [], []
    num_vars = problem.num_vars
    for step in sorted(at_outputs):
        t_s = step * spec.step_s
        for method in methods:
            outputs = at_outputs[step][design.rows[method]]
            varying = np.ptp(outputs, axis=0) > 0
            indices = np.zeros((4, outputs.shape[1], num_vars))
            detail = f"{method} t = {t_s:g} s"
            if varying.any():
                chosen = np.ascontiguousarray(outputs[:, varying])
                indices[:, varying] = engine.analyse(
                    method, chosen, num_vars, spec.seed, progress, detail
                )
            else:
                progress.advance(1.0, detail)
            for k in np.flatnonzero(~varying):
                notes.append(
                    f"{labels[k]} at t = {t_s:g} s does not vary over the {method} robots: "
                    "no variance to apportion, no index (empty in the CSV)"
                )
            percent = sensitivity_percent(indices, "ST")
            analyses.append(
                Analysis(
                    method,
                    "",
                    t_s,
                    problem.names,
                    indices,
                    percent,
                    tuple(labels),
                    f"t = {t_s:g} s",
                    runs=outputs.shape[0],
                    defined=varying,
                )
            )
    return analyses, tuple(notes)


def aggregate_rows(
    labels, names, method: str, aggregated, overall, runs: int
) -> list[tuple[Any, ...]]:
    """The aggregated-indices rows of one method: each output's trajectory (``aggregated``
    (M, 2, D)), then ``all outputs`` (``overall`` (2, D))."""
    summary = [*zip(labels, aggregated, strict=True), ("all outputs", overall)]
    return [
        row
        for label, (first, total) in summary
        for row in aggregated_rows(label, names, method, first, total, runs)
    ]


def index_trajectories(design, every, variances, at_analyses, spec, problem, labels):
    """``(analyses, rows)`` of the Sobol' and eFAST robots at every stop: ``every``
    {method: {step: (4, M, D) point indices}} (:func:`~planar_tui.sensitivity.engine.point_indices`),
    replaced at the ``at_s`` steps by ``at_analyses`` (with their confidence intervals);
    ``variances`` {method: {step: (M,)}} the outputs' variances over independent uniform
    robots, the weights of each method's aggregated rows (:func:`aggregate_rows`); an
    output of zero variance at a stop has no indices there (``defined``)."""
    at = {(a.method, a.speed_rad_s): a for a in at_analyses}
    analyses, rows = [], []
    for method, by_step in every.items():
        runs = len(design.unit[design.rows[method]])
        steps = sorted(by_step)
        for step in steps:
            t_s = step * spec.step_s
            analysis = at.get((method, t_s))
            if analysis is None:
                indices = by_step[step]
                analysis = Analysis(
                    method,
                    "",
                    t_s,
                    problem.names,
                    indices,
                    sensitivity_percent(indices, "ST"),
                    tuple(labels),
                    f"t = {t_s:g} s",
                    runs=runs,
                    defined=variances[method][step] > 0,
                )
            analyses.append(analysis)
        indices = np.stack([a.indices[[0, 2]] for a in analyses[-len(steps) :]], axis=1)
        weights = np.stack([variances[method][step] for step in steps])
        aggregated, overall = trajectory_aggregates(indices, weights)
        rows += aggregate_rows(labels, problem.names, method, aggregated, overall, runs)
    return analyses, rows


def band_grid(result, row: int = -1):
    """``(table, width)``: a rich table of every output's band statistics at recorded row
    ``row`` (5 significant digits) with exact, unshrinkable columns, and its width."""
    from rich import box
    from rich.table import Table

    rows = [
        [label, *(f"{v:.5g}" for v in result.band[row, :, k])]
        for k, label in enumerate(output_labels(result.names))
    ]
    header = ["output", *BAND_STATISTICS]
    widths = [max(len(cell) for cell in column) for column in zip(header, *rows, strict=True)]
    table = Table(box=box.SIMPLE_HEAD, show_edge=False, pad_edge=False, padding=(0, 1, 0, 0))
    for c, (title, width) in enumerate(zip(header, widths, strict=True)):
        table.add_column(title, justify="left" if c == 0 else "right", width=width, no_wrap=True)
    for cells in rows:
        table.add_row(*cells)
    # the cells, a space of padding and a space of the box's divider between two columns
    return table, sum(widths) + 2 * (len(widths) - 1)


def render(job, result, console) -> None:
    """The terminal view: the band at the last recorded time, then paper A's Table 4
    shape per time (percent of ST; fitted to the width, never cut), then the notes."""
    from rich.text import Text

    from planar_tui.sensitivity.tables import VIEWS, fit_tables

    console.print(f"{result.robot_label}: {job.label}", style="bold", markup=False)
    console.print(
        f"{result.robots} robots integrated on {result.device}",
        markup=False,
        highlight=False,
        soft_wrap=True,
    )
    console.print(
        Text(f"band over the robots at t = {result.t_s[-1]:g} s; angles rad, tip m", style="bold")
    )
    console.print(band_grid(result)[0])
    if result.analyses:
        console.print(fit_tables(result.analyses, VIEWS[0], console.width, "ST").renderable)
    for note in result.notes:
        console.print(f"note: {note}", markup=False, highlight=False)


def dominant_parameters(result) -> dict[str, str]:
    """Per output, the input of largest total index (first index method, last time);
    ``""`` where the output does not vary."""
    if not result.analyses:
        return {}
    last_t = result.analyses[-1].speed_rad_s
    analysis = next(a for a in result.analyses if a.speed_rad_s == last_t)
    total = analysis.indices[2]
    return {
        name: (analysis.names[int(total[k].argmax())] if total[k].any() else "")
        for k, name in enumerate(result.names)
    }


def figures(result) -> dict[str, Any]:
    """Sweep-row columns: ``NAME_mean``, ``NAME_std`` at the last recorded time per output,
    then ``NAME_dominant`` (see :func:`dominant_parameters`) when indices were computed."""
    row: dict[str, Any] = {}
    for k, name in enumerate(result.names):
        row[f"{name}_mean"] = float(result.band[-1, 0, k])
        row[f"{name}_std"] = float(result.band[-1, 1, k])
    for name, parameter in dominant_parameters(result).items():
        row[f"{name}_dominant"] = parameter
    return row

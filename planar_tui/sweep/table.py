"""The sweep CSV: one row per point, in point order, whatever order the points finished in.

Columns: ``point``, one per varied key path (named by the path, units as in the key), the
job kind's summary figures (``JobKind.point_figures``: every column any point reported, in
the order they first appear), then ``status`` (``ok`` / ``failed``; ``cancelled`` for a point a cancelled app sweep did
not run), ``message`` and
``seconds`` (the point's wall time: the one column that differs between runs). A figure
named like a varied key (a workspace sweep over ``precision_cm``) is not repeated.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from planar_tui.csvio import CsvTable
from planar_tui.sweep.worker import CANCELLED, PointOutcome

TRAILING = ("status", "message", "seconds")


def figure_columns(outcomes: Sequence[PointOutcome], paths: Sequence[str] = ()) -> list[str]:
    """Every figure any point reported, in the order they first appear (points in order),
    but those named like a varied key path (a workspace's ``precision_cm``: its column is
    already there)."""
    columns: dict[str, None] = {}
    for outcome in sorted(outcomes, key=lambda o: o.number):
        columns.update(dict.fromkeys(outcome.figures))
    return [name for name in columns if name not in paths]


def row(
    number: int, values: Sequence[Any], outcome: PointOutcome, columns: Sequence[str]
) -> list[Any]:
    """One point's row (a figure the point did not report is an empty cell, as are the
    seconds of a point not run)."""
    figures = [outcome.figures.get(name, "") for name in columns]
    seconds = "" if outcome.status == CANCELLED else round(outcome.seconds, 6)
    return [number, *values, *figures, outcome.status, outcome.message, seconds]


def sweep_table(
    paths: Sequence[str],
    values: Mapping[int, Sequence[Any]],
    outcomes: Mapping[int, PointOutcome],
) -> CsvTable:
    """The sweep's table from every point's ``values`` and ``outcomes`` (by point number)."""
    ordered = [outcomes[number] for number in sorted(outcomes)]
    columns = figure_columns(ordered, paths)
    header = ("point", *paths, *columns, *TRAILING)
    rows = [row(o.number, values[o.number], o, columns) for o in ordered]
    return CsvTable(header, rows)

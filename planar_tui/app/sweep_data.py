"""What the app's sweep dialog and sweep view compute, without any widget.

- :func:`parse_values`: the values a person types for one key path, as a sweep's
  ``values`` entry: ``-20, 0, 20`` (a list of TOML values) or ``25..35 x5`` (``from``,
  ``to``, ``count``: inclusive, evenly spaced).
- :func:`values_text`: a ``[[sweep]]`` table's ``values`` entry as the dialog shows it
  (the inverse of :func:`parse_values`).
- :func:`numeric_figures`: the columns of a sweep table that can be plotted;
  :func:`varying_figures`: those whose value changes from point to point (the outputs).
- :func:`line_series` and :func:`heat_grid`: a figure against one varied key (one series
  per combination of the other keys) or two (a grid, cells averaged when several points
  fall in one).
"""

from __future__ import annotations

import math
import re
import tomllib
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from planar_tui.csvio import CsvTable
from planar_tui.preset_writer import format_value

_RANGE = re.compile(
    r"^\s*(?P<lo>[-+]?[\d.]+(?:e[-+]?\d+)?)\s*\.\.\s*(?P<hi>[-+]?[\d.]+(?:e[-+]?\d+)?)"
    r"\s*[x×]\s*(?P<count>[-+]?\d+)\s*$",
    re.IGNORECASE,
)
#: How the values of one key are typed, for the dialog's hint.
VALUES_HINT = "values: 1, 2.5, 4 (a list) or 25..35 x5 (5 evenly spaced, ends included)"


class ValuesError(ValueError):
    """Text that is no list of values nor a range (the message says what is expected)."""


def parse_values(text: str) -> list[Any] | dict[str, Any]:
    """``text`` as a sweep ``values`` entry: ``{"from", "to", "count"}`` for ``LO..HI xN``,
    else the comma-separated TOML values (``[1, 2]`` items and quoted strings work).

    The sweep's own checks (count ≥ 1, values valid for the key) come after, in
    :func:`planar_tui.sweep.spec.build_sweep`; this only reads the text.
    """
    match = _RANGE.match(text)
    if match is not None:
        try:
            return {
                "from": float(match["lo"]),
                "to": float(match["hi"]),
                "count": int(match["count"]),
            }
        except ValueError as error:  # e.g. "1.2.3..4 x2"
            raise ValuesError(f"{text.strip()!r} is not a range ({VALUES_HINT})") from error
    if not text.strip():
        raise ValuesError(f"no values ({VALUES_HINT})")
    try:
        return list(tomllib.loads(f"v = [{text}]")["v"])
    except tomllib.TOMLDecodeError as error:
        raise ValuesError(f"{text.strip()!r} is not a list of values ({VALUES_HINT})") from error


def values_text(entry: Any) -> str:
    """A ``values`` entry as typed in the dialog: ``LO..HI xN`` for ``{from, to, count}``,
    else its items as comma-separated TOML values (``20, 30`` or ``[20, 70], [25, 65]``);
    :func:`parse_values` reads it back to the same entry."""
    if isinstance(entry, dict):
        return f"{entry['from']}..{entry['to']} x{entry['count']}"
    return ", ".join(format_value(item) for item in entry)


def _number(cell: Any) -> float | None:
    """A cell as a float, ``None`` when it holds none (text, empty, a failed point)."""
    if isinstance(cell, bool):
        return None
    if isinstance(cell, int | float):
        return float(cell)
    try:
        value = float(cell)
    except (TypeError, ValueError):
        return None
    return value if math.isfinite(value) else None


def numeric_figures(table: CsvTable, paths: Sequence[str]) -> list[str]:
    """The figure columns (not ``point``, the paths or the trailing columns) whose cells
    on the ``ok`` rows are all numbers."""
    header = list(table.header)
    status = header.index("status")
    skip = {"point", *paths, "status", "message", "seconds"}
    ok_rows = [row for row in table.rows if row[status] == "ok"]
    return [
        name
        for column, name in enumerate(header)
        if name not in skip and ok_rows and all(_number(row[column]) is not None for row in ok_rows)
    ]


def varying_figures(table: CsvTable, figures: Sequence[str]) -> list[str]:
    """The ``figures`` whose value differs between ``ok`` points (what the sweep changed:
    its outputs), in table order; an input the sweep left alone (``precision_cm``) is
    not among them."""
    header = list(table.header)
    status = header.index("status")
    ok_rows = [row for row in table.rows if row[status] == "ok"]
    return [
        name for name in figures if len({_number(row[header.index(name)]) for row in ok_rows}) > 1
    ]


@dataclass(frozen=True)
class Series:
    """A line: the figure against one key, for one combination of the other keys
    (``label``, empty when no other key varies); ``failed_x`` are the key's values at the
    points that failed."""

    label: str
    x: list[float]
    y: list[float]
    failed_x: list[float]


def _column(table: CsvTable, name: str) -> int:
    return list(table.header).index(name)


def line_series(
    table: CsvTable, paths: Sequence[str], across: str, figure: str, limit: int = 9
) -> list[Series]:
    """The figure against ``across``: one series per combination of the other keys' values
    (at most ``limit``, in order of appearance), points sorted by ``across``."""
    key, value, status = _column(table, across), _column(table, figure), _column(table, "status")
    others = [_column(table, path) for path in paths if path != across]
    groups: dict[tuple, list] = {}
    for row in table.rows:
        groups.setdefault(tuple(row[c] for c in others), []).append(row)
    series = []
    for combination, rows in list(groups.items())[:limit]:
        rows = sorted(rows, key=lambda row: _number(row[key]) or 0.0)
        good = [(row[key], row[value]) for row in rows if row[status] == "ok"]
        good = [(_number(x), _number(y)) for x, y in good]
        good = [(x, y) for x, y in good if x is not None and y is not None]
        failed = [_number(row[key]) for row in rows if row[status] != "ok"]
        label = ", ".join(
            f"{path}={cell}"
            for path, cell in zip([p for p in paths if p != across], combination, strict=True)
        )
        series.append(
            Series(
                label,
                [x for x, _ in good],
                [y for _, y in good],
                [x for x in failed if x is not None],
            )
        )
    return series


def _bins(values: list[float], limit: int) -> list[float]:
    """The distinct values when they are few, else ``limit`` bin centres over their range."""
    distinct = sorted(set(values))
    if len(distinct) <= limit:
        return distinct
    lo, hi = distinct[0], distinct[-1]
    step = (hi - lo) / limit
    return [lo + (k + 0.5) * step for k in range(limit)]


def _nearest(bins: list[float], value: float) -> int:
    return min(range(len(bins)), key=lambda k: abs(bins[k] - value))


def heat_grid(
    table: CsvTable, across: str, down: str, figure: str, limit: int = 16
) -> tuple[list[float], list[float], list[list[float | None]]]:
    """The figure over (``across``, ``down``): the axes' values (their distinct values, or
    ``limit`` bins for a sampled design) and ``grid[j][i]``, the mean of the ok points in
    that cell (``None`` where no ok point is)."""
    a, d = _column(table, across), _column(table, down)
    value, status = _column(table, figure), _column(table, "status")
    points = [(_number(row[a]), _number(row[d]), row) for row in table.rows]
    points = [(x, y, row) for x, y, row in points if x is not None and y is not None]
    xs = _bins([x for x, _, _ in points], limit)
    ys = _bins([y for _, y, _ in points], limit)
    sums = [[0.0] * len(xs) for _ in ys]
    counts = [[0] * len(xs) for _ in ys]
    for x, y, row in points:
        cell = _number(row[value]) if row[status] == "ok" else None
        if cell is not None:
            i, j = _nearest(xs, x), _nearest(ys, y)
            sums[j][i] += cell
            counts[j][i] += 1
    grid = [
        [s / c if c else None for s, c in zip(srow, crow, strict=True)]
        for srow, crow in zip(sums, counts, strict=True)
    ]
    return xs, ys, grid

"""Reading a result CSV back, and its columns as arrays, for the figure modules."""

from __future__ import annotations

import csv
import io
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from planar_tui.csvio import FORMULA_STARTS, CsvTable
from planar_tui.reader import BoundedReadError, open_bounded

#: Largest result CSV ``planar-tui plot`` reads (bytes): its cells take about ten times
#: that in memory.
MAX_CSV_BYTES = 64 * 2**20
#: Largest magnitude of a number drawn (a figure's axis ranges overflow near 1e308).
MAX_ABS_VALUE = 1e100


def _cell(text: str) -> Any:
    """A CSV cell as written by :class:`CsvTable`: a number when it reads as one, ``None``
    when empty, else the text (without the ``'`` put before a formula-like start); a
    number that is not finite or beyond :data:`MAX_ABS_VALUE` is a ``ValueError``."""
    if text == "":
        return None
    try:
        value = float(text)
    except ValueError:
        if text.startswith("'") and text[1:2] and text[1:].startswith(FORMULA_STARTS):
            return text[1:]
        return text
    if not abs(value) <= MAX_ABS_VALUE:
        raise _BadNumber(text)
    return value


class _BadNumber(ValueError):
    """A cell whose number cannot be drawn."""


def open_regular(path: Path | str, limit_bytes: int | None = None):
    """A text stream on ``path`` if it is a regular file of at most ``limit_bytes`` (:data:`MAX_CSV_BYTES`)
    (opened without blocking, so a FIFO with no writer is refused, not waited on), else a
    ``ValueError`` saying why; ``OSError`` when it cannot be opened."""
    limit_bytes = MAX_CSV_BYTES if limit_bytes is None else limit_bytes
    try:
        binary = open_bounded(path, limit_bytes, "a result CSV")
    except BoundedReadError as error:
        raise ValueError(str(error)) from None
    return io.TextIOWrapper(binary, encoding="utf-8", newline="")


def read_csv(path: Path | str) -> CsvTable:
    """The table in a CSV file (header, then rows of numbers, text and ``None``; blank
    lines skipped); ``OSError`` or ``UnicodeDecodeError`` when it cannot be read,
    ``ValueError`` when it holds no header, is no regular file, is larger than
    :data:`MAX_CSV_BYTES`, has a cell over the :mod:`csv` module's own limit (128 KiB) or a
    number that is not finite or beyond :data:`MAX_ABS_VALUE` (the message names the line
    and column)."""
    with open_regular(path) as stream:
        reader = csv.reader(stream)
        try:
            records = list(reader)
        except csv.Error as error:
            raise ValueError(f"line {reader.line_num}: {error}") from None
    if not records or not records[0]:
        raise ValueError("the file is empty (no header line)")
    header = tuple(records[0])
    rows = []
    for number, record in enumerate(records[1:], start=2):
        if not record:
            continue
        try:
            rows.append([_cell(text) for text in record])
        except _BadNumber as error:
            index = next(i for i, text in enumerate(record) if text == error.args[0])
            name = header[index] if index < len(header) else f"{index + 1}"
            raise ValueError(
                f"line {number}, column {name}: {error.args[0][:40]} is not a finite number "
                f"within ±{MAX_ABS_VALUE:g}"
            ) from None
    return CsvTable(header, rows)


def column(table: CsvTable, name: str) -> Any:
    """Column ``name`` as a float array (empty and text cells: NaN)."""
    import numpy as np

    if getattr(getattr(table.rows, "dtype", None), "kind", "") == "f":
        return np.asarray(table.rows[:, table.header.index(name)], dtype=float)
    index = table.header.index(name)
    values = []
    for row in table.rows:
        cell = row[index] if index < len(row) else None
        try:
            values.append(float(cell) if cell is not None and cell != "" else np.nan)
        except (TypeError, ValueError):
            values.append(np.nan)
    return np.array(values, dtype=float)


def text_column(table: CsvTable, name: str) -> list[str]:
    """Column ``name`` as text (numbers in their shortest form, empty cells ``""``)."""
    index = table.header.index(name)
    out = []
    for row in table.rows:
        cell = row[index] if index < len(row) else None
        if cell is None:
            out.append("")
        elif isinstance(cell, float) and cell.is_integer():
            out.append(str(int(cell)))
        else:
            out.append(str(cell))
    return out


def has_columns(header: Sequence[str], names: Sequence[str]) -> bool:
    """Whether every one of ``names`` is in ``header`` (extra columns are fine)."""
    present = set(header)
    return all(name in present for name in names)


def numbered(header: Sequence[str], prefix: str, suffix: str) -> list[str]:
    """The columns ``PREFIX1SUFFIX``, ``PREFIX2SUFFIX`` ... present, in joint order."""
    names = []
    while f"{prefix}{len(names) + 1}{suffix}" in header:
        names.append(f"{prefix}{len(names) + 1}{suffix}")
    return names

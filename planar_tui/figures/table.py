"""Reading a result CSV back, and its columns as arrays, for the figure modules."""

from __future__ import annotations

import csv
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from planar_tui.csvio import FORMULA_STARTS, CsvTable


def _cell(text: str) -> Any:
    """A CSV cell as written by :class:`CsvTable`: a number when it reads as one, ``None``
    when empty, else the text (without the ``'`` put before a formula-like start)."""
    if text == "":
        return None
    try:
        return float(text)
    except ValueError:
        if text.startswith("'") and text[1:2] and text[1:].startswith(FORMULA_STARTS):
            return text[1:]
        return text


def read_csv(path: Path | str) -> CsvTable:
    """The table in a CSV file (header, then rows of numbers, text and ``None``; blank
    lines skipped); ``OSError`` or ``UnicodeDecodeError`` when it cannot be read,
    ``ValueError`` when it holds no header."""
    with open(path, encoding="utf-8", newline="") as stream:
        records = list(csv.reader(stream))
    if not records or not records[0]:
        raise ValueError("the file is empty (no header line)")
    header = tuple(records[0])
    rows = [[_cell(text) for text in record] for record in records[1:] if record]
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

"""CSV tables and atomic file writing (temp file in the same folder, then rename)."""

from __future__ import annotations

import functools
import os
import tempfile
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any


def format_cell(value: Any) -> str:
    """One CSV cell: floats in shortest round-trip form (``repr``), so output is exact and
    byte-identical for identical results; everything else through ``str``."""
    if isinstance(value, float):
        return repr(value)
    if hasattr(value, "dtype") and getattr(value.dtype, "kind", "") == "f":
        return repr(float(value))
    return str(value)


@dataclass(frozen=True)
class CsvTable:
    """A header (column names carrying units, e.g. ``t_s``) and rows of cells."""

    header: tuple[str, ...]
    rows: Sequence[Sequence[Any]] | Any  # or a 2-D float NumPy array (the fast path)

    def lines(self) -> Iterator[str]:
        """The table as CSV lines (no quoting needed: cells never hold commas)."""
        yield ",".join(self.header)
        if getattr(getattr(self.rows, "dtype", None), "kind", "") == "f":
            # a float array: one C-level %-format per row, ``%r`` = shortest round trip
            row_format = ",".join(["%r"] * len(self.header))
            for row in self.rows.tolist():
                yield row_format % tuple(row)
            return
        for row in self.rows:
            yield ",".join(format_cell(cell) for cell in row)


@functools.cache
def _new_file_mode() -> int:
    """The mode ``open()`` would give a new file: ``0o666`` less the process umask."""
    mask = os.umask(0o022)
    os.umask(mask)
    return 0o666 & ~mask


def write_lines_atomic(path: Path | str, lines: Iterable[str]) -> Path:
    """Write ``lines`` (each followed by a newline) so that ``path`` is either the whole
    new file or untouched.

    The text goes to a temporary file in the destination folder, which is then renamed
    over ``path`` (``os.replace`` is atomic on POSIX); on any error, including
    ``KeyboardInterrupt``, the temporary file is removed. The file gets the permissions a
    plain ``open()`` would give it (an existing file keeps its own).
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    handle, temp_name = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(handle, "w", encoding="utf-8", newline="\n") as stream:
            stream.writelines(line + "\n" for line in lines)
        mode = path.stat().st_mode & 0o777 if path.is_file() else _new_file_mode()
        os.chmod(temp_name, mode)
        os.replace(temp_name, path)
    except BaseException:
        Path(temp_name).unlink(missing_ok=True)
        raise
    return path


def write_text_atomic(path: Path | str, text: str) -> Path:
    """Write ``text`` atomically (see :func:`write_lines_atomic`); it ends with a newline."""
    return write_lines_atomic(path, text.rstrip("\n").split("\n"))


def write_csv_atomic(path: Path | str, table: CsvTable) -> Path:
    """Write ``table`` atomically (see :func:`write_lines_atomic`)."""
    return write_lines_atomic(path, table.lines())

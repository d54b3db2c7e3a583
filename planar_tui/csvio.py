"""CSV tables and atomic file writing (temp file in the same folder, then rename)."""

from __future__ import annotations

import csv
import functools
import io
import math
import os
import re
import stat
import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, TextIO, cast

#: First characters that make a spreadsheet read a text cell as a formula (OWASP, "CSV
#: injection"): such a text cell is written with a leading ``'``.
FORMULA_STARTS = ("=", "+", "-", "@", "\t", "\r")


def text_cell(text: str) -> str:
    """A text cell as written: with a ``'`` before a leading ``=``, ``+``, ``-``, ``@``,
    tab or carriage return, so that no spreadsheet runs it as a formula (a robot named
    ``=1+1`` is written ``'=1+1``). Numbers are never changed."""
    return "'" + text if text.startswith(FORMULA_STARTS) else text


def _cell(value: Any) -> Any:
    """One CSV cell: NumPy scalars become Python scalars (floats keep their shortest
    round-trip form, ``str(float) == repr(float)``); ``None`` becomes an empty cell; text
    goes through :func:`text_cell`."""
    if isinstance(value, str):
        return text_cell(value)
    if hasattr(value, "item"):
        return value.item()
    return value


@dataclass(frozen=True)
class CsvTable:
    """A header (column names carrying units, e.g. ``t_s``) and rows of cells.

    Written through the standard library's :mod:`csv` module (RFC 4180 quoting: a cell
    holding a comma, a quote or a line break is quoted), one ``\\n`` per row; text cells
    that a spreadsheet would run as a formula get a leading ``'`` (:func:`text_cell`).
    """

    header: tuple[str, ...]
    rows: Sequence[Sequence[Any]] | Any  # or a 2-D float NumPy array

    def records(self) -> Iterator[list[Any]]:
        """The header, then every row, as lists of cells ready for ``csv.writer``."""
        yield list(self.header)
        if getattr(getattr(self.rows, "dtype", None), "kind", "") == "f":
            yield from cast(Any, self.rows).tolist()  # Python floats, C-level conversion
            return
        for row in self.rows:
            yield [_cell(cell) for cell in row]

    def first_non_finite_column(self) -> str | None:
        """The first column holding a NaN or an infinity, or ``None`` (one vectorised test
        for a float array or rows that test themselves, ``rows.non_finite_column()``, as
        :class:`~planar_tui.workspace.paving.levels.BoxRows` does; a pass over the cells
        otherwise)."""
        own_test = getattr(self.rows, "non_finite_column", None)
        if own_test is not None:
            index = own_test()
            return None if index is None else self.header[index]
        if getattr(getattr(self.rows, "dtype", None), "kind", "") == "f":
            import numpy as np

            finite = np.isfinite(self.rows)
            if finite.all():
                return None
            return self.header[int(np.flatnonzero(~finite.all(axis=0))[0])]
        for row in self.rows:
            for name, cell in zip(self.header, row, strict=False):
                if isinstance(cell, float) and not math.isfinite(cell):  # np.float64 too
                    return name
        return None

    def write(self, stream: TextIO) -> None:
        """Write the table as CSV to a text stream opened with ``newline=""``."""
        csv.writer(stream, lineterminator="\n").writerows(self.records())

    def lines(self) -> Iterator[str]:
        """The table as CSV text lines (a quoted cell may span lines: see :meth:`write`)."""
        buffer = io.StringIO()
        writer = csv.writer(buffer, lineterminator="\n")
        for record in self.records():
            writer.writerow(record)
            yield buffer.getvalue().removesuffix("\n")
            buffer.seek(0)
            buffer.truncate()


@functools.cache
def _new_file_mode() -> int:
    """The mode ``open()`` would give a new file: ``0o666`` less the process umask."""
    mask = os.umask(0o022)
    os.umask(mask)
    return 0o666 & ~mask


def _temporary_name(path: Path) -> Path:
    """A hidden ``.NAME.XXXXXXXX.tmp`` beside ``path``; NAME keeps at most 64 characters
    of the name, so the temporary name fits the file system whenever ``path``'s does."""
    import secrets  # here: its hashlib and random cost `planar-tui --help` 4 ms

    return path.with_name(f".{path.name[:64]}.{secrets.token_hex(4)}.tmp")


#: When this process started writing (the import of this module): a temporary file of an
#: output older than this was left by an earlier run (killed by SIGKILL, a power cut).
RUN_STARTED_S = time.time()


def _quiet(text: str) -> None:
    """Report nothing (the default :data:`notice`)."""


#: Where a removal of stale temporary files is reported (one line); the CLI prints it.
notice: Callable[[str], None] = _quiet


def _temporary_pattern(path: Path) -> re.Pattern[str]:
    """The names :func:`_temporary_name` gives temporary files of ``path``."""
    return re.compile(re.escape(f".{path.name[:64]}.") + r"[0-9a-f]{8}\.tmp")


def remove_stale_temporaries(path: Path) -> list[Path]:
    """Delete the temporary files of ``path`` that an earlier run left (the same folder,
    :func:`_temporary_name`'s pattern, regular files last changed before this run
    started), say so in one line (:data:`notice`) and return them. Nothing else is
    touched: another name, a link, a folder, or a file of a run still writing."""
    pattern = _temporary_pattern(path)
    removed = []
    try:
        entries = list(os.scandir(path.parent))
    except OSError:
        return []
    for entry in entries:
        if not pattern.fullmatch(entry.name):
            continue
        try:
            info = entry.stat(follow_symlinks=False)
            if stat.S_ISREG(info.st_mode) and info.st_mtime < RUN_STARTED_S:
                os.unlink(entry.path)
                removed.append((Path(entry.path), info.st_size))
        except OSError:
            continue
    if removed:
        size = sum(n for _, n in removed)
        names = ", ".join(p.name for p, _ in removed[:3]) + (" ..." if len(removed) > 3 else "")
        notice(
            f"note: removed {len(removed)} temporary file(s) of {path} left by an earlier, "
            f"interrupted run ({names}; {size / 2**20:.3g} MiB)"
        )
    return [p for p, _ in removed]


def write_atomic(path: Path | str, write: Callable[[Any], None], *, binary: bool = False) -> Path:
    """Write a text file (a binary one with ``binary``: a figure) by ``write(stream)`` so
    that ``path`` is either the whole new file or untouched.

    The text goes to a temporary file in the destination folder, which is then renamed
    over ``path`` (``os.replace`` is atomic on POSIX); on any error, including
    ``KeyboardInterrupt``, the temporary file is removed; those an earlier run could not
    remove (SIGKILL) go first (:func:`remove_stale_temporaries`). The file gets the
    permissions a plain ``open()`` would give it (an existing file keeps its own).
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    remove_stale_temporaries(path)
    temp: Path | None = None
    try:
        while temp is None:
            # the name is chosen before the file exists, so an interrupt (Ctrl-C, SIGTERM)
            # arriving at any point, even just as the file is created, removes it below
            temp = _temporary_name(path)
            try:
                handle = os.open(temp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
            except FileExistsError:  # another file of that name, not ours: draw again
                temp = None
        if binary:
            with os.fdopen(handle, "wb") as stream:
                write(stream)
        else:
            with os.fdopen(handle, "w", encoding="utf-8", newline="") as stream:
                write(stream)
        mode = path.stat().st_mode & 0o777 if path.is_file() else _new_file_mode()
        os.chmod(temp, mode)
        os.replace(temp, path)
    except BaseException:
        if temp is not None:
            temp.unlink(missing_ok=True)
        raise
    return path


def write_text_atomic(path: Path | str, text: str) -> Path:
    """Write ``text`` atomically (see :func:`write_atomic`); it ends with one newline."""
    return write_atomic(path, lambda stream: stream.write(text.rstrip("\n") + "\n"))


def write_csv_atomic(path: Path | str, table: CsvTable) -> Path:
    """Write ``table`` as CSV atomically (see :func:`write_atomic`)."""
    return write_atomic(path, table.write)


def write_new_text(path: Path | str, text: str) -> Path:
    """Write ``text`` to ``path``, which must not exist (:class:`FileExistsError`
    otherwise, even when another process creates it meanwhile): a temporary file in the
    same folder is hard-linked to ``path`` (``os.link`` never replaces), then removed,
    so ``path`` is the whole text or absent."""
    path = Path(path)
    temp = _temporary_name(path)
    try:
        with open(temp, "x", encoding="utf-8", newline="") as stream:
            stream.write(text)
        os.chmod(temp, _new_file_mode())
        os.link(temp, path)
    finally:
        temp.unlink(missing_ok=True)
    return path

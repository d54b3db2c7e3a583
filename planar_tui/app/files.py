"""Atomic writing of a saved preset, through the CLI's own atomic CSV writer."""

from __future__ import annotations

from pathlib import Path

from planar_tui.csvio import CsvTable, write_csv_atomic


def write_text_atomic(path: Path, text: str) -> Path:
    """Write ``text`` to ``path`` atomically (temp file, then rename).

    A one-column :class:`~planar_tui.csvio.CsvTable` whose cells are the text's lines
    prints each line unchanged, so :func:`~planar_tui.csvio.write_csv_atomic` does the
    temp-file-and-rename (and its clean-up on error) for us.
    """
    lines = text.rstrip("\n").split("\n")
    return write_csv_atomic(path, CsvTable((lines[0],), [[line] for line in lines[1:]]))

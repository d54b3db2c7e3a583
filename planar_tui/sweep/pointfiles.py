"""A sweep's point files (``point_outputs``) and the record of which of them it wrote.

The record (the *manifest*) is ``OUTPUT.point-files.txt`` beside the sweep's CSV and
checkpoint: one file name per line, appended and flushed to disk before the point file
itself is written, so that it names every file this sweep may have left in the folder.
It stays after the run (unlike the checkpoint): a later run of the same sweep starting
afresh deletes exactly the files it names, and nothing else.

Before anything runs (:func:`check_point_folder`) a sweep refuses a point folder that is
a symbolic link (or lies under one inside the output folder: its files would be written,
and deleted, elsewhere), and a folder holding ``point-*.csv`` files its record does not
name (a user's own, another sweep's): one line naming one of them.

Each point CSV has its provenance sidecar (``point-007.csv.json``,
:func:`planar_tui.provenance.point_provenance`), a point file like its CSV: recorded
before it is written (:func:`write_point_file`), deleted with the CSV when the sweep
starts afresh, looked for when it resumes (a point whose CSV or sidecar is missing runs
again), and a ``point-*.csv.json`` the record does not name is foreign (refused, never
deleted or overwritten).
"""

from __future__ import annotations

import os
import re
from pathlib import Path
from typing import Any

from planar_tui.csvio import write_atomic
from planar_tui.errors import PresetError, writing
from planar_tui.provenance import has_sidecar, sidecar_path, write_sidecar

#: The record's suffix, after the sweep CSV's name.
SUFFIX = ".point-files.txt"
#: The names point files have (``point-007.csv``, ``point-007-boxes.csv`` and their
#: sidecars ``point-007.csv.json``, ``point-007-boxes.csv.json``).
POINT_FILE = re.compile(r"^point-[0-9]+(?:-[A-Za-z0-9_.-]+)?\.csv(?:\.json)?$")
#: The patterns of the point files a folder may hold (CSVs and their sidecars).
POINT_GLOBS = ("point-*.csv", "point-*.csv.json")


def manifest_path(output: Path) -> Path:
    """Where the record of the sweep writing ``output`` lives."""
    return output.with_name(output.name + SUFFIX)


def recorded_files(manifest: Path) -> set[str]:
    """The point-file names the record holds (a line that is no point-file name, as a
    crash may cut one short, is ignored); empty when there is no record."""
    try:
        text = manifest.read_text(encoding="utf-8", errors="replace")
    except (FileNotFoundError, IsADirectoryError, NotADirectoryError):
        return set()
    return {line for line in text.splitlines() if POINT_FILE.match(line)}


def symlink_in(folder: Path, out_dir: Path) -> Path | None:
    """The first symbolic link among ``folder`` and its parents below ``out_dir``, or
    ``None`` (``out_dir`` itself is the user's choice, link or not)."""
    try:
        relative = folder.relative_to(out_dir)
    except ValueError:  # an absolute point_outputs elsewhere: check all of it
        relative, out_dir = Path(*folder.parts[1:]), Path(folder.anchor)
    current = out_dir
    for part in relative.parts:
        current = current / part
        if current.is_symlink():
            return current
    return None


def foreign_files(folder: Path, manifest: Path) -> list[Path]:
    """The ``point-*.csv`` and ``point-*.csv.json`` entries of ``folder`` that the record
    does not name, sorted."""
    if not folder.is_dir():
        return []
    mine = recorded_files(manifest)
    found = {path for pattern in POINT_GLOBS for path in folder.glob(pattern)}
    return sorted(path for path in found if path.name not in mine)


def check_point_folder(
    preset_path: Path | str, key: str, folder: Path, out_dir: Path, manifest: Path
) -> None:
    """Refuse (:class:`PresetError`, exit code 2) a point folder that is, or lies under, a
    symbolic link, or that holds ``point-*.csv`` (or ``.csv.json``) files this sweep did
    not write."""
    link = symlink_in(folder, out_dir)
    if link is not None:
        raise PresetError(
            preset_path,
            key,
            f"{link} is a symbolic link (point files would be written and deleted where it points)",
            "a real folder inside the output folder",
        )
    foreign = foreign_files(folder, manifest)
    if foreign:
        more = f" and {len(foreign) - 1} more" if len(foreign) > 1 else ""
        raise PresetError(
            preset_path,
            key,
            f"{folder} holds {foreign[0].name}{more}, which this sweep did "
            f"not write (not in {manifest.name})",
            "a folder of its own for the sweep's point files (move those files away)",
        )


class PointFileRecord:
    """The record of one run of a sweep: :meth:`start_afresh` deletes what earlier runs
    wrote; :meth:`add` records a name before its file is written."""

    def __init__(self, manifest: Path, folder: Path):
        self.manifest = manifest
        self.folder = folder
        self._known = recorded_files(manifest)

    def start_afresh(self) -> None:
        """Delete the point files the record names (regular files in the folder only;
        a link put there in their place is left alone), then empty the record. A file
        that cannot be deleted is :class:`~planar_tui.errors.OutputFailed`."""
        for name in sorted(self._known):
            path = self.folder / name
            with writing(path, "cannot delete the earlier point file"):
                if path.is_file() and not path.is_symlink():
                    path.unlink()
        self._known = set()
        if self.manifest.exists():
            self.manifest.write_text("", encoding="utf-8")

    def add(self, name: str) -> None:
        """Record ``name`` (flushed to disk) unless it is recorded already."""
        if name in self._known:
            return
        self.manifest.parent.mkdir(parents=True, exist_ok=True)
        with open(self.manifest, "a", encoding="utf-8") as stream:
            stream.write(name + "\n")
            stream.flush()
            os.fsync(stream.fileno())
        self._known.add(name)


def with_sidecars(names: list[str]) -> list[str]:
    """``names`` (point CSVs), each followed by its sidecar's name when it gets one
    (:func:`planar_tui.provenance.has_sidecar`): the files a finished point leaves."""
    return [
        made
        for name in names
        for made in [name, *([sidecar_path(name).name] if has_sidecar(name) else [])]
    ]


def write_point_file(
    path: Path, text: str, record: PointFileRecord | None, provenance: Any
) -> None:
    """Write one point CSV ``text`` at ``path`` and its sidecar ``provenance`` (a
    :class:`~planar_tui.provenance.Provenance`), each atomically and recorded first; a
    file that cannot be written is :class:`~planar_tui.errors.OutputFailed`."""
    with writing(path):
        if record is not None:
            for name in with_sidecars([path.name]):
                record.add(name)
        write_atomic(path, lambda stream: stream.write(text))
    with writing(sidecar_path(path)):
        write_sidecar(path, provenance)

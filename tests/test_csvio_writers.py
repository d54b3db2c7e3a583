"""The atomic writers' temporary files (planar_tui/csvio.py) at the level of the module:
a temporary name already taken (another writer's file) is never opened, and the sweep of
an earlier run's temporaries removes regular files only."""

from __future__ import annotations

import os
import time

import pytest

from planar_tui import csvio


def test_a_temporary_name_another_writer_holds_is_drawn_again_not_truncated(tmp_path, monkeypatch):
    """Two writers that draw the same temporary name: the second must not open (truncate,
    then rename away) the first one's file; it draws another name."""
    target = tmp_path / "out.csv"
    theirs = tmp_path / ".out.csv.0123abcd.tmp"
    theirs.write_text("the other writer's half-written table\n")  # newer than this run
    names = iter([theirs, tmp_path / ".out.csv.89abcdef.tmp"])
    monkeypatch.setattr(csvio, "_temporary_name", lambda path: next(names))
    csvio.write_text_atomic(target, "mine")
    assert target.read_text() == "mine\n"
    assert theirs.read_text() == "the other writer's half-written table\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == [theirs.name, "out.csv"]


def test_the_stale_sweep_removes_old_regular_files_only(tmp_path):
    """A link, a folder and a FIFO with a temporary's name and an old time are kept; an
    old regular file goes, a newer one (a run still writing) stays."""
    target = tmp_path / "out.csv"
    old = csvio.RUN_STARTED_S - 3600
    stale = tmp_path / ".out.csv.00000001.tmp"
    stale.write_text("left by a killed run")
    busy = tmp_path / ".out.csv.00000002.tmp"
    busy.write_text("being written")
    os.utime(busy, (time.time() + 60, time.time() + 60))
    elsewhere = tmp_path / "precious.txt"
    elsewhere.write_text("keep me")
    link = tmp_path / ".out.csv.00000003.tmp"
    link.symlink_to(elsewhere)
    folder = tmp_path / ".out.csv.00000004.tmp"
    folder.mkdir()
    fifo = tmp_path / ".out.csv.00000005.tmp"
    os.mkfifo(fifo)
    for path in (stale, link, folder, fifo, elsewhere):  # the link's target old too
        os.utime(path, (old, old), follow_symlinks=False)
    notes: list[str] = []
    original = csvio.notice
    csvio.notice = notes.append
    try:
        assert csvio.remove_stale_temporaries(target) == [stale]
    finally:
        csvio.notice = original
    assert not stale.exists() and busy.exists() and folder.is_dir()
    assert link.is_symlink() and fifo.exists() and elsewhere.read_text() == "keep me"
    assert len(notes) == 1 and "1 temporary file(s)" in notes[0] and stale.name in notes[0]


def test_write_new_text_writes_a_new_file_and_never_replaces_one(tmp_path):
    path = tmp_path / "new.txt"
    assert csvio.write_new_text(path, "first") == path
    assert path.read_text() == "first"
    with pytest.raises(FileExistsError):
        csvio.write_new_text(path, "second")
    assert path.read_text() == "first"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["new.txt"]  # no temporary left


def test_the_first_non_finite_column_of_plain_rows():
    table = csvio.CsvTable(("a", "b", "c"), [[1.0, "x", 2], [3.0, "y", float("inf")]])
    assert table.first_non_finite_column() == "c"
    assert csvio.CsvTable(("a", "b"), [[1.0, "nan"], [2, None]]).first_non_finite_column() is None

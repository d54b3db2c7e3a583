"""Atomic writing: the destination is the whole new file or untouched."""

from __future__ import annotations

import numpy as np
import pytest

from planar_tui.csvio import CsvTable, write_csv_atomic, write_text_atomic


def test_float_arrays_round_trip_exactly_in_shortest_form(tmp_path):
    values = np.array([[0.1, 1 / 3, -2.5e-300], [1e16, 7.0, np.pi]])
    path = write_csv_atomic(tmp_path / "a.csv", CsvTable(("a_m", "b_s", "c_J"), values))
    lines = path.read_text().splitlines()
    assert lines[0] == "a_m,b_s,c_J"
    assert lines[1].split(",")[0] == "0.1"
    parsed = np.array([[float(x) for x in line.split(",")] for line in lines[1:]])
    assert np.array_equal(parsed, values)


def test_mixed_rows_and_array_rows_write_the_same_text(tmp_path):
    values = np.array([[0.1, 2.0], [3.5, -4.25]])
    a = write_csv_atomic(tmp_path / "a.csv", CsvTable(("x", "y"), values))
    b = write_csv_atomic(tmp_path / "b.csv", CsvTable(("x", "y"), values.tolist()))
    assert a.read_bytes() == b.read_bytes()


def test_failure_while_writing_leaves_the_old_file_and_no_temp(tmp_path):
    path = tmp_path / "keep.csv"
    path.write_text("old\n")

    def rows():
        yield (1.0,)
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        write_csv_atomic(path, CsvTable(("x",), rows()))
    assert path.read_text() == "old\n"
    assert [p.name for p in tmp_path.iterdir()] == ["keep.csv"]


def test_text_is_written_with_one_final_newline(tmp_path):
    path = write_text_atomic(tmp_path / "sub" / "p.toml", "[robot]\nx = 1\n\n")
    assert path.read_text() == "[robot]\nx = 1\n"


def test_new_files_get_the_usual_permissions_and_old_files_keep_theirs(tmp_path):
    import os

    mask = os.umask(0o022)
    os.umask(mask)
    fresh = write_text_atomic(tmp_path / "new.csv", "a\n")
    assert fresh.stat().st_mode & 0o777 == 0o666 & ~mask
    kept = tmp_path / "old.csv"
    kept.write_text("x\n")
    kept.chmod(0o640)
    write_text_atomic(kept, "y\n")
    assert kept.stat().st_mode & 0o777 == 0o640


def test_a_later_run_removes_the_stale_temporary_files_of_its_output(tmp_path, cli):
    """A run killed by SIGKILL mid-write leaves ``.NAME.XXXXXXXX.tmp``: the next run of the
    same output removes it (and only files of that pattern, older than the run) and says
    so in one line."""
    import os
    import time

    out = tmp_path / "out"
    out.mkdir()
    stale = out / ".tq.csv.0123abcd.tmp"
    stale.write_bytes(b"x" * 1000)
    old = time.time() - 3600
    os.utime(stale, (old, old))
    kept = [
        out / ".tq.csv.0123abcd.tmp.bak",
        out / ".other.csv.0123abcd.tmp",
        out / ".tq.csv.0123ABCD.tmp",
        out / "tq.csv.0123abcd.tmp",
    ]
    for path in kept:
        path.write_text("not ours")
        os.utime(path, (old, old))
    fresh = out / ".tq.csv.fedcba98.tmp"  # a run still writing (newer than this run): kept
    fresh.write_text("busy")
    os.utime(fresh, (time.time() + 60, time.time() + 60))
    link = out / ".tq.csv.aaaaaaaa.tmp"
    link.symlink_to(tmp_path / "target")
    result = cli("torques", "paper-a-table1", "--out-dir", out, "--out", out / "tq.csv")
    assert result.exit_code == 0, result.output
    notes = [line for line in result.stderr.splitlines() if "temporary file" in line]
    assert len(notes) == 1, result.stderr
    assert ".tq.csv.0123abcd.tmp" in notes[0] and "1 temporary file(s)" in notes[0]
    assert not stale.exists()
    assert all(path.exists() for path in kept) and fresh.exists() and link.is_symlink()

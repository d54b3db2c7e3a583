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

"""Every CSV is real CSV: names holding a comma, a quote, a line break or non-ASCII text are
quoted (the standard library's csv module), so each file reads back through ``csv.reader``
with one field count and the exact cell values."""

from __future__ import annotations

import csv

import pytest

from planar_tui.csvio import CsvTable, write_csv_atomic
from tests.conftest import REPO

NAMES = ["2R, paper A Table 3", 'the "fast" arm', "two\nlines", "Rückenstütze ½ → π", "=1+1", "-x"]
#: How a name is written where it differs: a text cell a spreadsheet would run as a
#: formula gets a leading ' (docs/csv.md).
WRITTEN = {"=1+1": "'=1+1", "-x": "'-x"}


def read_back(path):
    with open(path, newline="", encoding="utf-8") as handle:
        return list(csv.reader(handle))


@pytest.mark.parametrize("name", NAMES)
def test_a_table_round_trips_through_csv_reader(tmp_path, name):
    table = CsvTable(("robot", "value_m", "count"), [(name, 0.1, 3), (name, 1e-300, 0)])
    rows = read_back(write_csv_atomic(tmp_path / "t.csv", table))
    cell = WRITTEN.get(name, name)
    assert rows == [["robot", "value_m", "count"], [cell, "0.1", "3"], [cell, "1e-300", "0"]]


def test_floats_keep_their_shortest_round_trip_form(tmp_path):
    import numpy as np

    values = np.array([[0.1, 1 / 3, -2.5e-17, 1e300]])
    rows = read_back(write_csv_atomic(tmp_path / "f.csv", CsvTable(("a", "b", "c", "d"), values)))
    assert [float(v) for v in rows[1]] == values[0].tolist()
    assert rows[1] == [repr(v) for v in values[0].tolist()]


def preset_with_names(tmp_path, name: str):
    """Every job kind, quick, with robots named ``name`` (the app's tiny preset)."""
    text = (REPO / "tests" / "data" / "app" / "tiny.toml").read_text(encoding="utf-8")
    quoted = '"' + name.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n") + '"'
    text = text.replace('name = "2R, paper A Table 3"', f"name = {quoted}")
    text = text.replace("[robot3rrr]\n", f"[robot3rrr]\nname = {quoted}\n")
    text += (
        '\n[torques]\ntheta_deg = [[0, 0], [10, 20]]\noutput = "tiny-torques.csv"\n'
        "\n[[workspace]]\njoint_limits_deg = [[20, 70], [110, 160], [245, 295]]\n"
        'precision_cm = 1.875\nform = "arc-distance"\noutput = "w2.csv"\n'
        'boxes_output = "w2-boxes.csv"\n'
    )
    text = text.replace("[workspace]\n", "[[workspace]]\n", 1)
    path = tmp_path / "names.toml"
    path.write_text(text, encoding="utf-8")
    return path


@pytest.mark.parametrize("name", NAMES)
def test_every_csv_the_cli_writes_reads_back_with_one_field_count(tmp_path, cli, name):
    out = tmp_path / "out"
    result = cli("run", preset_with_names(tmp_path, name), "--out-dir", out)
    assert result.exit_code == 0, result.output
    written = sorted(p.name for p in out.iterdir() if p.suffix == ".csv")
    assert sorted(p.name for p in out.iterdir()) == sorted(
        [*written, *(f"{n}.json" for n in written)]
    )
    assert written == [
        "tiny-sensitivity.csv",
        "tiny-simulate.csv",
        "tiny-torques.csv",
        "tiny-workspace.csv",
        "w2-boxes.csv",
        "w2.csv",
    ]
    for path in out.glob("*.csv"):
        rows = read_back(path)
        widths = {len(row) for row in rows}
        assert len(widths) == 1, (path.name, widths)
        assert len(rows) > 1
    sensitivity = read_back(out / "tiny-sensitivity.csv")
    assert sensitivity[0][0] == "robot"
    assert {row[0] for row in sensitivity[1:]} == {WRITTEN.get(name, name)}


@pytest.mark.parametrize("text", ["=1+1", "+1", "-x", "@SUM(A1)", "\tcmd"])
def test_text_cells_a_spreadsheet_would_run_get_a_leading_quote(tmp_path, text):
    table = CsvTable(("robot", "tau_Nm"), [(text, -1.5), ("plain", -0.0)])
    rows = read_back(write_csv_atomic(tmp_path / "t.csv", table))
    assert rows[1:] == [["'" + text, "-1.5"], ["plain", "-0.0"]]  # numbers untouched


def test_negative_numbers_in_float_tables_are_untouched(tmp_path):
    import numpy as np

    table = CsvTable(("a", "b"), np.array([[-1.0, -2.5e-300]]))
    assert read_back(write_csv_atomic(tmp_path / "f.csv", table))[1] == ["-1.0", "-2.5e-300"]

"""Sweeps never touch files they did not write, and a damaged checkpoint cannot crash a
resume (issue 19, items 1-2), through the public CLI."""

from __future__ import annotations

from planar_tui.errors import ExitCode
from tests.sweep_presets import TORQUES, TORQUES_BASE, write

POINTS = """[[sweep]]
job = "torques"
values."robot.masses_kg[2]" = [1.0, 2.0]
output = "s.csv"
point_outputs = "pts"
"""


def one_line(result) -> str:
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    assert "Traceback" not in result.output
    return lines[0]


def test_a_users_point_file_in_the_folder_is_refused_by_name_and_kept(tmp_path, cli):
    preset = write(tmp_path, "p.toml", TORQUES, POINTS, **TORQUES_BASE)
    out = tmp_path / "out"
    (out / "pts").mkdir(parents=True)
    (out / "pts" / "point-99.csv").write_text("mine\n")
    result = cli("sweep", preset, "--out-dir", out, "--workers", "1")
    assert result.exit_code == ExitCode.BAD_INPUT
    line = one_line(result)
    assert "point-99.csv" in line and "did not write" in line
    assert (out / "pts" / "point-99.csv").read_text() == "mine\n"
    assert not (out / "s.csv").exists()


def test_a_symlinked_point_folder_is_refused_and_the_files_it_points_to_kept(tmp_path, cli):
    preset = write(tmp_path, "p.toml", TORQUES, POINTS, **TORQUES_BASE)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (elsewhere / "point-1.csv").write_text("precious\n")
    out = tmp_path / "out"
    out.mkdir()
    (out / "pts").symlink_to(elsewhere)
    result = cli("sweep", preset, "--out-dir", out, "--workers", "1")
    assert result.exit_code == ExitCode.BAD_INPUT
    assert "symbolic link" in one_line(result)
    assert (elsewhere / "point-1.csv").read_text() == "precious\n"


def test_a_fresh_run_deletes_only_the_point_files_its_record_names(tmp_path, cli):
    preset = write(tmp_path, "p.toml", TORQUES, POINTS, **TORQUES_BASE)
    out = tmp_path / "out"
    assert cli("sweep", preset, "--out-dir", out, "--workers", "1").exit_code == 0
    assert sorted(p.name for p in (out / "pts").iterdir()) == ["point-1.csv", "point-2.csv"]
    record = out / "s.csv.point-files.txt"
    assert record.read_text().split() == ["point-1.csv", "point-2.csv"]
    (out / "pts" / "notes.txt").write_text("kept")  # no point file: not the sweep's business
    (out / "s.csv").unlink()
    one = write(tmp_path, "p.toml", TORQUES, POINTS.replace("[1.0, 2.0]", "[3.0]"),
                **TORQUES_BASE)  # fmt: skip
    assert cli("sweep", one, "--out-dir", out, "--workers", "1").exit_code == 0
    assert sorted(p.name for p in (out / "pts").iterdir()) == ["notes.txt", "point-1.csv"]
    assert record.read_text().split() == ["point-1.csv"]

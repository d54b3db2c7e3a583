"""``planar-tui export`` and ``planar-tui import``: files written whole, never replaced,
problems in one line with exit code 2."""

from __future__ import annotations

import tomllib

import pytest

from planar_tui.dynamics.robot import SerialRobot
from planar_tui.presets import load_preset
from tests.conftest import PRESETS, REPO


def one_error_line(result) -> str:
    assert result.exit_code == 2, result.output
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith("error: ")
    return lines[0]


@pytest.mark.parametrize(("format_name", "suffix"), [("mjcf", "xml"), ("urdf", "urdf")])
def test_export_then_import_is_the_presets_robot(cli, tmp_path, format_name, suffix):
    model = tmp_path / f"table1.{suffix}"
    result = cli("export", "paper-a-table1", "--format", format_name, "--out", model)
    assert result.exit_code == 0, result.output
    assert result.stdout.strip() == f"wrote {model}"
    preset = tmp_path / "table1.toml"
    result = cli("import", model, "--out", preset)
    assert result.exit_code == 0, result.output
    assert result.stderr == ""  # nothing left out: no note
    expected = load_preset(PRESETS / "paper-a-table1.toml").robots["robot"]
    assert load_preset(preset).robots == {"robot": expected}
    assert tomllib.loads(preset.read_text())["robot"]["name"] == expected.name


def test_export_of_a_jobs_own_robot(cli, tmp_path):
    model = tmp_path / "t4.urdf"
    assert cli("export", "paper-a-table4", "--robot", "sensitivity[2]", "--format", "urdf",
               "--out", model).exit_code == 0  # fmt: skip
    result = cli("import", model)  # to stdout
    assert result.exit_code == 0
    job = load_preset(PRESETS / "paper-a-table4.toml").jobs[1]
    written = tomllib.loads(result.stdout)["robot"]
    assert SerialRobot(**{k: tuple(v) if isinstance(v, list) else v
                          for k, v in written.items()}) == job.robot  # fmt: skip


def test_import_notes_go_to_stderr_and_into_the_preset(cli, tmp_path):
    preset = tmp_path / "acrobot.toml"
    result = cli("import", REPO / "tests" / "data" / "interop" / "acrobot.xml", "--out", preset)
    assert result.exit_code == 0
    assert result.stderr.startswith("note: the links are not straight along x")
    assert "# Note: the links are not straight along x" in preset.read_text()


def test_nothing_is_ever_overwritten(cli, tmp_path):
    model = tmp_path / "arm.xml"
    model.write_text("mine")
    line = one_error_line(cli("export", "paper-a-table1", "--format", "mjcf", "--out", model))
    assert line == (f"error: {model}: --out: is a file that exists: nothing is overwritten "
                    "(expected a new file name (delete or move the old one first))")  # fmt: skip
    assert model.read_text() == "mine"
    preset = tmp_path / "arm.toml"
    preset.write_text("mine")
    exported = tmp_path / "arm.urdf"
    assert cli("export", "paper-a-table1", "--format", "urdf", "--out", exported).exit_code == 0
    one_error_line(cli("import", exported, "--out", preset))
    assert preset.read_text() == "mine"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["arm.toml", "arm.urdf", "arm.xml"]


@pytest.mark.parametrize(
    ("arguments", "expected"),
    [
        (["export", "paper-a-table1", "--out", "x.xml"],
         "error: command line: --format: missing (expected mjcf or urdf)"),
        (["export", "paper-a-table1", "--format", "sdf", "--out", "x.sdf"],
         "error: command line: --format: is 'sdf' (expected mjcf or urdf)"),
        (["export", "paper-a-table1", "--format", "mjcf"],
         "error: command line: --out: missing (expected the file to write)"),
        (["export", "paper-a-table4", "--robot", "workspace", "--format", "mjcf", "--out", "x.xml"],
         "error: command line: --robot: is 'workspace', no job on a serial robot in "),
        (["export", "paper-b-table3", "--format", "mjcf", "--out", "x.xml"],
         "--robot: no serial robot: a 3-RRR is not exported"),
        (["import", "arm.step"], "error: arm.step: (file): has the suffix '.step'"),
        (["import", "arm.urdf"], "error: arm.urdf: (file): no such file"),
    ],
)  # fmt: skip
def test_bad_options_are_one_line(cli, tmp_path, monkeypatch, arguments, expected):
    monkeypatch.chdir(tmp_path)
    assert expected in one_error_line(cli(*arguments))
    assert list(tmp_path.iterdir()) == []


def test_an_import_refusal_names_the_file_and_element(cli, tmp_path):
    model = tmp_path / "arm.urdf"
    assert cli("export", "paper-a-table1", "--format", "urdf", "--out", model).exit_code == 0
    model.write_text(
        model.read_text().replace('"joint3" type="continuous"', '"joint3" type="prismatic"')
    )
    line = one_error_line(cli("import", model, "--out", tmp_path / "arm.toml"))
    assert line.startswith(f"error: {model}: line ")
    assert '<joint name="joint3">: is a prismatic joint' in line
    assert not (tmp_path / "arm.toml").exists()

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
    assert (
        cli(
            "export",
            "paper-a-table4",
            "--robot",
            "sensitivity[2]",
            "--format",
            "urdf",
            "--out",
            model,
        ).exit_code
        == 0
    )
    result = cli("import", model)  # to stdout
    assert result.exit_code == 0
    job = load_preset(PRESETS / "paper-a-table4.toml").jobs[1]
    written = tomllib.loads(result.stdout)["robot"]
    assert (
        SerialRobot(**{k: tuple(v) if isinstance(v, list) else v for k, v in written.items()})
        == job.robot
    )


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
    assert line == (
        f"error: {model}: --out: is a file that exists: nothing is overwritten "
        "(expected a new file name (delete or move the old one first))"
    )
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
        (
            ["export", "paper-a-table1", "--out", "x.xml"],
            "error: command line: --format: missing (expected mjcf or urdf)",
        ),
        (
            ["export", "paper-a-table1", "--format", "sdf", "--out", "x.sdf"],
            "error: command line: --format: is 'sdf' (expected mjcf or urdf)",
        ),
        (
            ["export", "paper-a-table1", "--format", "mjcf"],
            "error: command line: --out: missing (expected the file to write)",
        ),
        (
            [
                "export",
                "paper-a-table4",
                "--robot",
                "workspace",
                "--format",
                "mjcf",
                "--out",
                "x.xml",
            ],
            "error: command line: --robot: is 'workspace', no job on a serial robot in ",
        ),
        (
            ["export", "paper-b-table3", "--format", "mjcf", "--out", "x.xml"],
            "--robot: no serial robot: name a parallel one (a closed chain, MJCF only)",
        ),
        (["import", "arm.step"], "error: arm.step: (file): has the suffix '.step'"),
        (["import", "arm.urdf"], "error: arm.urdf: (file): no such file"),
    ],
)
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


MOTION = """
[robot]
lengths_m = [0.4, 0.3]
masses_kg = [1.0, 0.8]

[motion_uncertainty]
duration_s = 0.1
step_s = 0.02
torques_Nm = [2.0, 0.5]
samples = 16
methods = ["montecarlo", "sobol"]
tolerance_length_mm = 5.0
tolerance_mass_g = 50.0
output = "arm-motion.csv"
"""


def test_sensitivity_export_problem_writes_every_design(cli, tmp_path):
    preset = REPO / "tests" / "data" / "app" / "tiny.toml"
    runs = tmp_path / "runs"
    result = cli(
        "sensitivity",
        preset,
        "--samples",
        "16",
        "--method",
        "sobol",
        "--method",
        "efast",
        "--out-dir",
        tmp_path,
        "--export-problem",
        runs,
    )
    assert result.exit_code == 0, result.output
    for method in ("sobol", "efast"):
        assert sorted(p.name for p in (runs / method).iterdir()) == [
            "X.npy",
            "Y.npy",
            "problem.json",
            "run.json",
        ]
    # a second run would replace them: refused before the job runs, nothing written
    again = tmp_path / "again"
    line = one_error_line(
        cli("sensitivity", preset, "--samples", "16", "--out-dir", again, "--export-problem", runs)
    )
    assert "--export-problem: is a file that exists: nothing is overwritten" in line
    assert not again.exists()


def test_motion_netcdf_and_export_problem(cli, tmp_path):
    import xarray as xr

    preset = tmp_path / "arm.toml"
    preset.write_text(MOTION)
    result = cli(
        "motion",
        preset,
        "--out-dir",
        tmp_path,
        "--format",
        "netcdf",
        "--export-problem",
        tmp_path / "runs",
    )
    assert result.exit_code == 0, result.output
    assert (tmp_path / "arm-motion.csv").exists()  # CSV stays
    with xr.open_dataset(tmp_path / "arm-motion.nc", engine="h5netcdf") as data:
        assert data.attrs["job"] == "arm:motion_uncertainty"
        assert data.attrs["seed"] == 42 and data.attrs["samples"] == 16
        assert data["band"].shape == (6, 4, 5)
    assert (tmp_path / "runs" / "montecarlo" / "Y.npy").exists()
    assert (tmp_path / "runs" / "sobol" / "Y.npy").exists()
    line = one_error_line(cli("motion", preset, "--out-dir", tmp_path, "--format", "netcdf"))
    assert line.startswith(f"error: {tmp_path / 'arm-motion.nc'}: --format: is a file that exists")


def test_a_format_other_than_csv_or_netcdf_is_one_line(cli, tmp_path):
    preset = tmp_path / "arm.toml"
    preset.write_text(MOTION)
    line = one_error_line(cli("motion", preset, "--out-dir", tmp_path, "--format", "xlsx"))
    assert line == "error: command line: --format: is 'xlsx' (expected csv or netcdf)"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["arm.toml"]


def test_an_unwritable_output_is_one_line(cli, tmp_path):
    """A path under a file (no folder can be made there, even for root)."""
    blocker = tmp_path / "notes.txt"
    blocker.write_text("mine")
    model = blocker / "arm.xml"
    line = one_error_line(cli("export", "paper-a-table1", "--format", "mjcf", "--out", model))
    assert line.startswith(f"error: {model}: ")
    assert "is not a writable folder" in line
    assert blocker.read_text() == "mine"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["notes.txt"]

"""Every malformed preset gets one line ``error: FILE: key: problem (expected ...)``,
exit code 2, no traceback, and no output file created or truncated."""

from __future__ import annotations

import pytest

from tests.conftest import PRESETS

TABLE1 = (PRESETS / "paper-a-table1.toml").read_text()


def edited(old: str, new: str, count: int = 1) -> str:
    """The Table 1 preset with ``old`` replaced by ``new`` (which must occur)."""
    assert old in TABLE1, old
    return TABLE1.replace(old, new, count)


CASES = {
    "toml syntax": (edited("[robot]", "[robot"), "(syntax)", "invalid TOML"),
    "unknown table": (edited("[torques]", "[torque]"), "torque", "did you mean torques?"),
    "unknown key": (
        edited("duration_s = 1.0", "durations_s = 1.0"),
        "simulate[1].durations_s",
        "did you mean duration_s?",
    ),
    "missing key": (edited("duration_s = 1.0\n", ""), "simulate[1].duration_s", "missing key"),
    "robot table misspelt": (
        edited('[robot]\nname = "6R-PSM, paper A Table 1"', '[robot_]\nname = "x"'),
        "robot_",
        "unknown table",
    ),
    "missing robot": (
        TABLE1[TABLE1.index("[[simulate]]") :],
        "simulate[1]",
        "no robot for this job (expected a [robot] table or a [simulate.robot] table)",
    ),
    "wrong type": (edited("step_s = 1e-4", 'step_s = "fast"'), "simulate[1].step_s", "is a string"),
    "wrong type bool": (edited("every = 10", "every = true"), "simulate[1].every", "is a boolean"),
    "length != n": (
        edited("masses_kg = [0.484, 0.484, ", "masses_kg = [0.484, "),
        "robot.masses_kg",
        "has 5 values (expected 6, one per link)",
    ),
    "job list length != n": (
        edited("torques_Nm = [2.0, 0.3, 0.1, 0.03, 0.03, 0.001]", "torques_Nm = [2.0]"),
        "simulate[1].torques_Nm",
        "has 1 values",
    ),
    "rows != n": (
        edited("theta_deg = [[0, 0, 0, 0, 0, 0],", "theta_deg = [[0, 0],"),
        "torques.theta_deg",
        "row 1 has 2 values",
    ),
    "row count mismatch": (
        edited(
            "alpha_deg_s2 = [[0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0]]",
            "alpha_deg_s2 = [[0, 0, 0, 0, 0, 0]]",
        ),
        "torques.alpha_deg_s2",
        "has 1 rows",
    ),
    "zero length": (
        edited("lengths_m = [0.25,", "lengths_m = [0.0,"),
        "robot.lengths_m",
        "item 1 is 0.0, must be > 0",
    ),
    "negative mass": (
        edited("masses_kg = [0.484,", "masses_kg = [-0.484,"),
        "robot.masses_kg",
        "must be > 0",
    ),
    "zero inertia": (
        edited("inertias_kgm2 = [2.54e-3,", "inertias_kgm2 = [0,"),
        "robot.inertias_kgm2",
        "must be > 0",
    ),
    "nan mass": (
        edited("masses_kg = [0.484,", "masses_kg = [nan,"),
        "robot.masses_kg",
        "not a finite number",
    ),
    "inf duration": (
        edited("duration_s = 1.0", "duration_s = inf"),
        "simulate[1].duration_s",
        "not a finite number",
    ),
    "negative gravity": (
        edited("gravity_m_s2 = 9.81", "gravity_m_s2 = -9.81"),
        "robot.gravity_m_s2",
        "below the minimum",
    ),
    "empty lengths": (
        edited("lengths_m = [0.25, 0.25, 0.20, 0.20, 0.15, 0.15]", "lengths_m = []"),
        "robot.lengths_m",
        "is empty",
    ),
    "step <= 0": (edited("step_s = 1e-4", "step_s = 0"), "simulate[1].step_s", "must be > 0"),
    "duration <= 0": (
        edited("duration_s = 1.0", "duration_s = -1.0"),
        "simulate[1].duration_s",
        "must be > 0",
    ),
    "step > duration": (
        edited("step_s = 1e-4", "step_s = 2.0"),
        "simulate[1].step_s",
        "longer than duration_s",
    ),
    "every < 1": (
        edited("every = 10", "every = 0"),
        "simulate[1].every",
        "expected an integer >= 1",
    ),
    "absolute output": (
        edited('output = "table1-6r-torques.csv"', 'output = "/tmp/x.csv"'),
        "torques.output",
        "relative to the output folder",
    ),
    "job robot unknown key": (
        edited(
            "[[simulate]]                               # free fall",
            "[[simulate]]\n[simulate.robot]\nlengths_m = [1.0]\nmasses_kg = [1.0]\nmass_kg = 1\n[[simulate]]  # free fall",
        ),
        "simulate[2].robot.mass_kg",
        "unknown key",
    ),
}


@pytest.mark.parametrize("case", list(CASES))
def test_bad_preset_is_one_clear_line_exit_2_and_nothing_written(case, tmp_path, cli):
    text, key, problem = CASES[case]
    preset = tmp_path / "bad.toml"
    preset.write_text(text)
    out_dir = tmp_path / "out"
    out_dir.mkdir()
    existing = out_dir / "table1-6r-torques.csv"
    existing.write_text("keep me\n")

    result = cli("run", preset, "--out-dir", out_dir)

    assert result.exit_code == 2
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith(f"error: {preset}: {key}"), lines[0]
    assert problem in lines[0]
    assert "Traceback" not in result.output + result.stderr
    assert sorted(p.name for p in out_dir.iterdir()) == ["table1-6r-torques.csv"]
    assert existing.read_text() == "keep me\n"


def test_missing_preset_file_names_the_bundled_ones(tmp_path, cli):
    result = cli("simulate", tmp_path / "nope.toml")
    assert result.exit_code == 2
    assert result.stderr.startswith(f"error: {tmp_path / 'nope.toml'}: (file): no such file")
    assert "paper-a-table1" in result.stderr


def test_a_bad_preset_among_several_stops_before_any_job_runs(tmp_path, cli):
    bad = tmp_path / "bad.toml"
    bad.write_text(CASES["negative mass"][0])
    result = cli("run", PRESETS / "paper-a-table1.toml", bad, "--out-dir", tmp_path / "out")
    assert result.exit_code == 2
    assert not (tmp_path / "out").exists()


def test_command_without_such_jobs_is_an_error(tmp_path, cli):
    preset = tmp_path / "only-torques.toml"
    start = TABLE1.index("[[simulate]]")
    preset.write_text(TABLE1[:start] + TABLE1[TABLE1.index("[torques]") :])
    result = cli("simulate", preset, "--out-dir", tmp_path)
    assert result.exit_code == 2
    assert f"{preset}: simulate: no [simulate] job in this preset" in result.stderr

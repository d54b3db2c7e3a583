"""The ``[[path5r]]`` job: its CSV from the command line, the working mode taken from the
robot, the feed-forward check, a failing path (exit 1) and bad input (exit 2)."""

from __future__ import annotations

import csv

import numpy as np
import pytest

ROBOT = """[robot5r]
working_mode = "+-"
proximal_mass_kg = 1.0
distal_mass_kg = 0.8
proximal_inertia_kgm2 = 0.02
distal_inertia_kgm2 = 0.02
end_mass_kg = 0.5
gravity_m_s2 = 9.81
"""
JOB = """[[path5r]]
from_pose = [0, 60]
to_pose = [10, 65]
steps = 200
feed_forward = true
output = "f.csv"
"""


def run(cli, tmp_path, text):
    preset = tmp_path / "f.toml"
    preset.write_text(text, encoding="utf-8")
    return preset, cli("run", preset, "--out-dir", tmp_path / "out")


def test_the_csv_and_the_feed_forward_check(cli, tmp_path):
    _, result = run(cli, tmp_path, ROBOT + JOB)
    assert result.exit_code == 0, result.output
    with open(tmp_path / "out" / "f.csv", newline="") as handle:
        rows = list(csv.reader(handle))
    assert rows[0] == [
        "t_s",
        "x_cm",
        "y_cm",
        "theta1_rad",
        "theta1_rad_s",
        "theta1_rad_s2",
        "theta2_rad",
        "theta2_rad_s",
        "theta2_rad_s2",
        "tau1_Nm",
        "tau2_Nm",
        "power1_W",
        "power2_W",
    ]
    values = np.array(rows[1:], dtype=float)
    assert len(values) == 201
    # at rest at the start, in the mode +-: each motor holds against gravity alone,
    # symmetric design and pose: mirror torques
    assert values[0, 9] == pytest.approx(-values[0, 10], rel=1e-12)
    summary = " ".join(result.output.split())
    assert "feed-forward: deviation" in summary
    deviation = float(summary.split("feed-forward: deviation ")[1].split(",")[0])
    assert deviation < 1e-8


def test_a_path_out_of_reach_fails_naming_the_time(cli, tmp_path):
    preset, result = run(cli, tmp_path, ROBOT + JOB.replace("[10, 65]", "[0, 120]"))
    assert result.exit_code == 1, result.output
    lines = [line for line in result.stderr.splitlines() if line.startswith("error:")]
    assert len(lines) == 1, result.stderr
    assert f"{preset}: path5r[1]: the path fails at t = " in lines[0]
    assert "cannot close" in lines[0] or "singularity" in lines[0]


@pytest.mark.parametrize(
    "old, new, key",
    [
        ("[0, 60]", "[0, 60, 0]", "path5r[1].from_pose"),
        ("steps = 200", "steps = 2000000", "path5r[1].steps"),
        ("feed_forward = true", "feed_forward = 1", "path5r[1].feed_forward"),
        ("steps = 200", "elbow = [1, 1, 1]", "path5r[1].elbow"),
    ],
)
def test_bad_input_is_one_line_exit_2(cli, tmp_path, old, new, key):
    preset, result = run(cli, tmp_path, ROBOT + JOB.replace(old, new))
    assert result.exit_code == 2, result.output
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"error: {preset}: {key}: "), result.stderr
    assert not (tmp_path / "out").exists()


def test_a_negative_end_mass_is_refused(cli, tmp_path):
    preset, result = run(
        cli, tmp_path, ROBOT.replace("end_mass_kg = 0.5", "end_mass_kg = -1") + JOB
    )
    assert result.exit_code == 2
    assert result.stderr.startswith(f"error: {preset}: robot5r.end_mass_kg: ")


def test_the_working_mode_comes_from_elbow_or_the_robot(cli, tmp_path):
    """With `working_mode = "any"` and both modes within the limits at from_pose the job
    asks for `elbow` (exit 2); `elbow = [1, -1]` gives the robot's "+-" run's torques."""
    any_mode = ROBOT.replace('working_mode = "+-"', 'working_mode = "any"')
    preset, result = run(cli, tmp_path, any_mode + JOB)
    assert result.exit_code == 2, result.output
    assert result.stderr.startswith(f"error: {preset}: path5r[1].elbow: is not given and leg 1")
    _, result = run(
        cli, tmp_path, any_mode + JOB.replace("steps = 200", "steps = 200\nelbow = [1, -1]")
    )
    assert result.exit_code == 0, result.output
    chosen = (tmp_path / "out" / "f.csv").read_text()
    (tmp_path / "robot").mkdir()
    _, result = run(cli, tmp_path / "robot", ROBOT + JOB)
    assert result.exit_code == 0, result.output
    assert (tmp_path / "robot" / "out" / "f.csv").read_text() == chosen

"""A path job's ``constant_efforts``: the forward dynamics from rest under constant
actuator efforts, written to ``OUTPUT-forward.csv``.

Checked against what does not share the code under test: at rest without gravity and
efforts nothing moves (every robot kind); without gravity the actuators' work
``sum e_i (theta_i(T) - theta_i(0))`` equals the kinetic energy at ``T`` of the Lagrange
reference's bodies (:mod:`tests.lagrange_planar`, its own inverse kinematics and
velocities from the CSV's poses and rates); a platform pushed out of the workspace ends
the CSV there (a result, exit 0); bad input is refused (exit 2, one line).
"""

from __future__ import annotations

import csv
import re

import numpy as np
import pytest

from tests.conftest import PRESETS
from tests.test_path3rrr import JOB as RRR_JOB
from tests.test_path3rrr import ROBOT as RRR_ROBOT
from tests.test_path5r import JOB as FIVEBAR_JOB
from tests.test_path5r import ROBOT as FIVEBAR_ROBOT
from tests.test_path_prismatic import PRR_PRESET


def weightless(text: str, efforts: str, steps: int = 10) -> str:
    """A test preset without gravity, plot or feed-forward, with ``steps`` steps and
    ``constant_efforts = efforts``."""
    text = re.sub(r"gravity_m_s2 = [0-9.]+", "gravity_m_s2 = 0.0", text)
    text = re.sub(r"\n(plot|feed_forward) = [^\n]*", "", text)
    text = re.sub(r"\nsteps = \d+", f"\nsteps = {steps}", text)
    return re.sub(r"\n(output = [^\n]*)", rf"\nconstant_efforts = {efforts}\n\1", text)


def run(cli, tmp_path, text):
    preset = tmp_path / "p.toml"
    preset.write_text(text, encoding="utf-8")
    return preset, cli("run", preset, "--out-dir", tmp_path / "out")


def read(path) -> tuple[list[str], np.ndarray]:
    with open(path, newline="", encoding="utf-8") as handle:
        rows = list(csv.reader(handle))
    return rows[0], np.array(rows[1:], dtype=float)


KINDS = {
    "3rrr": (RRR_ROBOT + RRR_JOB, "[0, 0, 0]", "p"),
    "3rpr": ((PRESETS / "path-3rpr.toml").read_text(encoding="utf-8"), "[0, 0, 0]", "path-3rpr"),
    "3prr": (PRR_PRESET, "[0.0, 0.0, 0.0]", "prr"),
    "5r": (FIVEBAR_ROBOT + FIVEBAR_JOB, "[0, 0]", "f"),
}


@pytest.mark.parametrize("kind", KINDS)
def test_without_gravity_and_efforts_the_platform_stays_at_rest(cli, tmp_path, kind):
    text, zeros, stem = KINDS[kind]
    _, result = run(cli, tmp_path, weightless(text, zeros))
    assert result.exit_code == 0, result.output
    header, values = read(tmp_path / "out" / f"{stem}-forward.csv")
    pose = ["x_cm", "y_cm"] + (["phi_deg"] if kind != "5r" else [])
    assert header == ["t_s", *pose, *(f"{name}_s" for name in pose)]
    assert values.shape == (11, 1 + 2 * len(pose))
    start = re.search(r"from_pose = \[([^\]]*)\]", text)
    assert start is not None
    expected = [float(v) for v in start.group(1).split(",")]
    np.testing.assert_allclose(values[0, 1 : 1 + len(pose)], expected, rtol=1e-14)
    assert np.all(values[:, 1 : 1 + len(pose)] == values[0, 1 : 1 + len(pose)])  # exactly
    assert np.all(values[:, 1 + len(pose) :] == 0.0)


def test_the_actuators_work_becomes_kinetic_energy(cli, tmp_path):
    """Zero gravity, constant torques from rest: ``sum tau_i (theta_i(T) - theta_i(0))``
    equals the kinetic energy at ``T`` of the full-coordinate Lagrange model (its own
    closed-form inverse kinematics), to RK4 accuracy."""
    from planar_tui.batch import prepare_jobs
    from planar_tui.presets import load_preset
    from tests.lagrange_planar import rr_coordinates, rr_system
    from tests.test_parallel_dynamics_lagrange import rrr_legs

    torques = np.array([0.02, -0.015, 0.01])
    robot_text = RRR_ROBOT.replace(
        "platform_mass_kg",
        "proximal_inertia_kgm2 = 0.0045\ndistal_inertia_kgm2 = 0.003\nplatform_mass_kg",
    )
    text = weightless(robot_text + RRR_JOB, str(torques.tolist()), steps=100)
    text = text.replace("duration_s = 0.5", "duration_s = 0.1")
    preset, result = run(cli, tmp_path, text)
    assert result.exit_code == 0, result.output
    _, values = read(tmp_path / "out" / "p-forward.csv")
    (job,) = prepare_jobs(load_preset(preset).jobs_of("path3rrr"))
    legs = rrr_legs(job.robot, (1, -1, -1))
    system = rr_system(legs, (0.6, 0.4), (0.0045, 0.003), (1.5, 0.025), 0.0)
    scale = np.array([0.01, 0.01, np.pi / 180.0])
    first = rr_coordinates(legs, values[0, 1:4] * scale)
    last = rr_coordinates(legs, values[-1, 1:4] * scale)
    kinetic = system.energy(last, system.velocities(last, values[-1, 4:7] * scale))
    theta = np.array([[q[6 * i + 2] for i in range(3)] for q in (first, last)])
    work = torques @ (theta[1] - theta[0])
    assert kinetic > 1e-6  # the platform moved
    assert abs(values[-1, 1:4] - values[0, 1:4]).max() > 0.01
    assert work == pytest.approx(kinetic, rel=1e-9)  # measured 7e-13


def test_a_platform_pushed_out_of_the_workspace_ends_the_csv_there(cli, tmp_path):
    """The rows stop at the last step before the failing time the summary names; a
    platform that stays inside runs to ``duration_s``."""
    from planar_tui.batch import prepare_jobs, run_job
    from planar_tui.presets import load_preset

    preset = tmp_path / "p.toml"
    results = []
    for efforts in ("[3, 3, 3]", "[0, 0, 0]"):
        preset.write_text(weightless(RRR_ROBOT + RRR_JOB, efforts, steps=50), encoding="utf-8")
        (job,) = prepare_jobs(load_preset(preset).jobs_of("path3rrr"))
        results.append(run_job(job))
    pushed, still = results
    values = np.asarray(pushed.extra_tables["forward"].rows)
    assert 1 < len(values) < 51
    np.testing.assert_allclose(values[:, 0], np.arange(len(values)) * 0.01, atol=1e-15)
    stop = re.search(r"leaves the workspace at t = ([0-9.e-]+) s", pushed.summary)
    assert stop is not None, pushed.summary
    assert values[-1, 0] <= float(stop.group(1)) <= values[-1, 0] + 0.01
    assert len(still.extra_tables["forward"].rows) == 51
    assert "constant efforts: to t = 0.5 s" in still.summary


@pytest.mark.parametrize(
    ("efforts", "words"),
    [
        ("[1, 2]", "expected 3 efforts in N m"),
        ('[1, "a", 2]', "number"),
        ("[1, 2, 3, 4]", "expected 3 efforts in N m"),
    ],
)
def test_bad_constant_efforts_are_refused_in_one_line(cli, tmp_path, efforts, words):
    preset, result = run(cli, tmp_path, weightless(RRR_ROBOT + RRR_JOB, efforts))
    assert result.exit_code == 2, result.output
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith(f"error: {preset}: path3rrr[1].constant_efforts: "), lines[0]
    assert words in lines[0]
    assert not (tmp_path / "out").exists()


def test_the_five_bar_takes_two_efforts(cli, tmp_path):
    preset, result = run(cli, tmp_path, weightless(FIVEBAR_ROBOT + FIVEBAR_JOB, "[0, 0, 0]"))
    assert result.exit_code == 2, result.output
    assert result.stderr.startswith(f"error: {preset}: path5r[1].constant_efforts: ")
    assert "(expected 2 efforts in N m, one per actuator)" in result.stderr


def test_the_constant_efforts_run_counts_in_the_time_estimate(cli, tmp_path, monkeypatch):
    """1 000 forward-dynamics steps are estimated at 2 s: over a limit of 1 s the job is
    refused up front (exit 2, one line on ``steps``); without ``constant_efforts`` it is
    not."""
    import planar_tui.limits

    monkeypatch.setattr(planar_tui.limits, "MAX_JOB_SECONDS", 1.0)
    preset, result = run(cli, tmp_path, weightless(RRR_ROBOT + RRR_JOB, "[0, 0, 0]", 1000))
    assert result.exit_code == 2, result.output
    assert result.stderr.startswith(f"error: {preset}: path3rrr[1].steps: is 1,000: the path ")
    from planar_tui.batch import prepare_jobs
    from planar_tui.presets import load_preset
    from planar_tui.registry import JOB_KINDS

    preset.write_text(RRR_ROBOT + RRR_JOB.replace("steps = 20", "steps = 1000"))
    (job,) = prepare_jobs(load_preset(preset).jobs_of("path3rrr"))
    assert JOB_KINDS["path3rrr"].estimate(job)[1] < 1.0

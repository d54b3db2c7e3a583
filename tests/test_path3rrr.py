"""The ``[[path3rrr]]`` job: its CSV, summary and figures from the command line, the
bundled preset, a path that leaves the workspace (exit 1, the time named), bad input
(exit 2, one line), and the forward dynamics driven by the path's own efforts."""

from __future__ import annotations

import csv
import dataclasses

import numpy as np
import pytest

from planar_tui.workspace.path.forward import simulate
from planar_tui.workspace.path.job import pose_si
from planar_tui.workspace.path.quintic import quintic, sample_times
from planar_tui.workspace.rrr.mechanism import MECHANISM
from planar_tui.workspace.rrr.path import Path3RRRSpec
from planar_tui.workspace.rrr.robot import Robot3RRR
from tests.conftest import PRESETS

ROBOT = """[robot3rrr]
proximal_mass_kg = 0.6
distal_mass_kg = 0.4
platform_mass_kg = 1.5
platform_inertia_kgm2 = 0.025
gravity_m_s2 = 9.81
"""
JOB = """[[path3rrr]]
from_pose = [36, 5, -2]
to_pose = [44, 9, 2]
duration_s = 0.5
steps = 20
elbow = [1, -1, -1]
joint_limits_deg = [[20, 70], [110, 160], [245, 295]]
output = "p.csv"
plot = "p.png"
"""


def run(cli, tmp_path, text):
    preset = tmp_path / "p.toml"
    preset.write_text(text, encoding="utf-8")
    return preset, cli("run", preset, "--out-dir", tmp_path / "out")


def test_the_csv_has_a_row_per_time_and_the_columns_of_the_spec(cli, tmp_path):
    _, result = run(cli, tmp_path, ROBOT + JOB)
    assert result.exit_code == 0, result.output
    with open(tmp_path / "out" / "p.csv", newline="") as handle:
        rows = list(csv.reader(handle))
    header = rows[0]
    assert header[:4] == ["t_s", "x_cm", "y_cm", "phi_deg"]
    assert header[4:7] == ["theta1_rad", "theta1_rad_s", "theta1_rad_s2"]
    assert header[-6:] == ["tau1_Nm", "tau2_Nm", "tau3_Nm", "power1_W", "power2_W", "power3_W"]
    values = np.array(rows[1:], dtype=float)
    assert len(values) == 21
    np.testing.assert_allclose(values[:, 0], np.arange(21) * 0.025, atol=1e-15)
    np.testing.assert_allclose(values[[0, -1], 1:4], [[36, 5, -2], [44, 9, 2]], atol=1e-12)
    # the Table-3 limits hold the angles, the power is effort times rate
    limits = np.array([[20, 70], [110, 160], [245, 295]])
    degrees = np.degrees(values[:, [4, 7, 10]])
    assert np.all((degrees >= limits[:, 0]) & (degrees <= limits[:, 1]))
    np.testing.assert_allclose(values[:, -3:], values[:, -6:-3] * values[:, [5, 8, 11]])
    assert "peak |tau| = [" in result.output
    assert (tmp_path / "out" / "p.png").read_bytes().startswith(b"\x89PNG")


def test_the_bundled_preset_runs_inside_its_workspace(cli, tmp_path):
    result = cli("run", PRESETS / "path-3rrr.toml", "--out-dir", tmp_path)
    assert result.exit_code == 0, result.output
    values = np.loadtxt(tmp_path / "path-3rrr.csv", delimiter=",", skiprows=1)
    assert values.shape == (1001, 19)
    assert np.all(np.isfinite(values))
    # rest to rest: the efforts at both ends hold the robot against gravity alone
    assert np.abs(values[[0, -1], 5:13:3]).max() < 1e-12


def test_a_path_leaving_the_joint_limits_fails_naming_the_first_time(cli, tmp_path):
    text = ROBOT + JOB.replace("[36, 5, -2]", "[34, 5, 0]").replace("[44, 9, 2]", "[46, 9, 0]")
    text = text.replace("[1, -1, -1]", "[1, -1, 1]")
    preset, result = run(cli, tmp_path, text)
    assert result.exit_code == 1, result.output
    lines = [line for line in result.stderr.splitlines() if line.startswith("error:")]
    assert len(lines) == 1, result.stderr
    assert f"{preset}: path3rrr[1]: the path fails at t = " in lines[0]
    assert "leg 3 leaves its joint limits" in lines[0]
    assert not (tmp_path / "out" / "p.csv").exists()
    # the time named is the first sampled time out of the limits
    t = float(lines[0].split("t = ")[1].split(" s")[0])
    spec = Path3RRRSpec(
        from_pose=(34, 5, 0),
        to_pose=(46, 9, 0),
        duration_s=0.5,
        steps=20,
        elbow=(1, -1, 1),
        joint_limits_deg=((20, 70), (110, 160), (245, 295)),
    )
    times = sample_times(0.5, 20)
    states = quintic(pose_si(spec.from_pose), pose_si(spec.to_pose), 0.5, times)
    status = MECHANISM.inverse_dynamics(Robot3RRR(), spec, *states).status
    assert t == pytest.approx(times[np.flatnonzero(status)[0]])
    assert status[np.flatnonzero(status)[0] - 1] == 0


def test_a_singular_pose_fails(cli, tmp_path):
    """Leg 1 stretched straight (|C1 - A1| = l1 + l2 at t = 0): a serial singularity."""
    text = ROBOT + JOB.replace("[36, 5, -2]", "[60, 0, 0]").replace("[44, 9, 2]", "[55, 5, 0]")
    text = text.replace("joint_limits_deg = [[20, 70], [110, 160], [245, 295]]\n", "")
    _, result = run(cli, tmp_path, text)
    assert result.exit_code == 1, result.output
    assert "at t = 0 s (step 0): leg 1 meets a serial (type I) singularity" in result.stderr


BAD = {
    "a pose of two numbers": (JOB.replace("[36, 5, -2]", "[36, 5]"), "path3rrr[1].from_pose"),
    "zero steps": (JOB.replace("steps = 20", "steps = 0"), "path3rrr[1].steps"),
    "a negative duration": (
        JOB.replace("duration_s = 0.5", "duration_s = -1"),
        "path3rrr[1].duration_s",
    ),
    "an elbow of 2": (JOB.replace("[1, -1, -1]", "[1, 2, -1]"), "path3rrr[1].elbow"),
    "reversed limits": (JOB.replace("[20, 70]", "[70, 20]"), "path3rrr[1].joint_limits_deg"),
    "a negative mass": (JOB, "robot3rrr.distal_mass_kg"),
    "both modes at the start": (
        JOB.replace("elbow = [1, -1, -1]\n", "").replace(
            "joint_limits_deg = [[20, 70], [110, 160], [245, 295]]\n", ""
        ),
        "path3rrr[1].elbow",
    ),
}


@pytest.mark.parametrize("case", BAD)
def test_bad_input_is_one_line_exit_2_nothing_written(cli, tmp_path, case):
    job, key = BAD[case]
    robot = (
        ROBOT.replace("distal_mass_kg = 0.4", "distal_mass_kg = -0.4") if "mass" in case else ROBOT
    )
    preset, result = run(cli, tmp_path, robot + job)
    assert result.exit_code == 2, result.output
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith(f"error: {preset}: {key}: "), lines[0]
    assert not (tmp_path / "out").exists()


ROBOT_MODEL = Robot3RRR(
    proximal_mass_kg=0.6,
    distal_mass_kg=0.4,
    platform_mass_kg=1.5,
    proximal_inertia_kgm2=0.0045,
    distal_inertia_kgm2=0.003,
    platform_inertia_kgm2=0.025,
    gravity_m_s2=9.81,
)
SPEC = Path3RRRSpec(from_pose=(36, 5, -2), to_pose=(44, 9, 2), duration_s=0.5, elbow=(1, -1, -1))


def feed_forward_deviation(steps):
    start, stop = pose_si(SPEC.from_pose), pose_si(SPEC.to_pose)

    def effort(t):
        states = quintic(start, stop, SPEC.duration_s, np.array([t]))
        return MECHANISM.inverse_dynamics(ROBOT_MODEL, SPEC, *states).effort[0]

    motion = simulate(MECHANISM, ROBOT_MODEL, SPEC, start, np.zeros(3), effort, 0.5, steps)
    path = quintic(start, stop, SPEC.duration_s, motion.times_s)[0]
    return np.abs(motion.pose - path).max(), motion.drift_m


def test_feeding_the_paths_efforts_forward_reproduces_the_path_to_rk4_accuracy():
    coarse, drift = feed_forward_deviation(80)
    fine, _ = feed_forward_deviation(160)
    assert fine < 1e-6
    assert 10.0 < coarse / fine < 24.0  # fourth order: 16
    assert drift < 1e-14


def test_constant_efforts_trade_work_for_energy():
    """Holding torques at rest keep the platform still; other constant torques do the
    work tau . (theta(T) - theta(0)) = change of kinetic plus potential energy (the
    energy from the Lagrange reference's full coordinates)."""
    from tests.lagrange_planar import Leg, rr_coordinates, rr_system
    from tests.test_parallel_dynamics_lagrange import rrr_legs

    start = np.array(pose_si(SPEC.from_pose))
    zero = np.zeros(3)
    rest = quintic(start, start, 1.0, np.zeros(1))
    hold = MECHANISM.inverse_dynamics(ROBOT_MODEL, SPEC, *rest).effort[0]
    still = simulate(MECHANISM, ROBOT_MODEL, SPEC, start, zero, lambda t: hold, 0.1, 10)
    assert np.abs(still.pose - start).max() < 1e-12
    push = hold + np.array([0.2, -0.15, 0.1])
    motion = simulate(MECHANISM, ROBOT_MODEL, SPEC, start, zero, lambda t: push, 0.1, 200)
    legs: list[Leg] = rrr_legs(ROBOT_MODEL, SPEC.elbow)
    system = rr_system(legs, (0.6, 0.4), (0.0045, 0.003), (1.5, 0.025), ROBOT_MODEL.gravity_m_s2)
    energies = []
    for pose, rate in ((motion.pose[0], motion.rate[0]), (motion.pose[-1], motion.rate[-1])):
        q = rr_coordinates(legs, pose)
        energies.append(system.energy(q, system.velocities(q, rate)))
    ends = motion.pose[[0, -1]]
    zeros = np.zeros((2, 3))
    theta = MECHANISM.inverse_dynamics(ROBOT_MODEL, SPEC, ends, zeros, zeros).coordinate
    work = push @ (theta[1] - theta[0])
    assert abs(work) > 1e-5
    assert work == pytest.approx(energies[1] - energies[0], rel=1e-6)


def test_the_declared_figure_names_are_those_a_run_reports(tmp_path):
    from planar_tui.batch import prepare_jobs, run_job
    from planar_tui.presets import load_preset
    from planar_tui.registry import JOB_KINDS

    path = tmp_path / "p.toml"
    path.write_text(ROBOT + JOB)
    (job,) = prepare_jobs(load_preset(path).jobs_of("path3rrr"))
    figures = JOB_KINDS["path3rrr"].point_figures(job, run_job(job))
    assert JOB_KINDS["path3rrr"].figure_names(job) == tuple(figures)
    assert len(figures) == 9 and figures["tau3_abs_max_Nm"] > 0


def test_a_path_beyond_the_time_limit_is_refused_on_steps(cli, tmp_path, monkeypatch):
    """1 000 feed-forward steps are estimated at 2 s: over a limit of 1 s, refused up
    front (exit 2, one line on ``steps``); without feed-forward they fit."""
    import planar_tui.limits

    monkeypatch.setattr(planar_tui.limits, "MAX_JOB_SECONDS", 1.0)
    text = ROBOT + JOB.replace("steps = 20", "steps = 1000\nfeed_forward = true")
    preset, result = run(cli, tmp_path, text)
    assert result.exit_code == 2, result.output
    assert result.stderr.startswith(f"error: {preset}: path3rrr[1].steps: is 1,000: the path ")
    assert "(expected fewer steps)" in result.stderr
    _, result = run(cli, tmp_path, ROBOT + JOB.replace("steps = 20", "steps = 1000"))
    assert result.exit_code == 0, result.output


def test_the_torques_are_affine_in_the_platform_mass():
    """The dynamics is linear in the inertial parameters: the torques at 1.5 kg are the
    mean of those at 0 and 3 kg (what a sweep over the mass reports, point by point)."""
    masses = [dataclasses.replace(ROBOT_MODEL, platform_mass_kg=m) for m in (0.0, 1.5, 3.0)]
    states = quintic(pose_si(SPEC.from_pose), pose_si(SPEC.to_pose), 0.5, sample_times(0.5, 20))
    efforts = [MECHANISM.inverse_dynamics(robot, SPEC, *states).effort for robot in masses]
    assert np.abs(efforts[2] - efforts[0]).max() > 1.0
    np.testing.assert_allclose(efforts[1], (efforts[0] + efforts[2]) / 2, atol=1e-12)


@pytest.mark.slow
def test_a_sweep_over_the_platform_mass_reports_the_torque_figures(cli, tmp_path):
    """A sweep of a path job (worker processes: slow on a loaded machine): one row per
    platform mass with each actuator's figures, growing with the mass."""
    sweep = '[[sweep]]\njob = "path3rrr"\nvalues."robot3rrr.platform_mass_kg" = [0.0, 1.5, 3.0]\n'
    sweep += 'output = "sweep.csv"\n'
    _, result = run(cli, tmp_path, ROBOT + JOB + sweep)
    assert result.exit_code == 0, result.output
    with open(tmp_path / "out" / "sweep.csv", newline="") as handle:
        rows = list(csv.DictReader(handle))
    assert [row["status"] for row in rows] == ["ok"] * 3
    peaks = [float(row["tau1_abs_max_Nm"]) for row in rows]
    assert peaks[0] < peaks[1] < peaks[2]


def test_a_forward_dynamics_leaving_the_workspace_fails_the_job(cli, tmp_path, monkeypatch):
    """The feed-forward simulation straying out of reach is a failed job naming the time
    (forced here: a real path's simulation stays within RK4's error of it)."""
    import planar_tui.workspace.path.job as path_job
    from planar_tui.workspace.path.forward import PathFailure

    def strays(*args):
        raise PathFailure(0.25, 11)

    monkeypatch.setattr(path_job, "feed_forward", strays)
    preset, result = run(
        cli, tmp_path, ROBOT + JOB.replace("steps = 20", "steps = 20\nfeed_forward = true")
    )
    assert result.exit_code == 1, result.output
    lines = [line for line in result.stderr.splitlines() if line.startswith("error:")]
    assert len(lines) == 1, result.stderr
    assert (
        f"{preset}: path3rrr[1].feed_forward: the forward dynamics fails at t = 0.25 s: leg 1"
        in lines[0]
    )
    assert "leg 1 cannot close" in lines[0]
    assert not (tmp_path / "out" / "p.csv").exists()


def test_an_angle_crossing_a_half_turn_is_continuous_in_the_csv(cli, tmp_path):
    """Without joint limits an angle is reported in [-pi, pi) by the mechanism; along the
    path the CSV's angles are unwrapped: no jump of a turn between two times, and the
    rates agree with the angles' differences."""
    job = JOB.replace("[36, 5, -2]", "[40, 21, 0]").replace("[44, 9, 2]", "[45, 35, 0]")
    job = job.replace("[1, -1, -1]", "[1, 1, 1]").replace("steps = 20", "steps = 200")
    job = job.replace("joint_limits_deg = [[20, 70], [110, 160], [245, 295]]\n", "")
    _, result = run(cli, tmp_path, ROBOT + job)
    assert result.exit_code == 0, result.output
    values = np.loadtxt(tmp_path / "out" / "p.csv", delimiter=",", skiprows=1)
    theta, rate = values[:, [4, 7, 10]], values[:, [5, 8, 11]]
    assert np.abs(theta).max() > np.pi  # it did cross
    midpoint = (rate[1:] + rate[:-1]) / 2 * np.diff(values[:, 0])[:, None]
    np.testing.assert_allclose(np.diff(theta, axis=0), midpoint, atol=1e-4)

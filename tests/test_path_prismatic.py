"""The ``[[path3rpr]]`` and ``[[path3prr]]`` jobs through the CLI (``planar-tui run``).

Their CSV is checked against what does not share the NOC kernels: the leg forces against
the Lagrange-multiplier formulation in full coordinates (:mod:`tests.closed_chain`) at
sampled rows, the leg lengths by the direct kinematics (every row's actuator values hold
its pose among their assembly modes) and the powers as force times rate. A path leaving
the legs' limits fails the job (exit code 1, one line naming the first such time); bad
input is refused (exit code 2, one line naming the key, nothing written).
"""

from __future__ import annotations

import csv
import math
import re

import numpy as np
import pytest

from planar_tui import batch
from planar_tui.presets import load_preset
from tests import closed_chain
from tests.conftest import PRESETS

BUNDLED = PRESETS / "path-3rpr.toml"
PRR_PRESET = """
[robot3prr]
slider_mass_kg = 1.2
link_mass_kg = 0.6
link_inertia_kgm2 = 0.008
platform_mass_kg = 2.5
platform_inertia_kgm2 = 0.04
gravity_m_s2 = 9.81

[[path3prr]]
from_pose = [40, 25, 0]
to_pose = [44, 28, 8]
duration_s = 0.4
steps = 20
slider_modes = [1, 1, 1]
output = "prr.csv"
plot = "prr.svg"
"""


def read(path) -> list[dict[str, float]]:
    with open(path, newline="", encoding="utf-8") as handle:
        return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(handle)]


def header(path) -> list[str]:
    with open(path, newline="", encoding="utf-8") as handle:
        return next(csv.reader(handle))


def columns(kind_prefix: str = "rho") -> list[str]:
    legs = (1, 2, 3)
    return [
        "t_s",
        "x_cm",
        "y_cm",
        "phi_deg",
        *(f"{kind_prefix}{i}_cm{s}" for i in legs for s in ("", "_s", "_s2")),
        *(f"force{i}_N" for i in legs),
        *(f"power{i}_W" for i in legs),
    ]


def state(row, duration_s, start, stop):
    """The quintic's pose, rate and acceleration at ``row`` (SI), written here again."""
    tau = row["t_s"] / duration_s
    delta = np.array(stop) - np.array(start)
    s = tau**3 * (10 - 15 * tau + 6 * tau**2)
    pose = np.array(start) + delta * s
    return (
        np.array([pose[0] / 100, pose[1] / 100, math.radians(pose[2])]),
        delta * 30 * tau**2 * (1 - tau) ** 2 / duration_s * [0.01, 0.01, math.pi / 180],
        delta * 60 * tau * (1 - tau) * (1 - 2 * tau) / duration_s**2 * [0.01, 0.01, math.pi / 180],
    )


def check_rows(rows, build, mechanism, robot, spec, body, sample=(0, 5, 13)):
    """Forces against Lagrange multipliers, poses by the direct kinematics, power."""
    for k in sample:
        row = rows[k]
        pose, rate, acceleration = state(row, spec.duration_s, spec.from_pose, spec.to_pose)
        assert [row["x_cm"], row["y_cm"]] == pytest.approx(pose[:2] * 100, abs=1e-9)
        chain, actuators = build(pose, body)
        _, _, forces, residual = chain.solve(0, rate, acceleration, actuators, body[-1])
        assert residual < 1e-12
        found = np.array([row[f"force{i}_N"] for i in (1, 2, 3)])
        np.testing.assert_allclose(found, forces, rtol=0, atol=1e-8 * np.max(np.abs(forces)))
        rho = [row[f"rho{i}_cm"] for i in (1, 2, 3)]
        modes = mechanism.direct_kinematics(robot, rho)
        assert min(np.max(np.abs(m - [*pose[:2] * 100, pose[2]])) for m in modes) < 1e-7
        for i in (1, 2, 3):
            power = row[f"force{i}_N"] * row[f"rho{i}_cm_s"] / 100.0
            assert row[f"power{i}_W"] == pytest.approx(power, rel=1e-12, abs=1e-300)


def test_bundled_3rpr_path(cli, tmp_path):
    result = cli("run", BUNDLED, "--out-dir", tmp_path)
    assert result.exit_code == 0, result.output
    job = load_preset(BUNDLED).jobs[0]
    robot, spec = job.robot, job.spec
    out = tmp_path / "path-3rpr.csv"
    assert header(out) == columns()
    rows = read(out)
    assert len(rows) == spec.steps + 1
    from planar_tui.workspace.rpr.dynamics import body_array

    body = body_array(robot)
    bases = np.array(robot.base_joints_cm) / 100
    points = np.array(robot.platform_points_cm) / 100

    def build(pose, body):
        return closed_chain.rpr_chain(bases, points, pose, body)

    check_rows(rows, build, spec.mechanism, robot, spec, body, sample=(0, 37, 100, 163, 200))
    # at rest at both ends: no rates, the forces hold the weight only
    assert rows[0]["rho1_cm_s"] == 0.0 and rows[-1]["rho3_cm_s2"] == pytest.approx(0, abs=1e-9)


def test_3prr_path(cli, tmp_path):
    preset = tmp_path / "prr.toml"
    preset.write_text(PRR_PRESET, encoding="utf-8")
    result = cli("run", preset, "--out-dir", tmp_path)
    assert result.exit_code == 0, result.output
    job = load_preset(preset).jobs[0]
    robot, spec = job.robot, job.spec
    out = tmp_path / "prr.csv"
    assert header(out) == columns()
    assert "force (N)" in (tmp_path / "prr.svg").read_text(encoding="utf-8")
    rows = read(out)
    assert len(rows) == 21
    from planar_tui.workspace.prr.dynamics import body_array

    angles = np.radians(robot.slider_angles_deg)
    links = np.array(robot.distal_cm) / 100

    def build(pose, body):
        return closed_chain.prr_chain(
            np.array(robot.slider_points_cm) / 100,
            angles,
            np.array(robot.platform_points_cm) / 100,
            links,
            (1, 1, 1),
            pose,
            body,
        )

    check_rows(rows, build, spec.mechanism, robot, spec, body_array(robot))


def write(path, text):
    path.write_text(text, encoding="utf-8")
    return path


def run_failing(cli, tmp_path, text):
    preset = tmp_path / "bad.toml"
    preset.write_text(text, encoding="utf-8")
    result = cli("run", preset, "--out-dir", tmp_path / "out")
    lines = [line for line in result.stderr.splitlines() if line.startswith("error: ")]
    return result, lines


def test_3rpr_path_leaving_the_leg_limits_fails_at_its_first_time(cli, tmp_path):
    text = BUNDLED.read_text(encoding="utf-8").replace(
        "to_pose = [-12.0, 4.0, 25.0]", "to_pose = [-30.0, 4.0, 25.0]"
    )
    result, lines = run_failing(cli, tmp_path, text)
    assert result.exit_code == 1, result.output
    assert len(lines) == 1 and "the path fails at t = " in lines[0], lines
    assert "leaves its joint limits" in lines[0]
    assert not (tmp_path / "out" / "path-3rpr.csv").exists()


def test_3prr_path_out_of_reach_fails_at_its_first_time(cli, tmp_path):
    text = PRR_PRESET.replace("to_pose = [44, 28, 8]", "to_pose = [90, 25, 0]")
    result, lines = run_failing(cli, tmp_path, text)
    assert result.exit_code == 1, result.output
    assert len(lines) == 1 and "the path fails at t = 0.2 s (step 10)" in lines[0], lines


@pytest.mark.parametrize(
    ("text", "old", "new", "fragment"),
    [
        (
            "rpr",
            "leg_limits_cm = [[5, 25], [5, 25], [5, 25]]",
            "leg_limits_cm = [[25, 5]]",
            "leg_limits_cm",
        ),
        ("rpr", "to_pose = [-12.0, 4.0, 25.0]", "to_pose = [-12.0, 4.0]", "to_pose"),
        ("rpr", "cylinder_mass_kg = 0.4", "cylinder_mass_kg = -0.4", "cylinder_mass_kg"),
        ("prr", "slider_modes = [1, 1, 1]", "slider_modes = [1, 2, 1]", "slider_modes"),
        ("prr", "link_mass_kg = 0.6", "link_mass_kg = -1", "link_mass_kg"),
    ],
)
def test_bad_input_is_refused(cli, tmp_path, text, old, new, fragment):
    source = BUNDLED.read_text(encoding="utf-8") if text == "rpr" else PRR_PRESET
    assert old in source
    result, lines = run_failing(cli, tmp_path, source.replace(old, new))
    assert result.exit_code == 2, result.output
    assert len(lines) == 1 and lines[0].startswith("error: ") and fragment in lines[0], lines
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())


def test_3prr_mode_asked_where_both_reach(cli, tmp_path):
    """Without ``slider_modes`` a leg closing in both modes within its stroke is refused
    (leg 3 at (40, 15) cm); at (40, 25) cm each leg has one, which the job takes."""
    text = PRR_PRESET.replace("slider_modes = [1, 1, 1]\n", "")
    assert cli("run", write(tmp_path / "one.toml", text), "--out-dir", tmp_path).exit_code == 0
    text = text.replace("from_pose = [40, 25, 0]", "from_pose = [40, 15, 0]")
    result, lines = run_failing(cli, tmp_path, text)
    assert result.exit_code == 2, result.output
    assert len(lines) == 1 and "slider_modes" in lines[0] and "leg 3 closes in both" in lines[0]


@pytest.mark.parametrize("robot", ["3-RPR", "3-PRR"])
def test_feed_forward_follows_the_path(robot, tmp_path):
    """The platform's forward dynamics (RK4, the path's steps) under the path's own forces
    stays on the path to the integrator's accuracy; the legs close exactly."""
    if robot == "3-RPR":
        text = BUNDLED.read_text(encoding="utf-8").replace("steps = 200", "steps = 100")
    else:
        text = PRR_PRESET
    (job,) = load_preset(write(tmp_path / "ff.toml", text + "feed_forward = true\n")).jobs
    summary = batch.run_job(job).summary
    found = re.search(r"deviation ([0-9.e+-]+), closure drift ([0-9.e+-]+) m", summary)
    assert found, summary
    assert float(found[1]) < 1e-4 and float(found[2]) < 1e-12


def test_a_path_beyond_the_time_limit_is_refused_on_steps(cli, tmp_path, monkeypatch):
    """The shared estimate holds for these jobs too: 1 000 feed-forward steps over a limit
    of 1 s are refused up front (exit 2, one line on ``steps``)."""
    import planar_tui.limits

    monkeypatch.setattr(planar_tui.limits, "MAX_JOB_SECONDS", 1.0)
    for text in (BUNDLED.read_text(encoding="utf-8"), PRR_PRESET):
        text = re.sub(r"steps = \d+", "steps = 1000\nfeed_forward = true", text)
        result, lines = run_failing(cli, tmp_path, text)
        assert result.exit_code == 2, result.output
        assert len(lines) == 1 and ".steps: is 1,000: the path " in lines[0], lines

"""The path sensitivity of the prismatic robots' actuator forces (the 3-RPR's legs, the
3-PRR's sliders: planar_tui/pathsensitivity/rpr.py, prr.py): their inputs and effort
names, an input that cannot enter the forces, a purely additive closed form, bad input."""

from __future__ import annotations

import csv

import numpy as np
import pytest

from planar_tui.pathsensitivity.engine import design_efforts, path_outputs, path_states, scaled
from planar_tui.pathsensitivity.inputs import robot_inputs
from planar_tui.workspace.prr.path import Path3PRRSpec
from planar_tui.workspace.prr.robot import Robot3PRR
from planar_tui.workspace.rpr.path import Path3RPRSpec
from planar_tui.workspace.rpr.robot import Robot3RPR

RPR = """[robot3rpr]
cylinder_mass_kg = 0.8
cylinder_com_cm = 10
piston_mass_kg = 0.5
platform_mass_kg = 1.5
platform_inertia_kgm2 = 0.025
{gravity}
[[path3rpr_sensitivity]]
from_pose = [35, 15, 0]
to_pose = [37, 17, {phi}]
duration_s = 0.5
steps = 10
tolerance_length_mm = 0.1
tolerance_mass_g = 20
tolerance_inertia_kgm2 = 2e-4
samples = 16
output = "s.csv"
"""
PRR = """[robot3prr]
slider_mass_kg = 0.8
link_mass_kg = 0.4
platform_mass_kg = 1.5
platform_inertia_kgm2 = 0.025
{gravity}
[[path3prr_sensitivity]]
from_pose = [40, 25, 0]
to_pose = [42, 27, {phi}]
duration_s = 0.5
steps = 10
tolerance_length_mm = 0.1
tolerance_mass_g = 20
tolerance_inertia_kgm2 = 2e-4
samples = 16
output = "s.csv"
"""
POINTS = [
    f"{field}[{i}].{c}" for field in ("{}", "platform_points_cm") for i in (1, 2, 3) for c in "xy"
]
NAMES = {
    "path3rpr_sensitivity": [
        *(name.format("base_joints_cm") for name in POINTS),
        "cylinder_com_cm",  # the piston's is 0: at its joint, no input
        "cylinder_mass_kg",
        "piston_mass_kg",
        "platform_mass_kg",
        "platform_inertia_kgm2",
    ],
    "path3prr_sensitivity": [
        *(name.format("slider_points_cm") for name in POINTS),
        "distal_cm[1]",
        "distal_cm[2]",
        "distal_cm[3]",
        "slider_mass_kg",
        "link_mass_kg",
        "platform_mass_kg",
        "platform_inertia_kgm2",
    ],
}
PRESETS = {"path3rpr_sensitivity": RPR, "path3prr_sensitivity": PRR}


def run(cli, tmp_path, text):
    preset = tmp_path / "p.toml"
    preset.write_text(text, encoding="utf-8")
    return preset, cli("run", preset, "--out-dir", tmp_path / "out")


def read(path):
    with open(path, newline="", encoding="utf-8") as handle:
        return list(csv.DictReader(handle))


@pytest.mark.parametrize("kind", list(PRESETS))
def test_the_forces_are_named_and_a_fixed_orientation_leaves_out_the_platform_inertia(
    cli, tmp_path, kind
):
    """On a horizontal machine (no gravity) along a path at constant orientation the
    platform does not turn: its inertia enters no force, so its Sobol' indices are exactly
    0 at every step (every other input moves the forces); the tables name the forces
    ``force{j}_N`` and have a row per output, input and step."""
    text = PRESETS[kind].format(gravity="", phi=0)
    _, result = run(cli, tmp_path, text)
    assert result.exit_code == 0, result.output
    assert "peak|F1|" in result.output
    out = tmp_path / "out"
    main, per_step = read(out / "s.csv"), read(out / "s-path.csv")
    names = NAMES[kind]
    assert list(dict.fromkeys(r["parameter"] for r in main)) == names
    assert len(main) == 6 * len(names) * 2  # peak and RMS of 3 forces, Sobol' and PCE
    assert list(dict.fromkeys(r["output"] for r in per_step)) == [
        "force1_N",
        "force2_N",
        "force3_N",
    ]
    assert len(per_step) == 11 * 3 * len(names) * 2
    aggregated = {r["output"] for r in read(out / "s-path-aggregated.csv")}
    assert aggregated == {"force1_N", "force2_N", "force3_N", "all forces"}
    sobol = [r for r in main + per_step if r["method"] == "sobol" and r["S1"] != ""]
    inertia = [r for r in sobol if r["parameter"] == "platform_inertia_kgm2"]
    assert inertia and all(float(r["S1"]) == 0.0 == float(r["ST"]) for r in inertia)
    moving = [r for r in sobol if r["parameter"] == "platform_mass_kg"]
    assert max(float(r["ST"]) for r in moving) > 0.01


STATIC = {
    "path3rpr_sensitivity": (
        Robot3RPR(
            cylinder_mass_kg=0.8,
            cylinder_com_cm=10.0,
            piston_mass_kg=0.5,
            piston_com_cm=5.0,
            platform_mass_kg=1.5,
            gravity_m_s2=9.81,
        ),
        Path3RPRSpec(from_pose=(35, 15, 0), to_pose=(35, 15, 0), duration_s=1.0, steps=4),
    ),
    "path3prr_sensitivity": (
        Robot3PRR(slider_mass_kg=0.8, link_mass_kg=0.4, platform_mass_kg=1.5, gravity_m_s2=9.81),
        Path3PRRSpec(
            from_pose=(40, 25, 0),
            to_pose=(40, 25, 0),
            duration_s=1.0,
            steps=4,
            slider_modes=(1, 1, 1),
        ),
    ),
}


@pytest.mark.parametrize("kind", list(STATIC))
def test_gravity_statics_have_the_closed_form_shares(kind):
    """A platform held still (gravity statics), the masses the only inputs (±20 g): each
    force is linear in the masses, F_i = sum_b c_ib m_b, so S1 = ST = c_ib² / sum c²
    (equal ranges). The coefficients c_ib come from one massive body at a time through the
    mechanism (bodies at the same centre-of-mass distances), not through the estimators."""
    import dataclasses

    from planar_tui.sensitivity.engine import analyse, unit_design
    from planar_tui.sensitivity.pce import pce_indices, pce_unit_design

    robot, spec = STATIC[kind]
    inputs = robot_inputs(robot, (), 0.01, 0.02, None)
    states = path_states(spec)
    massless = {i.field: 0.0 for i in inputs}
    coefficients = []
    for body in inputs:
        alone = dataclasses.replace(robot, **{**massless, body.field: 1.0})
        solution = spec.mechanism.inverse_dynamics(
            alone, spec, states.pose, states.rate, states.acceleration
        )
        assert not solution.status.any()
        coefficients.append(solution.effort[0])
    c2 = np.array(coefficients).T ** 2  # (actuators, masses)
    expected = np.concatenate([c2 / c2.sum(axis=1, keepdims=True)] * 2)
    for method, unit, tolerance in (
        ("pce", pce_unit_design(len(inputs), 64, 7), 1e-8),
        ("sobol", unit_design("sobol", len(inputs), 1024, 7), 0.03),
    ):
        efforts = design_efforts(robot, spec, inputs, scaled(inputs, np.asarray(unit)), states)
        outputs = path_outputs(efforts, states.times_s)[:, :6]
        if method == "pce":
            indices = pce_indices(np.asarray(unit), outputs, 7, num_resamples=1)[0]
        else:
            indices = analyse(method, outputs, len(inputs), 7)
        np.testing.assert_allclose(indices[0], expected, atol=tolerance, err_msg=method)
        np.testing.assert_allclose(indices[2], expected, atol=tolerance, err_msg=method)


BAD = {
    "a length tolerance of the cylinder's centre of mass": (
        "path3rpr_sensitivity",
        RPR.replace("tolerance_length_mm = 0.1", "tolerance_length_mm = 150"),
        "tolerance_length_mm",
    ),
    "a massless 3-PRR": (
        "path3prr_sensitivity",
        "[robot3prr]\n" + PRR[PRR.index("[[") :],
        "tolerance_mass_g",
    ),
    "a 3-PRR mass tolerance of the lightest body": (
        "path3prr_sensitivity",
        PRR.replace("tolerance_mass_g = 20", "tolerance_mass_g = 400"),
        "tolerance_mass_g",
    ),
}


@pytest.mark.parametrize("case", BAD)
def test_bad_input_is_one_line_exit_2_nothing_written(cli, tmp_path, case):
    kind, text, key = BAD[case]
    preset, result = run(cli, tmp_path, text.format(gravity="", phi=5))
    assert result.exit_code == 2, result.output
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith(f"error: {preset}: {kind}[1].{key}: "), lines[0]
    assert not (tmp_path / "out").exists()

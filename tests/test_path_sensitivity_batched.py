"""The path sensitivity's robots in one kernel call
(:func:`planar_tui.kernels.dynamics_robots.robots_path_efforts` through
``pathsensitivity.engine.design_efforts``) against each robot's own inverse dynamics
(``mechanism.inverse_dynamics``, one robot at a time): the same efforts for random design
rows of all four robots, and NaN at every step for a robot whose path fails."""

from __future__ import annotations

import numpy as np
import pytest

from planar_tui.batch import prepare_jobs
from planar_tui.pathsensitivity.engine import design_efforts, path_states, scaled
from planar_tui.pathsensitivity.inputs import robot_at
from planar_tui.pathsensitivity.sizes import inputs_of
from planar_tui.presets import load_preset
from tests.test_path_sensitivity import JOB, ROBOT
from tests.test_path_sensitivity_prismatic import PRESETS

FIVEBAR = """[robot5r]
working_mode = "+-"
proximal_mass_kg = 0.5
distal_mass_kg = 0.3
end_mass_kg = 1.0
gravity_m_s2 = 9.81

[[path5r_sensitivity]]
from_pose = [0, 60]
to_pose = [5, 65]
steps = 20
tolerance_length_mm = 0.1
tolerance_mass_g = 20
output = "f.csv"
"""
CASES = {
    "3-RRR": ROBOT + JOB,
    "five-bar": FIVEBAR,
    "3-RPR": PRESETS["path3rpr_sensitivity"].format(gravity="gravity_m_s2 = 9.81", phi=10),
    "3-PRR": PRESETS["path3prr_sensitivity"].format(gravity="gravity_m_s2 = 9.81", phi=10),
}

#: The cases whose far row cannot follow the path.
FAILING = ("3-RRR", "five-bar", "3-PRR")


def prepared(tmp_path, text):
    preset = tmp_path / "p.toml"
    preset.write_text(text, encoding="utf-8")
    (ready,) = prepare_jobs(load_preset(preset).jobs)
    return ready.prepared, ready.robot


def one_by_one(robot, spec, inputs, rows, states):
    """Each row's efforts by its own ``inverse_dynamics`` call; NaN where its path fails."""
    found = []
    for row in rows:
        solution = spec.mechanism.inverse_dynamics(
            robot_at(robot, inputs, row), spec, states.pose, states.rate, states.acceleration
        )
        found.append(np.where(solution.status.any(), np.nan, solution.effort))
    return np.array(found)


@pytest.mark.parametrize("case", list(CASES))
def test_the_robots_in_one_call_have_each_robots_own_efforts(tmp_path, case):
    """Random design rows within the tolerances, more than one kernel call's worth, then a
    row far outside them (every input 40 % above or below its nominal value, by turns):
    the batched efforts equal the one-robot kernel's to 1e-12 of the largest effort. The
    revolute robots' far row cannot follow the path (a leg that cannot close or a joint
    limit): NaN at every step in both (the 3-RPR has no limits, its far row still
    runs)."""
    spec, robot = prepared(tmp_path, CASES[case])
    inputs = inputs_of(spec, robot)
    unit = np.random.default_rng(35).random((70, len(inputs)))
    rows = scaled(inputs, unit)
    far = np.array([i.nominal * (1.4 if k % 2 else 0.6) for k, i in enumerate(inputs)])
    rows = np.vstack([rows, far])
    states = path_states(spec)
    batched = design_efforts(robot, spec, inputs, rows, states)
    expected = one_by_one(robot, spec, inputs, rows, states)
    assert batched.shape == expected.shape == (71, spec.steps + 1, batched.shape[2])
    assert np.isfinite(expected[:70]).all()
    fails = case in FAILING
    assert np.isnan(expected[70]).all() == fails and np.isnan(expected[70]).any() == fails
    assert np.array_equal(np.isnan(batched), np.isnan(expected))
    scale = np.nanmax(np.abs(expected))
    assert scale > 0.1
    np.testing.assert_allclose(batched, expected, rtol=0, atol=1e-12 * scale)

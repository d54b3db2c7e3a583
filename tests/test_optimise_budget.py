"""An optimisation is bounded before it starts, as a sweep is (issue 19, item 4): its
evaluations' total computing time and its workers' memory, estimated from the job kind's
estimates at the variables' corners, refused in one line over the limits."""

from __future__ import annotations

import pytest

from planar_tui.errors import ExitCode
from tests.sweep_presets import one_line

LONG_OPTIMISATION = """[robot]
lengths_m = [0.3, 0.25]
masses_kg = [2.0, 1.5]

[simulate]
duration_s = {duration_s}
step_s = 1e-6
every = 1000000000
output = "sim.csv"

[[optimise]]
job = "simulate"
variables."robot.masses_kg[2]" = {{ from = 1.0, to = 2.0 }}
{objective}
budget = {budget}
population = 10
"""
ONE = 'minimise = "energy_drift_max_J"'
TWO = 'minimise = ["energy_drift_max_J", "t_end_s"]'


def _preset(tmp_path, duration_s=3600, budget=100, objective=ONE):
    path = tmp_path / "opt.toml"
    path.write_text(
        LONG_OPTIMISATION.format(duration_s=duration_s, budget=budget, objective=objective)
    )
    return path


def test_an_optimisation_of_long_evaluations_is_refused_with_its_estimate(tmp_path, cli):
    """100 evaluations of about an hour each (one design is well under a day; 101 runs,
    with the certified re-run, about four days) are refused before anything runs."""
    from planar_tui.dynamics.robot import rk4_step_seconds

    one_s = 3600 / 1e-6 * rk4_step_seconds(2)
    assert one_s < 86_400 < 101 * one_s
    result = cli("optimise", _preset(tmp_path), "--out-dir", tmp_path / "out", "--workers", "1")
    assert result.exit_code == ExitCode.BAD_INPUT
    line = one_line(result)
    assert "optimise[1]: 100 evaluations and 1 certified re-run(s) need about" in line
    assert "days of computing" in line and "limit 1 day" in line
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize(("objective", "reruns"), [(ONE, 1), (TWO, 10)])
def test_the_estimate_is_the_evaluations_and_the_certified_reruns(tmp_path, objective, reruns):
    """Every design of this simulation costs the same (the mass does not change the
    step count), so the estimate is (budget + re-runs) × steps × one RK4 step's cost."""
    from planar_tui.dynamics.robot import rk4_step_seconds
    from planar_tui.optimise.budget import estimate_optimisation
    from planar_tui.optimise.spec import parse_optimisations
    from planar_tui.presets import load_preset

    preset = load_preset(_preset(tmp_path, duration_s=10, budget=40, objective=objective))
    (opt,) = parse_optimisations(preset)
    found = estimate_optimisation(opt)
    assert found is not None
    expected = (40 + reruns) * 10 / 1e-6 * rk4_step_seconds(2)
    assert found.seconds == pytest.approx(expected, rel=1e-9)
    assert found.memory_bytes > 0


def test_workers_whose_memory_exceeds_the_limit_are_refused(tmp_path, cli, monkeypatch):
    from planar_tui.sweep import budget

    monkeypatch.setattr(budget, "memory_limit_bytes", lambda: 500 * 2**20)
    preset = _preset(tmp_path, duration_s=1, budget=4)
    result = cli("optimise", preset, "--out-dir", tmp_path / "out", "--workers", "2")
    assert result.exit_code == ExitCode.BAD_INPUT
    line = one_line(result)
    assert "--workers: 2 local workers for opt:optimise[1]" in line and "limit 500 MiB" in line
    assert not (tmp_path / "out").exists()

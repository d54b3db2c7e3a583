"""Every sweep run is bounded before it starts (issue 19, items 3-4): worker counts,
the workers' memory, the points' total computing time, ``max_points``; points are made
lazily, so a 100 000-point sweep starts without parsing every point first."""

from __future__ import annotations

import pytest

from planar_tui.errors import ExitCode
from tests.sweep_presets import TORQUES, TORQUES_BASE, one_line, write

SWEEP = """[[sweep]]
job = "torques"
values."robot.masses_kg[2]" = [1.0, 2.0]
output = "s.csv"
"""


@pytest.mark.parametrize("workers", ["100000000000000000000", "1000"])
def test_a_worker_count_above_the_cores_is_refused_in_one_line(tmp_path, cli, workers):
    preset = write(tmp_path, "p.toml", TORQUES, SWEEP, **TORQUES_BASE)
    result = cli("sweep", preset, "--out-dir", tmp_path / "out", "--workers", workers)
    assert result.exit_code == ExitCode.BAD_INPUT
    line = one_line(result)
    assert line.startswith("error: command line: --workers: is ")
    assert "per usable core" in line
    assert not (tmp_path / "out").exists()


def test_workers_whose_memory_exceeds_the_limit_are_refused(tmp_path, cli, monkeypatch):
    from planar_tui.sweep import budget

    monkeypatch.setattr(budget, "memory_limit_bytes", lambda: 500 * 2**20)
    preset = write(tmp_path, "p.toml", TORQUES, SWEEP, **TORQUES_BASE)
    result = cli("sweep", preset, "--out-dir", tmp_path / "out", "--workers", "2")
    assert result.exit_code == ExitCode.BAD_INPUT
    line = one_line(result)
    assert "--workers: 2 local workers" in line and "limit 500 MiB" in line


LONG_SIMULATION = """[robot]
lengths_m = [0.3, 0.25]
masses_kg = [2.0, 1.5]

[simulate]
duration_s = 64800
step_s = 1e-6
every = 1000000000
output = "sim.csv"

[[sweep]]
job = "simulate"
values."robot.masses_kg[2]" = { from = 1.0, to = 2.0, count = 100 }
"""


def test_a_sweep_of_long_points_is_refused_with_its_estimate(tmp_path, cli):
    """100 points of about 18 hours each: one point is accepted (under a day), the sweep
    (about 75 days) is not, before anything runs."""
    preset = tmp_path / "long.toml"
    preset.write_text(LONG_SIMULATION)
    from planar_tui.dynamics.simulate import rk4_step_seconds

    assert 0.5 * 86_400 < 64800 / 1e-6 * rk4_step_seconds(2) < 86_400  # one point: < 1 day
    result = cli("sweep", preset, "--out-dir", tmp_path / "out", "--workers", "1")
    assert result.exit_code == ExitCode.BAD_INPUT
    line = one_line(result)
    assert "sweep[1]: 100 points need about 75" in line and "days of computing" in line
    assert "limit 1 day" in line
    assert not (tmp_path / "out").exists()


def test_max_points_is_bounded(tmp_path, cli):
    preset = write(
        tmp_path, "p.toml", TORQUES, SWEEP + "max_points = 1000000000000\n", **TORQUES_BASE
    )
    result = cli("sweep", preset, "--out-dir", tmp_path / "out", "--workers", "1")
    assert result.exit_code == ExitCode.BAD_INPUT
    assert "sweep[1].max_points" in one_line(result)


@pytest.mark.parametrize(
    "values",
    [
        'values."robot.masses_kg[2]" = { from = 1, to = 2, count = 100000000 }',
        'ranges."robot.masses_kg[2]" = [1, 2]\nsample = { method = "uniform", count = 100000000 }',
        'values."robot.masses_kg[2]" = { from = 1, to = 2, count = 1000 }\n'
        'values."robot.lengths_m[1]" = { from = 0.1, to = 0.3, count = 1000 }\n'
        'values."robot.lengths_m[2]" = { from = 0.1, to = 0.3, count = 1000 }',
    ],
)
def test_huge_counts_are_refused_without_being_built(tmp_path, cli, monkeypatch, values):
    from planar_tui.sweep import points, spec

    def not_built(*args, **kwargs):
        raise AssertionError("values built")

    monkeypatch.setattr(spec, "_read_values", not_built)
    monkeypatch.setattr(points, "unit_sample", not_built)
    text = f'[[sweep]]\njob = "torques"\n{values}\nmax_points = 1000000\n'
    preset = write(tmp_path, "p.toml", TORQUES, text, **TORQUES_BASE)
    result = cli("sweep", preset, "--out-dir", tmp_path / "out", "--workers", "1")
    assert result.exit_code == ExitCode.BAD_INPUT
    assert "more than max_points = 1,000,000" in one_line(result)


def test_a_100000_point_sweep_starts_after_checking_a_sample_of_points(tmp_path, monkeypatch):
    """Points are made as they are reached: before the first point finishes, only the
    points checked up front (at most MAX_CHECKS) and the first one were parsed."""
    from planar_tui.errors import Cancelled
    from planar_tui.presets import load_preset
    from planar_tui.progress import Progress
    from planar_tui.sweep import points as points_module
    from planar_tui.sweep.service import run_sweep
    from planar_tui.sweep.spec import parse_sweeps

    text = """[[sweep]]
job = "torques"
values."robot.masses_kg[2]" = { from = 1, to = 2, count = 1000 }
values."robot.lengths_m[1]" = { from = 0.1, to = 0.3, count = 100 }
output = "big.csv"
"""
    preset = write(tmp_path, "p.toml", TORQUES, text, **TORQUES_BASE)
    (sweep,) = parse_sweeps(load_preset(preset))
    made = []
    real = points_module.point_job
    monkeypatch.setattr(points_module, "point_job", lambda s, v: made.append(v) or real(s, v))
    progress = Progress()
    seen = []

    def first(outcome) -> None:
        seen.append((outcome.number, len(made)))
        progress.request_cancel()

    with pytest.raises(Cancelled):
        run_sweep(sweep, progress, out_dir=tmp_path / "out", on_outcome=first)
    assert sweep.point_count == 100_000
    (number, parsed), *_ = seen
    assert number == 1
    assert parsed <= points_module.MAX_CHECKS + 1


@pytest.mark.parametrize(
    "text", ["", "# nothing\n", "[robot]\nlengths_m = [0.3]\nmasses_kg = [1.0]\n"]
)
def test_a_preset_with_nothing_to_run_is_one_line_exit_2(tmp_path, cli, text):
    preset = tmp_path / "empty.toml"
    preset.write_text(text)
    result = cli("run", preset, "--out-dir", tmp_path / "out")
    assert result.exit_code == ExitCode.BAD_INPUT
    line = one_line(result)
    assert line.startswith(f"error: {preset}: (file): has no job and no [[sweep]] table")
    assert not (tmp_path / "out").exists()

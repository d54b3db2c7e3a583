"""Saving presets: load → dump → load gives the same robots and jobs, for every preset."""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import pytest

from planar_tui.preset_writer import dump_preset, format_value
from planar_tui.presets import load_preset, parse_preset
from planar_tui.resources import bundled_presets

DATA = Path(__file__).parent / "data" / "app"
PRESETS = [*bundled_presets(), *sorted(DATA.glob("*.toml"))]


@pytest.mark.parametrize("path", PRESETS, ids=lambda p: p.name)
def test_round_trip_gives_equal_jobs(path, tmp_path):
    original = load_preset(path)
    copy = tmp_path / path.name
    copy.write_text(dump_preset(original, "round trip"), encoding="utf-8")
    again = load_preset(copy)
    assert again.robots == original.robots
    assert len(again.jobs) == len(original.jobs)
    for new, old in zip(again.jobs, original.jobs, strict=True):
        assert (new.kind, new.index, new.robot, new.spec, new.output) == (
            old.kind,
            old.index,
            old.robot,
            old.spec,
            old.output,
        )
        assert new.label.split(":")[1] == old.label.split(":")[1]
    assert copy.read_text().startswith("# round trip\n")


def test_a_job_with_its_own_robot_keeps_it(tmp_path):
    text = """
[robot]
lengths_m = [1.0]
masses_kg = [1.0]

[[simulate]]
duration_s = 0.1
step_s = 0.01

[[simulate]]
duration_s = 0.1
step_s = 0.01
[simulate.robot]
lengths_m = [0.5, 0.25]
masses_kg = [2.0, 1.0]
"""
    path = tmp_path / "own.toml"
    path.write_text(text)
    preset = load_preset(path)
    dumped = dump_preset(preset)
    assert dumped.count("[simulate.robot]") == 1
    again = parse_preset(path, tomllib.loads(dumped))
    assert [job.robot for job in again.jobs] == [job.robot for job in preset.jobs]
    assert again.jobs[1].robot.n_links == 2


@pytest.mark.parametrize(
    "value",
    [
        0.1,
        1e-4,
        2.5e-300,
        -0.0,
        7,
        True,
        'a "quoted" name',
        [1, 2.5],
        [[1.0, 2.0], [3.0]],
        {"a": 1.5, "b": [1, 2]},
    ],
)
def test_format_value_is_exact_toml(value):
    parsed = tomllib.loads(f"v = {format_value(value)}")["v"]
    assert parsed == value
    if isinstance(value, float):
        assert math.copysign(1, parsed) == math.copysign(1, value)


def test_decimal_settings_survive_the_round_trip_exactly(tmp_path):
    """Values are kept in the units the preset gave (0.9 mm must not come back as
    0.9000000000000001 after a mm -> m -> mm conversion)."""
    text = """
[robot]
lengths_m = [0.303, 0.214]
masses_kg = [1.126, 0.796]

[sensitivity]
tolerance_length_mm = 0.9
tolerance_mass_g = 1.3
samples = 64
methods = ["sobol"]
"""
    path = tmp_path / "decimals.toml"
    path.write_text(text)
    saved = tomllib.loads(dump_preset(load_preset(path), "decimals"))
    assert saved["sensitivity"]["tolerance_length_mm"] == 0.9
    assert saved["sensitivity"]["tolerance_mass_g"] == 1.3

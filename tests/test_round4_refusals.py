"""Hostile round 4 (issue 33): what the CLI reads is refused in one line with exit code 2
and no traceback, or computed right: a torques job's memory estimated from its rows,
optimisation variables that overlap, empty paths, leg limits and lengths at the edge of
the floats."""

from __future__ import annotations

from pathlib import Path

import pytest

from planar_tui import limits
from planar_tui.dynamics.torques import BYTES_PER_STATE_CELL, torques_estimate
from planar_tui.errors import PresetError
from planar_tui.presets import load_preset

ROBOT = "[robot]\nlengths_m = [0.303, 0.214]\nmasses_kg = [1.126, 0.796]\n"


def refused(result, *parts: str) -> None:
    """Exit code 2, one line on stderr holding every part, no traceback."""
    assert result.exit_code == 2, result.output
    assert "Traceback" not in result.output
    assert len(result.stderr.strip().splitlines()) == 1, result.stderr
    for part in parts:
        assert part in result.stderr, (part, result.stderr)


def write(folder: Path, text: str, name: str = "p.toml") -> Path:
    path = folder / name
    path.write_text(text)
    return path


# -- torques: memory from the rows ---------------------------------------------------------
def test_a_torques_job_estimates_its_memory_from_its_rows():
    memory, seconds = torques_estimate(5_000_000, 2)
    assert memory == 5_000_000 * 8 * BYTES_PER_STATE_CELL  # 8 cells a state of a 2R
    assert seconds > 0


def test_a_torques_job_over_the_memory_limit_is_refused(tmp_path, monkeypatch):
    monkeypatch.setattr(limits, "memory_limit_bytes", lambda: 2**20)
    rows = "[" + ", ".join(["[0, 1]"] * 500) + "]"
    path = write(tmp_path, ROBOT + f"\n[torques]\ntheta_deg = {rows}\n")
    with pytest.raises(PresetError) as caught:
        load_preset(path)
    assert str(caught.value) == (
        f"error: {path}: torques.theta_deg: 500 states of 2 links needs about 1.22 MiB of "
        "memory (limit 1 MiB) (expected fewer states)"
    )
    rows = "[" + ", ".join(["[0, 1]"] * 400) + "]"  # 400 × 8 × 320 bytes: under 1 MiB
    write(tmp_path, ROBOT + f"\n[torques]\ntheta_deg = {rows}\n")
    assert load_preset(path).jobs[0].kind == "torques"


# -- optimisation and sweep variables that overlap -----------------------------------------
TORQUES = ROBOT + "\n[torques]\ntheta_deg = [[0, 10]]\n"


@pytest.mark.parametrize(
    ("variables", "problem"),
    [
        (
            'variables."robot.masses_kg" = { choices = [[1.0, 0.8], [1.1, 0.7]] }\n'
            'variables."robot.masses_kg[1]" = { from = 0.5, to = 2 }\n',
            'optimise[1].variables."robot.masses_kg[1]": overlaps robot.masses_kg: one names a'
            " value within the other (expected each value once, by one key path)",
        ),
        (
            'variables."robot.masses_kg[1]" = { from = 0.5, to = 2 }\n'
            'variables."robot.masses_kg" = { choices = [[1.0, 0.8], [1.1, 0.7]] }\n',
            'optimise[1].variables."robot.masses_kg": overlaps robot.masses_kg[1]',
        ),
        (
            'variables."theta_deg[1]" = { choices = [[0, 10], [5, 5]] }\n'
            'variables."robot.masses_kg[1]" = { from = 0.5, to = 2 }\n'
            'coarse = { "theta_deg[1][2]" = 3 }\n',
            'optimise[1].coarse."theta_deg[1][2]": overlaps theta_deg[1]',
        ),
        (
            'variables."robot.masses_kg[1]" = { from = 0.5, to = 2, fixed_sum = '
            '{ "robot.masses_kg" = 2 } }\n',
            'fixed_sum."robot.masses_kg": overlaps robot.masses_kg[1]',
        ),
    ],
)
def test_optimisation_variables_that_overlap_are_refused(tmp_path, cli, variables, problem):
    preset = write(
        tmp_path,
        TORQUES + '\n[[optimise]]\njob = "torques"\noutput = "o.csv"\n'
        + variables + 'minimise = "tau1_abs_max_Nm"\n',
    )  # fmt: skip
    result = cli("optimise", preset, "--out-dir", tmp_path, "--workers", "1")
    refused(result, f"error: {preset}: ", problem)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["p.toml"]


def test_sweep_key_paths_that_overlap_are_refused(tmp_path, cli):
    preset = write(
        tmp_path,
        TORQUES + '\n[[sweep]]\njob = "torques"\n'
        'values."robot.masses_kg" = [[1.0, 0.8], [1.1, 0.7]]\n'
        'values."robot.masses_kg[2]" = [0.5, 0.6]\n',
    )  # fmt: skip
    result = cli("sweep", preset, "--out-dir", tmp_path)
    refused(result, 'sweep[1].values."robot.masses_kg[2]": overlaps robot.masses_kg')

"""Path jobs in ``[[optimise]]``: the peak torque of a 3-RRR actuator (the path job's
summary column ``tau1_abs_max_Nm``) minimised over the platform's mass, and held by a
constraint. The starting design's figure comes from a separate ``planar-tui run`` of the
same job; the inverse dynamics are linear in the masses, so ``tau1`` is affine in the
platform mass at every time and its peak |.| a convex function of it: the optimum over
``[0, 3]`` kg can be no worse than either end nor the starting design (1.5 kg)."""

from __future__ import annotations

import csv

import numpy as np
import pytest

from tests.test_path3rrr import JOB, ROBOT

OPTIMISE = """
[[optimise]]
job = "path3rrr"
variables."robot3rrr.platform_mass_kg" = { from = 0.0, to = 3.0 }
minimise = "tau1_abs_max_Nm"
constraints = ["tau2_abs_max_Nm <= 100"]
budget = 8
population = 4
output = "opt.csv"
"""


def rows(path):
    with open(path, newline="") as stream:
        return list(csv.DictReader(stream))


@pytest.mark.slow  # worker processes compile the kernels: a minute on a loaded machine
def test_an_optimise_table_minimises_a_path_jobs_peak_torque(cli, tmp_path):
    job = JOB.replace('plot = "p.png"\n', "")
    preset = tmp_path / "p.toml"
    preset.write_text(ROBOT + job + OPTIMISE, encoding="utf-8")
    start = cli("run", preset, "--out-dir", tmp_path / "start")
    assert start.exit_code == 0, start.output
    path = np.array(
        [[float(r["tau1_Nm"]), float(r["tau2_Nm"])] for r in rows(tmp_path / "start" / "p.csv")]
    )
    start_peak = float(np.abs(path[:, 0]).max())

    result = cli("optimise", preset, "--out-dir", tmp_path / "opt", "--workers", "1")
    assert result.exit_code == 0, result.output
    evaluations = rows(tmp_path / "opt" / "opt.csv")
    assert len(evaluations) == 8
    masses = [float(r["robot3rrr.platform_mass_kg"]) for r in evaluations]
    assert all(0.0 <= m <= 3.0 for m in masses)
    assert len(set(masses)) > 1  # the designs vary
    for row in evaluations:  # the constraint's column is reported and decides feasibility
        assert (row["feasible"] == "true") == (float(row["tau2_abs_max_Nm"]) <= 100)
    (best,) = rows(tmp_path / "opt" / "opt-optimum.csv")
    best_peak = float(best["tau1_abs_max_Nm"])
    assert best_peak <= start_peak + 1e-9
    assert best_peak <= min(float(r["tau1_abs_max_Nm"]) for r in evaluations) + 1e-9

"""Optimisation over the certified columns: the 3-RRR's certified dexterous area
(``dexterous_area_inside_cm2``) with the leg length fixed (``fixed_sum``: proximal + distal
= 60 cm), and a path's peak torque under the constraint that its certificate says ``yes``
(``path_certified >= 1``). Each optimum is checked against a brute-force grid over the same
small design space, every design run here as its own job."""

from __future__ import annotations

import csv

import pytest

from planar_tui.batch import prepare_jobs, run_job
from planar_tui.presets import load_preset
from tests.test_path3rrr import ROBOT

pytestmark = pytest.mark.slow  # every design of the grid is a job

PROXIMAL_CM = tuple(range(24, 37))  # integers: the optimiser's space, every point
DEXTEROUS = """[robot3rrr]
base_side_cm = 120
platform_side_cm = 40
proximal_cm = {proximal}
distal_cm = {distal}

[[workspace]]
form = "arc-distance"
precision_cm = 1.0
joint_limits_deg = [[0, 90], [90, 180], [225, 315]]
orientation_deg = 0
geometric_reference = false
elbow = [1, -1, 1]
kappa_max = 4
output = "w.csv"
"""
OPTIMISE_DEXTEROUS = """
[[optimise]]
job = "workspace"
variables."robot3rrr.proximal_cm" = { from = 24, to = 36, integer = true, fixed_sum = { "robot3rrr.distal_cm" = 60 } }
maximise = "dexterous_area_inside_cm2"
budget = 32
population = 8
seed = 1
output = "opt.csv"
"""
TO_X_CM = (40, 44, 48, 52, 56)
PATH = """[[path3rrr]]
from_pose = [36, 5, -2]
to_pose = [{x}, 9, 2]
duration_s = 0.5
steps = 20
elbow = [1, -1, -1]
joint_limits_deg = [[20, 70], [110, 160], [245, 295]]
kappa_max = 60
output = "p.csv"
"""
OPTIMISE_PATH = f"""
[[optimise]]
job = "path3rrr"
variables."to_pose[1]" = {{ choices = {list(TO_X_CM)} }}
maximise = "tau1_abs_max_Nm"
constraints = ["path_certified >= 1"]
budget = 16
population = 8
seed = 1
output = "opt.csv"
"""


def one_job(tmp_path, text):
    path = tmp_path / "one.toml"
    path.write_text(text, encoding="utf-8")
    (job,) = prepare_jobs(load_preset(path).jobs)
    return run_job(job)


def optimum(tmp_path, cli, text):
    preset = tmp_path / "opt.toml"
    preset.write_text(text, encoding="utf-8")
    result = cli("optimise", preset, "--out-dir", tmp_path, "--workers", "1")
    assert result.exit_code == 0, result.output
    with open(tmp_path / "opt-optimum.csv", newline="", encoding="utf-8") as handle:
        (best,) = list(csv.DictReader(handle))
    return best


def test_the_largest_dexterous_area_with_a_fixed_leg_length_is_the_grids(tmp_path, cli):
    areas = {}
    for p in PROXIMAL_CM:
        result = one_job(tmp_path, DEXTEROUS.format(proximal=p, distal=60 - p))
        areas[p] = result.dexterity.area_inside_cm2
    best_p = max(areas, key=areas.get)
    assert len(set(areas.values())) > 1  # the design matters
    best = optimum(tmp_path, cli, DEXTEROUS.format(proximal=30, distal=30) + OPTIMISE_DEXTEROUS)
    assert float(best["robot3rrr.proximal_cm"]) == best_p
    assert float(best["dexterous_area_inside_cm2"]) == pytest.approx(areas[best_p], rel=1e-12)


def test_the_peak_torque_of_a_certified_path_is_the_grids_best_certified(tmp_path, cli):
    verdicts, torque = {}, {}
    for x in TO_X_CM:
        result = one_job(tmp_path, ROBOT + PATH.format(x=x))
        verdicts[x] = result.certificate.certified
        torque[x] = float(abs(result.solution.effort[:, 0]).max())
    certified = [x for x in TO_X_CM if verdicts[x] == "yes"]
    assert certified and len(certified) < len(TO_X_CM)  # the constraint binds
    best_x = max(certified, key=torque.get)
    assert torque[best_x] < max(torque.values())  # the unconstrained best is not certified
    best = optimum(tmp_path, cli, ROBOT + PATH.format(x=44) + OPTIMISE_PATH)
    assert float(best["to_pose[1]"]) == best_x
    assert float(best["path_certified"]) == 1.0
    assert float(best["tau1_abs_max_Nm"]) == pytest.approx(torque[best_x], rel=1e-12)

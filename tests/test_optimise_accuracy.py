"""Optimisation over the accuracy columns: the 3-RRR's smallest certified worst-case error
(``accuracy_dx_max_cm``) with the leg length fixed (``fixed_sum``: proximal + distal =
60 cm) and at least :data:`AREA_CM2` of certified workspace
(``accuracy_certified_area_cm2``). The optimum is checked against a brute-force grid over
the same designs, every design run here as its own job."""

from __future__ import annotations

import pytest

from tests.test_optimise_certified import one_job, optimum

pytestmark = pytest.mark.slow  # every design of the grid is a job

PROXIMAL_CM = tuple(range(24, 37))  # integers: the optimiser's space, every point
AREA_CM2 = 150
ACCURATE = """[robot3rrr]
base_side_cm = 120
platform_side_cm = 40
proximal_cm = {proximal}
distal_cm = {distal}

[[workspace]]
form = "arc-distance"
precision_cm = 2.0
joint_limits_deg = [[0, 90], [90, 180], [225, 315]]
orientation_deg = 0
geometric_reference = false
elbow = [1, -1, 1]
accuracy = {{ actuator_deg = 0.1, tolerance_cm = 0.01 }}
output = "w.csv"
"""
OPTIMISE_ACCURATE = f"""
[[optimise]]
job = "workspace"
variables."robot3rrr.proximal_cm" = {{ from = 24, to = 36, integer = true, fixed_sum = {{ "robot3rrr.distal_cm" = 60 }} }}
minimise = "accuracy_dx_max_cm"
constraints = ["accuracy_certified_area_cm2 >= {AREA_CM2}"]
budget = 32
population = 8
seed = 1
output = "opt.csv"
"""


def test_the_smallest_worst_case_error_with_enough_certified_area_is_the_grids(tmp_path, cli):
    error, area = {}, {}
    for p in PROXIMAL_CM:
        outcome = one_job(tmp_path, ACCURATE.format(proximal=p, distal=60 - p)).accuracy
        error[p], area[p] = outcome.worst[0], outcome.certified_area_cm2
    feasible = [p for p in PROXIMAL_CM if area[p] >= AREA_CM2]
    assert feasible and len(feasible) < len(PROXIMAL_CM)  # the constraint binds
    best_p = min(feasible, key=error.get)
    assert error[best_p] > min(error.values())  # the unconstrained best is infeasible
    best = optimum(tmp_path, cli, ACCURATE.format(proximal=30, distal=30) + OPTIMISE_ACCURATE)
    assert float(best["robot3rrr.proximal_cm"]) == best_p
    assert float(best["accuracy_dx_max_cm"]) == pytest.approx(error[best_p], rel=1e-12)
    assert float(best["accuracy_certified_area_cm2"]) >= AREA_CM2

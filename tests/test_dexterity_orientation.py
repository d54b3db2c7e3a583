"""Dexterous regions over a range of orientations (``kappa_max`` with ``orientation_deg =
[lo, hi]``): a point is dexterous when every φ of the range closes the legs in the working
mode and has κ ≤ kappa_max. Checked against the float references of
:mod:`tests.test_dexterity` (the 3-RRR's elbows as circle intersections) and
:mod:`tests.test_dexterity_prismatic` (the 3-RPR's leg lengths, the 3-PRR's sliders), κ by
central differences, at every φ of a dense grid over the range: every sample of a box said
dexterous is dexterous at every φ; every grid point dexterous at every φ (with a margin)
lies in a kept box; a tiny box is never proved dexterous with kappa_max 0.1 % below its
worst κ over the range, nor outside 0.1 % above; that check fails with the pose-box test's
κ enclosure shrunk by 1 %
(:func:`tests.certified_path_reference.shrink_kappa`)."""

from __future__ import annotations

import numpy as np
import pytest

from planar_tui.workspace.paving.orientation_dexterity import range_evaluator
from planar_tui.workspace.prr import mechanism as prr
from planar_tui.workspace.rpr import mechanism as rpr
from planar_tui.workspace.rrr import mechanism as rrr
from tests.certified_path_reference import shrink_kappa
from tests.test_dexterity import covered, grid, joint_angles, run, samples
from tests.test_dexterity_prismatic import prr_actuators, rpr_actuators

RRR = """
[robot3rrr]
base_side_cm = 120
platform_side_cm = 40
proximal_cm = 30
distal_cm = 30
[workspace]
joint_limits_deg = [[-180, 180], [-180, 180], [-180, 180]]
precision_cm = {precision}
form = "arc-distance"
geometric_reference = false
orientation_deg = [-4, 6]
orientation_mode = "total"
elbow = [1, -1, 1]
kappa_max = 6
output = "ws.csv"
"""
RPR = """
[robot3rpr]
base_joints_cm = [[0, 0], [120, 0], [60, 103.92]]
platform_points_cm = [[0, 23.09], [-20, -11.55], [20, -11.55]]
[[workspace3rpr]]
leg_limits_cm = [[20, 100], [20, 100], [20, 100]]
precision_cm = {precision}
orientation_deg = [-10, 10]
orientation_mode = "total"
geometric_reference = false
kappa_max = 1.5
characteristic_length_cm = 25
output = "rpr.csv"
"""
PRR = """
[robot3prr]
[[workspace3prr]]
precision_cm = {precision}
orientation_deg = [-5, 5]
orientation_mode = "total"
slider_modes = [1, 1, 1]
geometric_reference = false
kappa_max = 6
output = "prr.csv"
"""
TEXTS = {"rrr": RRR, "rpr": RPR, "prr": PRR}
MECHANISMS = {"rrr": rrr.MECHANISM, "rpr": rpr.MECHANISM, "prr": prr.MECHANISM}
#: φ samples over the range (its ends among them).
PHI_SAMPLES = 41


def rrr_actuators(job):
    """``(x, y, phi) -> (valid, theta (3, ...))`` in the job's given elbow."""
    robot, spec = job.robot, job.spec
    legs = [
        (a, q, robot.proximal_cm, robot.distal_cm, sign, limits)
        for a, q, sign, limits in zip(
            robot.base_joints_cm(),
            robot.platform_points_cm(),
            spec.elbow,
            spec.limits_rad,
            strict=True,
        )
    ]
    return lambda x, y, phi: joint_angles(legs, x, y, phi)


def actuators_of(robot, job):
    if robot == "rrr":
        return rrr_actuators(job)
    if robot == "rpr":
        return rpr_actuators(job)
    return prr_actuators(job, job.spec.slider_modes)


def worst_kappa(actuators, x, y, phis, length_cm, step_cm=1e-6):
    """Whether the legs close at every φ of ``phis``, and the largest κ over them, at the
    points ``(x, y)``: κ of :math:`\\partial q / \\partial(x, y, L\\varphi)` by central
    differences (angle differences wrapped)."""
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    valid_all, worst = np.ones(x.shape, dtype=bool), np.ones(x.shape)
    for phi in phis:
        valid_all &= actuators(x, y, phi)[0]
        columns = []
        for dx, dy, dphi in ((step_cm, 0, 0), (0, step_cm, 0), (0, 0, step_cm / length_cm)):
            ahead = actuators(x + dx, y + dy, phi + dphi)[1]
            behind = actuators(x - dx, y - dy, phi - dphi)[1]
            columns.append(np.angle(np.exp(1j * (ahead - behind))) / (2 * step_cm))
        inverse = np.moveaxis(np.array(columns), (0, 1), (-1, -2))
        sigma = np.linalg.svd(inverse, compute_uv=False)
        with np.errstate(divide="ignore", invalid="ignore"):
            kappa = sigma[..., 0] / sigma[..., -1]
        worst = np.maximum(worst, np.where(np.isfinite(kappa), kappa, np.inf))
    return valid_all, worst


def phi_grid(job):
    lo, hi = job.spec.orientation_deg
    return np.radians(np.linspace(lo, hi, PHI_SAMPLES))


def check_inside_boxes(robot, job, outcome):
    """Every sample of a box said dexterous: legs closed and κ ≤ kappa_max at every φ."""
    x, y = samples(outcome.boxes[outcome.status == 2])
    valid, kappa = worst_kappa(actuators_of(robot, job), x, y, phi_grid(job), outcome.length_cm)
    ok = valid & (kappa <= outcome.kappa_max * (1 + 1e-6))
    assert ok.all(), f"{np.count_nonzero(~ok)} samples of dexterous boxes are not dexterous"


def check_dexterous_points_kept(robot, job, outcome, step_cm):
    """Every grid point dexterous at every φ (κ below kappa_max by 0.1 %) is kept."""
    xs, ys = grid(outcome, step_cm)
    x, y = (a.ravel() for a in np.meshgrid(xs, ys))
    valid, kappa = worst_kappa(actuators_of(robot, job), x, y, phi_grid(job), outcome.length_cm)
    good = valid & (kappa < outcome.kappa_max * (1 - 1e-3))
    assert good.any()
    lost = good & ~covered(outcome.boxes, xs, ys)
    assert not lost.any(), f"{np.count_nonzero(lost)} dexterous points in no kept box"


@pytest.mark.parametrize("robot", ["rrr", "rpr", "prr"])
def test_the_region_holds_at_every_orientation(tmp_path, robot):
    job, result = run(tmp_path, TEXTS[robot].format(precision=0.5))
    outcome = result.dexterity
    assert 0.0 < outcome.area_inside_cm2 <= outcome.area_kept_cm2
    assert outcome.area_kept_cm2 <= result.outcome.area_kept_cm2 + 1e-9  # in the workspace
    check_inside_boxes(robot, job, outcome)
    check_dexterous_points_kept(robot, job, outcome, 0.25)


def check_decisions(robot, job, outcome, shrink_by=None, count=12):
    """At tiny boxes about kept points (legs closed at every φ, worst κ ``ref`` over 401 φ
    of the range below ``kappa_max``): with a bound 0.1 % below ``ref`` no box is proved
    dexterous, with one 0.1 % above none is proved outside."""
    centres = outcome.boxes[:, [0, 2]] + 0.5 * (outcome.boxes[:, [1, 3]] - outcome.boxes[:, [0, 2]])
    lo, hi = job.spec.orientation_deg
    phis = np.radians(np.linspace(lo, hi, 401))
    valid, worst = worst_kappa(actuators_of(robot, job), *centres.T, phis, outcome.length_cm)
    good = valid & (worst < outcome.kappa_max)
    points, reference = centres[good], worst[good]
    step = max(1, len(points) // count)
    points, reference = points[::step], reference[::step]
    assert len(points) >= count // 2
    test = MECHANISMS[robot].path_box_test
    for (x, y), ref in zip(points, reference, strict=True):
        box = np.array([[x, x + 1e-4, y, y + 1e-4]])
        for bound, wrong in ((ref / 1.001, "dexterous"), (ref * 1.001, "outside")):
            evaluate = range_evaluator(
                lambda: test(job.robot, job.spec), np.radians([lo, hi]), bound, outcome.length_cm
            )
            verdict, kappa = evaluate(box)
            said = "dexterous" if verdict[0] == 2 and kappa[0, 1] <= bound else ""
            said = "outside" if verdict[0] == 0 else said
            assert said != wrong, (
                f"({x:.4g}, {y:.4g}) said {wrong} at κ_max = {bound:.6g}, worst κ {ref:.6g}"
            )


NARROW = {"rrr": "[-4, 6]", "rpr": "[-10, 10]", "prr": "[-5, 5]"}


@pytest.mark.parametrize("robot", ["rrr", "rpr", "prr"])
@pytest.mark.parametrize("shrink", [False, True])
def test_tiny_boxes_are_decided_about_the_worst_kappa(tmp_path, monkeypatch, robot, shrink):
    text = TEXTS[robot].format(precision=1.0).replace(NARROW[robot], "[-1, 1]")
    job, result = run(tmp_path, text)
    if not shrink:
        check_decisions(robot, job, result.dexterity)
        return
    shrink_kappa(monkeypatch, MECHANISMS[robot])
    with pytest.raises(AssertionError, match=r"said (dexterous|outside) at"):
        check_decisions(robot, job, result.dexterity)


def test_a_range_without_its_elbow_exits_2_with_one_line(cli, tmp_path):
    path = tmp_path / "d.toml"
    path.write_text(RRR.format(precision=1.0).replace("elbow = [1, -1, 1]\n", ""), "utf-8")
    result = cli("workspace", path, "--out-dir", tmp_path)
    assert result.exit_code == 2, result.output
    assert result.output.startswith("error: ") and result.output.count("\n") == 1
    assert "elbow: is not set with kappa_max and orientation_deg = [lo, hi]" in result.output
    assert not (tmp_path / "ws.csv").exists()

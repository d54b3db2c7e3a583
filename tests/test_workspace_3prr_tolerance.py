"""Tolerance-certified 3-PRR workspaces (``tolerance_cm``, ``tolerances_cm``,
``tolerance_mode`` on ``[[workspace3prr]]``): robust boxes against robots sampled within the
tolerances (a float leg test written here), the "some" region against every sampled robot's
workspace, zero tolerance against the nominal paving, and bad input."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from planar_tui.workspace.paving.levels import INSIDE
from tests.test_workspace_3prr import job_of, preset_text
from tests.test_workspace_3rpr import pave, refused
from tests.test_workspace_3rpr_tolerance import box_points, in_boxes

T_SLIDER_CM, T_PLATFORM_CM, T_DISTAL_CM = 0.8, 0.5, 0.6
TOLERANCES = (
    f"tolerances_cm = {{ slider_points_cm = {T_SLIDER_CM}, platform_points_cm = "
    f"{T_PLATFORM_CM}, distal_cm = {T_DISTAL_CM} }}\n"
)
PHI = 15.0


def tolerant_job(tmp_path, mode, tolerance=TOLERANCES):
    return job_of(tmp_path, phi=PHI, precision=1.0, extra=f'{tolerance}tolerance_mode = "{mode}"\n')


def robots(rng, count):
    """Per robot and leg ``a_x, a_y, b_x, b_y, kappa`` (count, 3, 5): every sign pattern of
    one leg's five shifts at the tolerances' corners on all legs, then random robots."""
    corners = np.array(list(itertools.product((-1.0, 1.0), repeat=5)))
    rows = [np.repeat(corner[None, :], 3, axis=0) for corner in corners]
    rows += [rng.uniform(-1.0, 1.0, size=(3, 5)) for _ in range(count)]
    scale = np.array([T_SLIDER_CM, T_SLIDER_CM, T_PLATFORM_CM, T_PLATFORM_CM, T_DISTAL_CM])
    return np.array(rows) * scale


def reached(job, points, shifts):
    """(robots, points): every leg closes, ``d_seg <= l + kappa <= d_end`` with the segment
    ``B + a + [lo, hi] u`` and the joint ``v + R(phi)(q + b)``."""
    robot = job.robot
    phi = math.radians(job.spec.orientation_deg)
    rot = np.array([[math.cos(phi), -math.sin(phi)], [math.sin(phi), math.cos(phi)]])
    ok = np.ones((len(shifts), len(points)), dtype=bool)
    for leg in range(3):
        a, b, kappa = shifts[:, leg, :2], shifts[:, leg, 2:4], shifts[:, leg, 4]
        angle = math.radians(robot.slider_angles_deg[leg])
        u = np.array([math.cos(angle), math.sin(angle)])
        lo, hi = robot.strokes_cm[leg]
        start = np.array(robot.slider_points_cm[leg]) + a + lo * u  # (robots, 2)
        joint = points[None] + ((np.array(robot.platform_points_cm[leg]) + b) @ rot.T)[:, None]
        rel = joint - start[:, None]  # (robots, points, 2)
        s = np.clip(rel @ u, 0.0, hi - lo)
        d_seg = np.hypot(*np.moveaxis(rel - s[..., None] * u, -1, 0))
        d_end = np.maximum(
            np.hypot(*np.moveaxis(rel, -1, 0)), np.hypot(*np.moveaxis(rel - (hi - lo) * u, -1, 0))
        )
        length = robot.distal_cm[leg] + kappa[:, None]
        ok &= (d_seg <= length) & (length <= d_end)
    return ok


def test_robust_inside_boxes_are_reached_by_every_sampled_robot(tmp_path):
    rng = np.random.default_rng(5)
    outcome = pave(tolerant_job(tmp_path, "all"))
    inside = outcome.boxes[outcome.status == INSIDE]
    assert len(inside) > 50
    assert reached(job_of(tmp_path, phi=PHI), box_points(inside, rng), robots(rng, 30)).all()


def test_the_some_region_holds_every_sampled_robots_workspace(tmp_path):
    rng = np.random.default_rng(13)
    job = tolerant_job(tmp_path, "some")
    outcome = pave(job)
    xlo, xhi, ylo, yhi = outcome.extent_cm
    points = np.stack([rng.uniform(xlo, xhi, 20000), rng.uniform(ylo, yhi, 20000)], axis=1)
    boundary = outcome.boxes[outcome.status != INSIDE] + np.array([-1.0, 1.0, -1.0, 1.0])
    points = np.concatenate([points, box_points(boundary, rng)])
    reached_by_one = reached(job, points, robots(rng, 30)).any(axis=0)
    assert reached_by_one.sum() > 1000 and not reached_by_one.all()
    assert in_boxes(points[reached_by_one], outcome.boxes).all()


def test_the_brackets_nest_robust_nominal_some(tmp_path):
    robust, some = pave(tolerant_job(tmp_path, "all")), pave(tolerant_job(tmp_path, "some"))
    nominal = pave(job_of(tmp_path, phi=PHI, precision=1.0))
    assert robust.area_kept_cm2 < nominal.area_kept_cm2 < some.area_kept_cm2
    assert robust.area_inside_cm2 < nominal.area_inside_cm2 < some.area_inside_cm2


@pytest.mark.parametrize("mode", ["all", "some"])
def test_zero_tolerance_is_the_nominal_paving_bit_for_bit(tmp_path, mode):
    zero = pave(tolerant_job(tmp_path, mode, tolerance="tolerance_cm = 0\n"))
    nominal = pave(job_of(tmp_path, phi=PHI, precision=1.0))
    assert np.array_equal(zero.boxes, nominal.boxes)
    assert np.array_equal(zero.status, nominal.status)


@pytest.mark.parametrize(
    ("job", "fragment"),
    [
        ('tolerance_mode = "some"', "tolerance_mode: is set without a tolerance"),
        ("tolerance_cm = 40", "tolerance_cm: is ±40 cm on distal_cm = 40 cm"),
        ("tolerances_cm = { base_joints_cm = 0.1 }", "tolerances_cm.base_joints_cm: unknown"),
        ("tolerance_cm = 0.1\nsingularities = true", "singularities: is True with a tolerance"),
        ("tolerance_cm = 0.1\ngeometric_reference = true", "geometric_reference: is true with"),
    ],
)
def test_bad_tolerance_input_is_one_line_exit_2(cli, tmp_path, job, fragment):
    refused(cli, tmp_path, "workspace3prr", preset_text("", job), fragment)

"""Tolerance-certified 3-RPR workspaces (``tolerance_cm``, ``tolerances_cm``,
``tolerance_mode`` on ``[[workspace3rpr]]``): robust boxes against robots sampled within the
tolerances (a float leg-distance test written here), the "some" region against every sampled
robot's workspace, zero tolerance against the nominal paving, and bad input."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from planar_tui.workspace.paving.levels import INSIDE
from tests.test_workspace_3rpr import job_of, pave, preset_text, refused

#: Tolerances large enough that the robust, nominal and "some" regions differ by many boxes.
T_BASE_CM, T_PLATFORM_CM = 0.8, 0.5
LIMITS = ((30, 80), (25, 85), (35, 75))
TOLERANCES = (
    f"tolerances_cm = {{ base_joints_cm = {T_BASE_CM}, platform_points_cm = {T_PLATFORM_CM} }}\n"
)


def tolerant_job(tmp_path, mode, tolerance=TOLERANCES, phi=20.0, precision=1.0):
    extra = f'{tolerance}tolerance_mode = "{mode}"\n'
    return job_of(tmp_path, limits=LIMITS, phi=phi, precision=precision, extra=extra)


def robots(rng, count):
    """Shifts ``(a, b)`` of the base joints and platform points, each (count, 3, 2): every
    sign pattern of one leg's four coordinates at the tolerances' corners on all legs, then
    random robots inside the tolerance box."""
    corners = np.array(list(itertools.product((-1.0, 1.0), repeat=4)))  # a_x, a_y, b_x, b_y
    rows = [np.repeat(corner[None, :], 3, axis=0) for corner in corners]
    rows += [rng.uniform(-1.0, 1.0, size=(3, 4)) for _ in range(count)]
    shifts = np.array(rows)
    return shifts[..., :2] * T_BASE_CM, shifts[..., 2:] * T_PLATFORM_CM


def leg_distances(job, points, a, b):
    """``|v + R(phi)(q_i + b_i) - (A_i + a_i)|`` for every robot, point and leg:
    (robots, points, 3)."""
    phi = math.radians(job.spec.orientation_deg)
    rot = np.array([[math.cos(phi), -math.sin(phi)], [math.sin(phi), math.cos(phi)]])
    base = np.array(job.robot.base_joints_cm)[None] + a  # (robots, 3, 2)
    platform = (np.array(job.robot.platform_points_cm)[None] + b) @ rot.T
    legs = points[None, :, None, :] + (platform - base)[:, None, :, :]
    return np.hypot(legs[..., 0], legs[..., 1])


def reached(job, points, a, b):
    """(robots, points): every leg's distance within its limits."""
    d = leg_distances(job, points, a, b)
    lo = np.array([row[0] for row in job.spec.leg_limits_cm])
    hi = np.array([row[1] for row in job.spec.leg_limits_cm])
    return np.all((d >= lo) & (d <= hi), axis=-1)


def box_points(boxes, rng, per_box=3):
    """Each box's four corners and ``per_box`` random points."""
    xlo, xhi, ylo, yhi = boxes.T
    corners = [np.stack([x, y], axis=1) for x in (xlo, xhi) for y in (ylo, yhi)]
    randoms = [
        np.stack([rng.uniform(xlo, xhi), rng.uniform(ylo, yhi)], axis=1) for _ in range(per_box)
    ]
    return np.concatenate(corners + randoms)


def in_boxes(points, boxes):
    x, y = points[:, :1], points[:, 1:]
    return np.any(
        (x >= boxes[:, 0]) & (x <= boxes[:, 1]) & (y >= boxes[:, 2]) & (y <= boxes[:, 3]), axis=1
    )


def test_robust_inside_boxes_are_reached_by_every_sampled_robot(tmp_path):
    rng = np.random.default_rng(7)
    outcome = pave(tolerant_job(tmp_path, "all"))
    inside = outcome.boxes[outcome.status == INSIDE]
    assert len(inside) > 50
    points = box_points(inside, rng)
    a, b = robots(rng, 40)
    assert reached(job_of(tmp_path, limits=LIMITS, phi=20.0), points, a, b).all()


def test_robust_outside_points_are_missed_by_the_robot_pushing_one_leg(tmp_path):
    """Outside the robust kept boxes, each point is missed by a robot of the tolerances: per
    leg, the one moving the leg point by ``gamma = t_A + t_q`` along the leg (a = -t_A n,
    b = t_q R^T n) lengthens or shortens that leg past its limit."""
    rng = np.random.default_rng(3)
    job = tolerant_job(tmp_path, "all")
    outcome = pave(job)
    xlo, xhi, ylo, yhi = outcome.extent_cm
    points = np.stack([rng.uniform(xlo, xhi, 4000), rng.uniform(ylo, yhi, 4000)], axis=1)
    points = points[~in_boxes(points, outcome.boxes)]
    nominal = leg_distances(job, points, np.zeros((1, 3, 2)), np.zeros((1, 3, 2)))[0]
    assert len(points) > 1000
    phi = math.radians(job.spec.orientation_deg)
    rot = np.array([[math.cos(phi), -math.sin(phi)], [math.sin(phi), math.cos(phi)]])
    base, platform = np.array(job.robot.base_joints_cm), np.array(job.robot.platform_points_cm)
    missed = np.zeros(len(points), dtype=bool)
    for leg, (lo, hi) in enumerate(job.spec.leg_limits_cm):
        u = points + rot @ platform[leg] - base[leg]
        n = u / np.hypot(u[:, :1], u[:, 1:])
        for sign in (1.0, -1.0):
            shift_a, shift_b = -T_BASE_CM * sign * n, T_PLATFORM_CM * sign * (n @ rot)
            assert np.all(np.abs(shift_a) <= T_BASE_CM) and np.all(np.abs(shift_b) <= T_PLATFORM_CM)
            leg_point = u + shift_b @ rot.T - shift_a  # v + R(q + b) - (A + a)
            d = np.hypot(leg_point[:, 0], leg_point[:, 1])
            missed |= (d < lo) | (d > hi)
        missed |= (nominal[:, leg] < lo) | (nominal[:, leg] > hi)
    assert missed.all()


def test_the_some_region_holds_every_sampled_robots_workspace(tmp_path):
    rng = np.random.default_rng(11)
    job = tolerant_job(tmp_path, "some")
    outcome = pave(job)
    xlo, xhi, ylo, yhi = outcome.extent_cm
    points = np.stack([rng.uniform(xlo, xhi, 20000), rng.uniform(ylo, yhi, 20000)], axis=1)
    boundary = outcome.boxes[outcome.status != INSIDE] + np.array([-1.0, 1.0, -1.0, 1.0])
    points = np.concatenate([points, box_points(boundary, rng)])  # near the region's edge
    a, b = robots(rng, 40)
    reached_by_one = reached(job, points, a, b).any(axis=0)
    assert reached_by_one.sum() > 3000 and not reached_by_one.all()
    assert in_boxes(points[reached_by_one], outcome.boxes).all()


def test_the_brackets_nest_robust_nominal_some(tmp_path):
    robust, some = pave(tolerant_job(tmp_path, "all")), pave(tolerant_job(tmp_path, "some"))
    nominal = pave(job_of(tmp_path, limits=LIMITS, phi=20.0, precision=1.0))
    assert robust.area_kept_cm2 < nominal.area_kept_cm2 < some.area_kept_cm2
    assert robust.area_inside_cm2 < nominal.area_inside_cm2 < some.area_inside_cm2


@pytest.mark.parametrize("mode", ["all", "some"])
def test_zero_tolerance_is_the_nominal_paving_bit_for_bit(tmp_path, mode):
    zero = pave(tolerant_job(tmp_path, mode, tolerance="tolerance_cm = 0\n"))
    nominal = pave(job_of(tmp_path, limits=LIMITS, phi=20.0, precision=1.0))
    assert np.array_equal(zero.boxes, nominal.boxes)
    assert np.array_equal(zero.status, nominal.status)
    assert zero.area_inside_cm2 == nominal.area_inside_cm2
    assert zero.area_kept_cm2 == nominal.area_kept_cm2


@pytest.mark.parametrize(
    ("job", "fragment"),
    [
        ('tolerance_mode = "all"', "tolerance_mode: is set without a tolerance"),
        ("tolerance_cm = -0.1", "workspace3rpr[1].tolerance_cm"),
        ('tolerance_cm = 0.1\ntolerance_mode = "most"', "workspace3rpr[1].tolerance_mode"),
        ("tolerances_cm = { proximal_cm = 0.1 }", "tolerances_cm.proximal_cm: unknown quantity"),
        ("tolerance_cm = 0.1\nsingularities = true", "singularities: is True with a tolerance"),
        ("tolerance_cm = 0.1\ngeometric_reference = true", "geometric_reference: is true with"),
        ('tolerance_cm = 0.1\nform = "geometric"', "form: is 'geometric' with a tolerance"),
    ],
)
def test_bad_tolerance_input_is_one_line_exit_2(cli, tmp_path, job, fragment):
    refused(cli, tmp_path, "workspace3rpr", preset_text("", job), fragment)

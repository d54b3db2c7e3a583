"""Orientation ranges of the 3-PRR (``orientation_deg = [lo, hi]`` with ``orientation_mode``):
the certified bracket against float point tests at many sampled orientations on random
geometries (widened or narrowed by the sampling's chord bound), a degenerate range equal to
the constant-orientation result, thread-count invariance, bad input and the CLI."""

from __future__ import annotations

import math

import numpy as np
import pytest

from planar_tui.workspace.paving.layout import PAPER_B_BASE_CM, PAPER_B_PLATFORM_CM
from planar_tui.workspace.prr.job import Spec3PRR
from planar_tui.workspace.prr.robot import Robot3PRR
from tests.test_workspace_3prr import preset_text
from tests.test_workspace_3rpr import refused
from tests.test_workspace_3rpr_orientation import (
    RANGE_ERRORS,
    assert_degenerate_is_constant,
    assert_points_bracketed,
    assert_range_command,
    assert_thread_invariant,
    chord_bound,
    pave,
)


def jitter(points, rng, width):
    return tuple(tuple(float(v) for v in np.add(p, rng.uniform(-width, width, 2))) for p in points)


def random_case(seed):
    """A random 3-PRR about the bundled design and an orientation range."""
    rng = np.random.default_rng(seed)
    lows = rng.uniform(-10.0, 30.0, 3)
    robot = Robot3PRR(
        slider_points_cm=jitter(PAPER_B_BASE_CM, rng, 15.0),
        slider_angles_deg=tuple(
            float(a) for a in np.add((0.0, 120.0, 240.0), rng.uniform(-20, 20, 3))
        ),
        strokes_cm=tuple((float(lo), float(lo + rng.uniform(60.0, 110.0))) for lo in lows),
        distal_cm=tuple(float(v) for v in rng.uniform(30.0, 60.0, 3)),
        platform_points_cm=jitter(PAPER_B_PLATFORM_CM, rng, 10.0),
    )
    lo = float(rng.uniform(-60.0, 60.0))
    return robot, (lo, lo + float(rng.uniform(3.0, 40.0)))


def spec_of(phi, mode, precision=2.0, **changes):
    return Spec3PRR(
        orientation_deg=phi,
        orientation_mode=mode,
        precision_cm=precision,
        geometric_reference=False,
        **changes,
    )


def feasible(robot, angle, points, shift):
    """Float test at the positions ``points`` (n, 2): every leg has ``d_seg <= l + shift``
    and ``d_end >= l - shift`` (the segment distance and the far end's)."""
    c, s = math.cos(angle), math.sin(angle)
    ok = np.ones(len(points), dtype=bool)
    for (bx, by), a, (lo, hi), length, (qx, qy) in zip(
        robot.slider_points_cm,
        robot.slider_angles_deg,
        robot.strokes_cm,
        robot.distal_cm,
        robot.platform_points_cm,
        strict=True,
    ):
        ux, uy = math.cos(math.radians(a)), math.sin(math.radians(a))
        px = points[:, 0] + c * qx - s * qy - bx
        py = points[:, 1] + s * qx + c * qy - by
        t = np.clip(px * ux + py * uy, lo, hi)
        d_seg = np.hypot(px - t * ux, py - t * uy)
        d_end = np.maximum(
            np.hypot(px - lo * ux, py - lo * uy), np.hypot(px - hi * ux, py - hi * uy)
        )
        ok &= (d_seg <= length + shift) & (d_end >= length - shift)
    return ok


@pytest.mark.parametrize("mode", ["maximal", "total"])
@pytest.mark.parametrize("seed", range(4))
def test_random_geometries_bracket_the_sampled_reference(seed, mode):
    robot, phi = random_case(seed)
    outcome = pave(robot, spec_of(phi, mode))

    def closes(angle, points, shift):
        return feasible(robot, angle, points, shift)

    r = chord_bound(robot.platform_points_cm, phi)
    assert_points_bracketed(outcome, mode, phi, closes, r, seed)


@pytest.mark.parametrize("mode", ["maximal", "total"])
@pytest.mark.parametrize("seed", range(3))
def test_a_degenerate_range_is_the_constant_orientation_result(seed, mode):
    """``[φ, φ]`` (built in code: a preset refuses it) gives the constant-orientation job's
    boxes and areas at φ, refinement and the leaf check included."""
    robot, phi = random_case(seed)
    assert_degenerate_is_constant(robot, spec_of(phi[0], None, refine_precision_cm=1.0), mode)


def test_maximal_holds_total_and_the_middle_orientation():
    robot, phi = random_case(5)
    maximal, total = pave(robot, spec_of(phi, "maximal")), pave(robot, spec_of(phi, "total"))
    single = pave(robot, spec_of(0.5 * (phi[0] + phi[1]), None))
    assert total.area_inside_cm2 <= single.area_kept_cm2
    assert 0.0 < single.area_inside_cm2 <= maximal.area_kept_cm2


@pytest.mark.parametrize("mode", ["maximal", "total"])
def test_the_boxes_do_not_depend_on_the_thread_count(mode):
    robot, phi = random_case(1)
    assert_thread_invariant(robot, spec_of(phi, mode, precision=1.0, refine_precision_cm=0.5))


@pytest.mark.parametrize(("job", "fragment"), [e for e in RANGE_ERRORS if "[30, 10]" not in e[0]])
def test_bad_range_settings_are_one_line_errors(cli, tmp_path, job, fragment):
    refused(cli, tmp_path, "workspace3prr", preset_text("", job), fragment)


def test_the_command_paves_a_range_says_so_and_plots_it(cli, tmp_path):
    job = 'orientation_deg = [10, 30]\norientation_mode = "maximal"'
    assert_range_command(cli, tmp_path, "workspace3prr", preset_text("", job), "maximal")

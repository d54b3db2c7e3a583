"""Orientation ranges of the 3-RPR (``orientation_deg = [lo, hi]`` with ``orientation_mode``):
the certified bracket against a sampled reference on random geometries (shapely polygons of
the annuli at many orientations, widened or narrowed by the sampling's chord bound, and float
point tests), a degenerate range equal to the constant-orientation result, thread-count
invariance, bad input and the CLI."""

from __future__ import annotations

import csv
import dataclasses
import math

import numpy as np
import pytest

from planar_tui.progress import Progress
from planar_tui.workspace.paving.layout import PAPER_B_BASE_CM, PAPER_B_PLATFORM_CM
from planar_tui.workspace.paving.levels import INSIDE, BoxBudget
from planar_tui.workspace.paving.runner import compute_planar
from planar_tui.workspace.rpr.job import Spec3RPR
from planar_tui.workspace.rpr.robot import Robot3RPR, annulus
from tests.conftest import on_one_and_two_threads
from tests.test_workspace_3rpr import preset_text, refused
from tests.test_workspace_orientation import _Job, assert_bracketed

SAMPLES = 48


def pave(robot, spec):
    return compute_planar(robot, spec, BoxBudget(_Job(spec), Progress()))


def random_case(seed):
    """A random 3-RPR about paper B's scale, leg limits and an orientation range."""
    rng = np.random.default_rng(seed)
    base = tuple(
        tuple(float(v) for v in np.add(a, rng.uniform(-15, 15, 2))) for a in PAPER_B_BASE_CM
    )
    platform = tuple(
        tuple(float(v) for v in np.add(q, rng.uniform(-10, 10, 2))) for q in PAPER_B_PLATFORM_CM
    )
    lows = rng.uniform(10.0, 50.0, 3)
    limits = tuple((float(lo), float(lo + rng.uniform(40.0, 70.0))) for lo in lows)
    lo = float(rng.uniform(-60.0, 60.0))
    phi = (lo, lo + float(rng.uniform(3.0, 40.0)))
    return Robot3RPR(base_joints_cm=base, platform_points_cm=platform), limits, phi


def spec_of(limits, phi, mode, precision=2.0, **changes):
    return Spec3RPR(
        leg_limits_cm=limits,
        orientation_deg=phi,
        orientation_mode=mode,
        precision_cm=precision,
        geometric_reference=False,
        **changes,
    )


def sampled_phis(phi):
    lo, hi = (math.radians(v) for v in phi)
    return [lo + (hi - lo) * k / SAMPLES for k in range(SAMPLES + 1)]


def at_samples(robot, limits, phi, shift, outward):
    """Per sampled orientation, the intersection of the annuli of ``[lo - shift, hi +
    shift]`` (outer or inner polygons)."""
    from shapely import intersection_all

    polygons = []
    for angle in sampled_phis(phi):
        centres = robot.centres_cm(angle)
        polygons.append(
            intersection_all(
                [
                    annulus(c, max(0.0, lo - shift), hi + shift, 256, outward)
                    for c, (lo, hi) in zip(centres, limits, strict=True)
                ]
            )
        )
    return polygons


def reference(robot, limits, phi, mode):
    """``(inner, outer)`` with ``inner ⊆ W ⊆ outer``: every φ of the range is within half a
    step of a sample, so each leg's distance moves by at most ``r = 2 |q|max sin(step / 4)``
    (the chord); the maximal workspace lies in the union over the samples of the annuli
    widened by ``r`` and holds the union of the sampled ones, the total workspace lies in
    the intersection of the sampled ones and holds that of the annuli narrowed by ``r``."""
    from shapely import intersection_all, union_all

    r = chord_bound(robot.platform_points_cm, phi)
    if mode == "maximal":
        inner = union_all(at_samples(robot, limits, phi, 0.0, False))
        outer = union_all(at_samples(robot, limits, phi, r, True))
    else:
        inner = intersection_all(at_samples(robot, limits, phi, -r, False))
        outer = intersection_all(at_samples(robot, limits, phi, 0.0, True))
    return inner, outer


def feasible(robot, limits, angle, points, shift=0.0):
    """Float test: every leg closes at the positions ``points`` (n, 2) and the orientation,
    with its limits widened by ``shift`` (narrowed if negative)."""
    ok = np.ones(len(points), dtype=bool)
    for (cx, cy), (lo, hi) in zip(robot.centres_cm(angle), limits, strict=True):
        d = np.hypot(points[:, 0] - cx, points[:, 1] - cy)
        ok &= (lo - shift <= d) & (d <= hi + shift)
    return ok


def in_boxes(boxes, points):
    """Which of ``points`` (n, 2) lie in one of the boxes (rows ``x_lo, x_hi, y_lo, y_hi``)."""
    x, y = points[:, 0:1], points[:, 1:2]
    b = boxes[:, :4]
    return ((b[:, 0] <= x) & (x <= b[:, 1]) & (b[:, 2] <= y) & (y <= b[:, 3])).any(axis=1)


def chord_bound(points, phi):
    """How far a leg length moves between φ and the nearest of the sampled orientations:
    ``2 |q|max sin(step / 4)`` (plus round-off)."""
    step = math.radians(phi[1] - phi[0]) / SAMPLES
    return 2.0 * max(math.hypot(*q) for q in points) * math.sin(step / 4.0) * (1 + 1e-9) + 1e-9


def assert_points_bracketed(outcome, mode, phi, closes, r, seed):
    """Float point tests of a range paving, independent of polygons: ``closes(angle,
    points, shift)`` is the float test with the leg bounds widened by ``shift``, ``r`` the
    chord bound. Maximal: a point closing at some sampled φ lies in a kept box, a point of an
    inside box closes, widened by r, at some sampled φ. Total: a point of an inside box
    closes at every sampled φ, a point closing, narrowed by r, at every one is kept."""
    rng = np.random.default_rng(100 + seed)
    x0, x1, y0, y1 = outcome.extent_cm
    points = np.column_stack([rng.uniform(x0, x1, 20000), rng.uniform(y0, y1, 20000)])
    angles = sampled_phis(phi)
    exact = np.array([closes(a, points, 0.0) for a in angles])
    inside = in_boxes(outcome.boxes[outcome.status == INSIDE], points)
    kept = in_boxes(outcome.boxes, points)
    if mode == "maximal":
        widened = np.array([closes(a, points, r) for a in angles])
        assert exact.any(axis=0).any() and kept[exact.any(axis=0)].all()
        assert inside.any() and widened.any(axis=0)[inside].all()
    else:
        narrowed = np.array([closes(a, points, -r) for a in angles])
        assert inside.any() and exact[:, inside].all()
        assert kept[narrowed.all(axis=0)].all()


@pytest.mark.parametrize("mode", ["maximal", "total"])
@pytest.mark.parametrize("seed", range(4))
def test_random_geometries_bracket_the_sampled_reference(seed, mode):
    robot, limits, phi = random_case(seed)
    outcome = pave(robot, spec_of(limits, phi, mode))
    inner, outer = reference(robot, limits, phi, mode)
    assert_bracketed(outcome, inner, outer)

    def closes(angle, points, shift):
        return feasible(robot, limits, angle, points, shift)

    r = chord_bound(robot.platform_points_cm, phi)
    assert_points_bracketed(outcome, mode, phi, closes, r, seed)


def test_maximal_holds_total_and_each_single_orientation_between():
    robot, limits, phi = random_case(7)
    maximal = pave(robot, spec_of(limits, phi, "maximal"))
    total = pave(robot, spec_of(limits, phi, "total"))
    single = pave(robot, spec_of(limits, 0.5 * (phi[0] + phi[1]), None))
    assert total.area_inside_cm2 <= single.area_kept_cm2
    assert single.area_inside_cm2 <= maximal.area_kept_cm2
    assert total.area_inside_cm2 <= maximal.area_kept_cm2
    assert maximal.area_kept_cm2 > single.area_inside_cm2 > 0.0


@pytest.mark.parametrize("mode", ["maximal", "total"])
@pytest.mark.parametrize("seed", range(3))
def test_a_degenerate_range_is_the_constant_orientation_result(seed, mode):
    """``[φ, φ]`` (built in code: a preset refuses it) gives the boxes and areas of the
    constant-orientation job at φ, refinement included."""
    robot, limits, phi = random_case(seed)
    one = spec_of(limits, phi[0], None, refine_precision_cm=1.0)
    assert_degenerate_is_constant(robot, one, mode)


def assert_degenerate_is_constant(robot, one, mode):
    """The spec ``one`` (one orientation φ) and ``[φ, φ]`` in ``mode`` pave alike."""
    phi = one.orientation_deg
    ranged = dataclasses.replace(one, orientation_deg=(phi, phi), orientation_mode=mode)
    a, b = pave(robot, one), pave(robot, ranged)
    assert np.array_equal(a.boxes, b.boxes) and np.array_equal(a.status, b.status)
    assert (a.area_inside_cm2, a.area_kept_cm2) == (b.area_inside_cm2, b.area_kept_cm2)


@pytest.mark.parametrize("mode", ["maximal", "total"])
def test_the_boxes_do_not_depend_on_the_thread_count(mode):
    robot, limits, phi = random_case(1)
    spec = spec_of(limits, phi, mode, precision=1.0, refine_precision_cm=0.5)
    assert_thread_invariant(robot, spec)


def assert_thread_invariant(robot, spec):
    """The same boxes, labels and areas on 1 and 2 threads (and some inside boxes)."""
    one, two = on_one_and_two_threads(lambda: pave(robot, spec))
    assert len(one.boxes) > 100 and (one.status == INSIDE).any()
    assert np.array_equal(one.boxes, two.boxes) and np.array_equal(one.status, two.status)
    assert (one.area_inside_cm2, one.area_kept_cm2) == (two.area_inside_cm2, two.area_kept_cm2)


RANGE = 'orientation_deg = [10, 30]\norientation_mode = "maximal"\ngeometric_reference = false'
#: Job lines a parallel kind refuses with a range, and what the error line says.
RANGE_ERRORS = [
    ("orientation_deg = [10, 30]", "orientation_mode: missing key"),
    ('orientation_deg = 10\norientation_mode = "total"', "with a single orientation_deg"),
    ("orientation_deg = [30, 10]", "orientation_deg: range [30, 10]"),
    ('orientation_deg = [10, 30]\norientation_mode = "some"', "orientation_mode"),
    (RANGE + '\nform = "geometric"', "form: is 'geometric' with orientation_deg"),
    (RANGE.replace("false", "true"), "geometric_reference: is true with orientation_deg"),
    (RANGE + "\nsingularities = true", "singularities: is true with orientation_deg"),
    (RANGE + "\ntolerance_cm = 0.1", "orientation_deg: is (10.0, 30.0) with a tolerance"),
]


@pytest.mark.parametrize(("job", "fragment"), RANGE_ERRORS)
def test_bad_range_settings_are_one_line_errors(cli, tmp_path, job, fragment):
    refused(cli, tmp_path, "workspace3rpr", preset_text("", job), fragment)


def test_the_command_paves_a_range_says_so_and_plots_it(cli, tmp_path):
    job = 'orientation_deg = [10, 30]\norientation_mode = "total"'
    assert_range_command(cli, tmp_path, "workspace3rpr", preset_text("", job), "total")


def assert_range_command(cli, tmp_path, command, text, mode):
    """The command runs the preset ``text`` (a range [10, 30] in ``mode``): a bracket in
    the summary CSV without an exact area, the mode and range in the summary, a figure."""
    preset = tmp_path / "range.toml"
    preset.write_text(text, encoding="utf-8")
    result = cli(command, preset, "--out-dir", tmp_path, "--plot", tmp_path / "f.svg")
    assert result.exit_code == 0, result.output
    with open(tmp_path / "o.csv", encoding="utf-8") as f:
        (row,) = list(csv.DictReader(f))
    assert 0.0 < float(row["area_inside_cm2"]) <= float(row["area_kept_cm2"])
    assert (tmp_path / "f.svg").read_text(encoding="utf-8").lstrip().startswith("<?xml")
    assert row["area_geometric_cm2"] == ""  # no exact reference over a range
    assert f"{mode}, φ ∈ [10, 30]°" in result.stdout and "x (cm)" in result.stdout

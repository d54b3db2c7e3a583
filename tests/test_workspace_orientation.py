"""Orientation workspaces (maximal, total) against the certified sampled references."""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest

from planar_tui.progress import Progress
from planar_tui.workspace.paving.levels import BoxBudget
from planar_tui.workspace.rrr.job import WorkspaceSpec
from planar_tui.workspace.rrr.orientation import compute_orientation_workspace, reach_box_for
from planar_tui.workspace.rrr.orientation_reference import reference_polygons
from planar_tui.workspace.rrr.robot import Robot3RRR
from tests.conftest import on_one_and_two_threads

TABLE3 = ((20.0, 70.0), (110.0, 160.0), (245.0, 295.0))


class _Job:
    def __init__(self, spec):
        self.spec = spec
        self.preset_path = "test.toml"
        self.label = "test:workspace"
        self.key = "workspace"


def run(robot, limits, phi, mode, precision):
    spec = WorkspaceSpec(
        joint_limits_deg=limits,
        orientation_deg=phi,
        orientation_mode=mode,
        precision_cm=precision,
        form="arc-distance",
        geometric_reference=False,
    )
    return compute_orientation_workspace(robot, spec, BoxBudget(_Job(spec), Progress()))


def union_of(boxes):
    from shapely import box, union_all

    return union_all([box(b[0], b[2], b[1], b[3]) for b in boxes])


def check_against_reference(robot, limits, phi, mode, precision, samples):
    """inside boxes ⊆ outer reference, inner reference ⊆ kept boxes (as sets), and both
    area brackets overlap; returns the outcome and the reference polygons."""
    outcome = run(robot, limits, phi, mode, precision)
    limits_rad = tuple((math.radians(a), math.radians(b)) for a, b in limits)
    inner, outer = reference_polygons(robot, limits_rad, phi, mode, samples, segments=512)
    assert inner.area <= outer.area
    assert_bracketed(outcome, inner, outer)
    return outcome, inner, outer


def assert_bracketed(outcome, inner, outer):
    """The paving's inside boxes lie in the ``outer`` reference and its kept boxes hold the
    ``inner`` one (as sets, to 1e-9 relative), and the area brackets overlap."""
    inside = union_of(outcome.boxes[outcome.status == 2])
    kept = union_of(outcome.boxes)
    scale = max(outer.area, 1.0)
    assert inside.difference(outer).area <= 1e-9 * scale
    assert inner.difference(kept).area <= 1e-9 * scale
    assert outcome.area_inside_cm2 <= outer.area * (1 + 1e-12)
    assert inner.area <= outcome.area_kept_cm2 * (1 + 1e-12)


@pytest.mark.parametrize("mode", ["maximal", "total"])
def test_table3_robot_brackets_the_sampled_reference(mode):
    robot = Robot3RRR()
    outcome, inner, outer = check_against_reference(robot, TABLE3, (-10.0, 10.0), mode, 0.25, 80)
    # not vacuous: a real workspace, proved boxes, a bracket that narrows with ε
    assert inner.area > (200.0 if mode == "maximal" else 10.0)
    assert outcome.area_inside_cm2 > 0.5 * inner.area
    assert outcome.area_kept_cm2 < 1.5 * outer.area


def test_maximal_contains_total_and_each_single_orientation():
    robot = Robot3RRR()
    total = run(robot, TABLE3, (-10.0, 10.0), "total", 0.5)
    maximal = run(robot, TABLE3, (-10.0, 10.0), "maximal", 0.5)
    assert total.area_kept_cm2 < maximal.area_inside_cm2
    # the single orientation's exact area (paper B Table 3: 106.75 cm²) lies in between
    assert total.area_kept_cm2 < 106.7 < 106.8 < maximal.area_inside_cm2


def random_robot(seed):
    rng = np.random.default_rng(seed)
    a = rng.uniform(80, 140)
    b = rng.uniform(20, 50)
    l1, l2 = rng.uniform(25, 50, size=2)
    robot = Robot3RRR(base_side_cm=a, platform_side_cm=b, proximal_cm=l1, distal_cm=l2)
    centres = (45.0, 135.0, 270.0)
    limits = tuple(
        (c - w, c + w) for c, w in zip(centres, rng.uniform(30, 70, size=3), strict=True)
    )
    lo = rng.uniform(-20, 10)
    return robot, limits, (lo, lo + rng.uniform(5, 25))


@pytest.mark.parametrize("seed", [3, 11])
@pytest.mark.parametrize("mode", ["maximal", "total"])
def test_random_geometries_bracket_the_sampled_reference(seed, mode):
    robot, limits, phi = random_robot(seed)
    _, inner, _outer = check_against_reference(robot, limits, phi, mode, 1.0, 40)
    assert inner.area > 500.0  # the draws give a workspace, so the check bites


def test_reach_box_over_a_range_contains_every_orientations_reach():
    robot = Robot3RRR()
    xlo, xhi, ylo, yhi = reach_box_for(robot, (-40.0, 75.0))
    for phi in np.linspace(-40.0, 75.0, 47):
        a, b, c, d = robot.reach_box_cm(math.radians(phi))
        assert xlo <= a + 1e-9 and b <= xhi + 1e-9 and ylo <= c + 1e-9 and d <= yhi + 1e-9


PRESET = """
[robot3rrr]
[workspace]
joint_limits_deg = [[20, 70], [110, 160], [245, 295]]
precision_cm = 1.0
geometric_reference = {reference}
{extra}output = "ws.csv"
"""


def write(tmp_path, extra, reference="false"):
    path = tmp_path / "o.toml"
    path.write_text(PRESET.format(extra=extra, reference=reference), encoding="utf-8")
    return path


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        ("orientation_deg = [-5, 5]\n", "workspace.orientation_mode: missing key"),
        ('orientation_deg = 5\norientation_mode = "total"\n', "with a single orientation_deg"),
        ('orientation_deg = [5, -5]\norientation_mode = "total"\n', "empty or reversed"),
        ('orientation_deg = [1, 2, 3]\norientation_mode = "total"\n', "has 3 values"),
        ('orientation_deg = [0, 400]\norientation_mode = "total"\n', "at most 360"),
        ('orientation_deg = [0, 4]\norientation_mode = "all"\n', "maximal, total"),
        (
            'orientation_deg = [0, 4]\norientation_mode = "total"\nform = "slope"\n',
            "workspace.form: is 'slope' with orientation_deg = [lo, hi]",
        ),
    ],
)
def test_bad_orientation_settings_are_one_line_errors(cli, tmp_path, extra, message):
    result = cli("workspace", write(tmp_path, extra), "--out-dir", tmp_path)
    assert result.exit_code == 2, result.output
    assert message in result.output
    assert result.output.startswith("error: ") and result.output.count("\n") == 1
    assert not (tmp_path / "ws.csv").exists()


@pytest.mark.slow
def test_cli_writes_the_orientation_columns_and_the_reference(cli, tmp_path):
    extra = 'orientation_deg = [-5, 5]\norientation_mode = "maximal"\n'
    result = cli("workspace", write(tmp_path, extra, "true"), "--out-dir", tmp_path)
    assert result.exit_code == 0, result.output
    assert "maximal, φ ∈ [-5, 5]°" in result.output
    with open(tmp_path / "ws.csv", encoding="utf-8") as f:
        (row,) = list(csv.DictReader(f))
    assert row["orientation_mode"] == "maximal"
    assert (row["orientation_lo_deg"], row["orientation_hi_deg"]) == ("-5.0", "5.0")
    assert row["form"] == "arc-distance"
    reference = float(row["area_geometric_cm2"])
    error = float(row["area_geometric_error_cm2"])
    assert float(row["area_inside_cm2"]) <= reference + error
    assert reference - error <= float(row["area_kept_cm2"])
    assert cli("workspace", write(tmp_path, extra), "--form", "slope").exit_code == 2


@pytest.mark.parametrize(
    ("body", "stage"),
    [
        (
            'orientation_deg = [-30, 30]\norientation_mode = "maximal"\nprecision_cm = 0.004\n'
            "geometric_reference = false",
            "maximal orientation workspace",
        ),
        (
            'orientation_deg = [-30, 30]\norientation_mode = "total"\nprecision_cm = 1.0',
            "sampled reference",
        ),
        (
            "precision_cm = 1.0\nsingularities = true\nelbow = [1, -1, 1]\n"
            "singularity_precision_cm = 0.0005\ngeometric_reference = false",
            "type II singularities",
        ),
    ],
)
def test_cancel_stops_the_new_stages_within_a_fraction_of_a_second(body, stage):
    from benchmarks.bench_cancel import cancel_latency, robot_job
    from planar_tui import batch

    job = robot_job(
        "workspace", f"joint_limits_deg = [[20, 70], [110, 160], [245, 295]]\n{body}", "3rrr"
    )
    job = batch.prepare_jobs([job])[0]
    latency, asked = cancel_latency(lambda progress: batch.run_job(job, progress), stage, 0.1)
    assert asked.startswith(stage)
    assert latency <= 0.5


@pytest.mark.slow
def test_a_total_workspace_that_vanishes_inside_the_range_has_an_empty_reference():
    """The reviewer's preset (r12 geos.toml): the running intersection over φ becomes empty
    part-way (GEOS used to fail on it: "Unable to determine overlay result geometry
    dimension"); the reference is then empty and the certified bracket holds it."""
    robot = Robot3RRR(
        base_side_cm=100.94572997602054,
        platform_side_cm=58.062514021537595,
        proximal_cm=34.64940819451931,
        distal_cm=50.19484602462308,
    )
    limits = (
        (34.15538907306626, 168.73114725643143),
        (112.43905315095893, 140.15560485901807),
        (263.026966301221, 433.70709400261893),
    )
    phi = (-67.74067727622524, -16.36482984849)
    limits_rad = tuple((math.radians(a), math.radians(b)) for a, b in limits)
    inner, outer = reference_polygons(robot, limits_rad, phi, "total")  # default samples
    assert inner.area == 0.0 and outer.area == 0.0
    # each single orientation of the range has a workspace: emptiness is the range's doing
    lo_only, _ = reference_polygons(robot, limits_rad, (phi[0], phi[0] + 1.0), "total", 16)
    assert lo_only.area > 100.0
    outcome = run(robot, limits, phi, "total", 3.0)
    assert outcome.area_inside_cm2 <= outer.area
    assert inner.area <= outcome.area_kept_cm2


def test_a_failed_overlay_is_snapped_and_kept_on_its_side_of_the_exact_one():
    """When GEOS fails on an overlay the retry on the 1e-6 cm grid is eroded (inner) or
    dilated (outer): still inside / around the exact intersection of two discs."""
    import shapely
    from shapely.errors import GEOSException

    from planar_tui.workspace.rrr.orientation_reference import GRID_CM, _overlay

    first = shapely.Point(0.0, 0.0).buffer(10.0, quad_segs=64)
    second = shapely.Point(7.3, 1.1).buffer(6.0, quad_segs=64)
    exact = shapely.intersection(first, second)

    def failing(a, b, grid_size=None):
        if grid_size is None:
            raise GEOSException("Unable to determine overlay result geometry dimension")
        assert grid_size == GRID_CM
        return shapely.intersection(a, b, grid_size=grid_size)

    inner = _overlay(first, second, failing, False)
    outer = _overlay(first, second, failing, True)
    assert inner.difference(exact).area == 0.0 and exact.difference(outer).area == 0.0
    assert exact.area - 1e-3 < inner.area < exact.area < outer.area < exact.area + 1e-3


@pytest.mark.parametrize("mode", ["maximal", "total"])
def test_orientation_paving_is_parallel_and_the_same_on_1_and_2_threads(mode):
    """Issue 12: pave in parallel with the same boxes and areas whatever the thread count
    (``range_level`` is a ``prange`` kernel over each level's frontier)."""
    from planar_tui.kernels.workspace_orientation import range_level

    assert range_level.targetoptions.get("parallel")
    spec = WorkspaceSpec(
        joint_limits_deg=TABLE3,
        orientation_deg=(-10.0, 10.0),
        orientation_mode=mode,
        precision_cm=0.5,
        refine_precision_cm=0.25,
        form="arc-distance",
        geometric_reference=False,
    )
    one, two = on_one_and_two_threads(
        lambda: compute_orientation_workspace(Robot3RRR(), spec, BoxBudget(_Job(spec), Progress()))
    )
    assert len(one.boxes) > 100 and (one.status == 2).any()
    assert np.array_equal(one.boxes, two.boxes) and np.array_equal(one.status, two.status)
    assert (one.area_inside_cm2, one.area_kept_cm2) == (two.area_inside_cm2, two.area_kept_cm2)
    assert one.boxes_processed == two.boxes_processed

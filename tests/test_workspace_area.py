"""Workspace areas: geometric bracket vs the paper and Monte-Carlo, certified brackets."""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest
from planar_tui.kernels.workspace_arc import limits_array, points_feasible

from planar_tui.progress import Progress
from planar_tui.workspace.paving.levels import BoxBudget
from planar_tui.workspace.rrr.compute import compute_workspace, kernel_parameters
from planar_tui.workspace.rrr.geometry import geometric_area, workspace_polygon
from planar_tui.workspace.rrr.job import WorkspaceSpec
from planar_tui.workspace.rrr.robot import Robot3RRR
from tests.conftest import REFERENCE, on_one_and_two_threads

ROBOT = Robot3RRR()
# (table, joint limits deg, phi deg, paper eps cm, search box, exact area known from planning)
CASES = {
    3: (((20, 70), (110, 160), (245, 295)), 0.0, 0.1171875, ((0, 120), (0, 120)), 106.750),
    4: (((-15, 75), (105, 195), (225, 315)), 30.0, 0.3125, ((-40, 120), (-40, 120)), 486.950),
    5: (((50, 70), (140, 160), (260, 280)), 0.0, 0.03125, ((0, 128), (0, 128)), 0.8794),
}


def paper_rows(table: int) -> list[dict]:
    with open(REFERENCE / "paper_workspace_tables.csv", encoding="utf-8") as f:
        return [row for row in csv.DictReader(f) if row["table"] == str(table)]


def paper_area(table: int, form: str, precision: str | None = None) -> float:
    for row in paper_rows(table):
        if row["form"] == form and (precision is None or row["precision_cm"] == precision):
            return float(row["area_cm2"])
    raise KeyError((table, form, precision))


def spec_for(table, form, precision=None, **extra) -> WorkspaceSpec:
    limits, phi, eps, box, _ = CASES[table]
    return WorkspaceSpec(
        joint_limits_deg=limits,
        orientation_deg=phi,
        precision_cm=precision or eps,
        form=form,
        search_box_cm=box,
        geometric_reference=False,
        **extra,
    )


class _Job:
    def __init__(self, spec):
        self.spec = spec
        self.preset_path = "test.toml"
        self.label = "test:workspace"


def run(spec):
    return compute_workspace(ROBOT, spec, BoxBudget(_Job(spec), Progress()))


@pytest.fixture(scope="module")
def geometric():
    return {
        t: geometric_area(ROBOT, spec_for(t, "geometric").limits_rad, math.radians(c[1]))
        for t, c in CASES.items()
    }


@pytest.mark.parametrize("table", [3, 4, 5])
def test_geometric_bracket_matches_the_paper_within_half_a_percent(table, geometric):
    g = geometric[table]
    assert g.inner_cm2 <= g.outer_cm2
    assert g.error_bound_cm2 <= 2e-5 * g.outer_cm2
    assert g.area_cm2 == pytest.approx(paper_area(table, "geometric"), rel=5e-3)
    # the exact areas measured while planning the issue (106.750, 486.950, 0.8794)
    exact = CASES[table][4]
    assert g.inner_cm2 - 5e-4 * exact <= exact <= g.outer_cm2 + 5e-4 * exact


@pytest.mark.parametrize("table", [3, 4, 5])
def test_geometric_area_agrees_with_monte_carlo_of_the_exact_leg_test(table, geometric):
    """Independent of shapely: uniform points in the reach box, exact leg-wise test."""
    spec = spec_for(table, "arc-distance")
    xlo, xhi, ylo, yhi = ROBOT.reach_box_cm(spec.orientation_rad)
    g = geometric[table]
    if table == 5:  # tiny workspace: sample the outer polygon's bounds grown by 20 %
        x0, y0, x1, y1 = workspace_polygon(ROBOT, spec.limits_rad, 0.0, 256, True).bounds
        pad = 0.2 * max(x1 - x0, y1 - y0)
        xlo, xhi, ylo, yhi = x0 - pad, x1 + pad, y0 - pad, y1 + pad
    rng = np.random.default_rng(2024 + table)
    n = 400_000
    xs, ys = rng.uniform(xlo, xhi, n), rng.uniform(ylo, yhi, n)
    inside = np.zeros(n, dtype=np.bool_)
    points_feasible(xs, ys, kernel_parameters(ROBOT, spec), limits_array(spec.limits_rad), inside)
    box_area = (xhi - xlo) * (yhi - ylo)
    fraction = inside.mean()
    estimate = fraction * box_area
    sigma = math.sqrt(fraction * (1 - fraction) / n) * box_area
    assert abs(estimate - g.area_cm2) < 4.5 * sigma + 1e-9


@pytest.mark.parametrize("table", [3, 4, 5])
def test_brackets_contain_the_exact_area_and_shrink_with_epsilon(table, geometric):
    g = geometric[table]
    eps = CASES[table][2]
    widths = []
    for form, factor in [("arc-distance", 4), ("arc-distance", 1), ("mean-value", 8)]:
        out = run(spec_for(table, form, eps * factor))
        assert out.area_inside_cm2 <= g.inner_cm2
        assert g.outer_cm2 <= out.area_kept_cm2
        if form == "arc-distance":
            widths.append(out.area_kept_cm2 - out.area_inside_cm2)
    assert widths[1] < widths[0]


def test_table3_mean_value_and_slope_at_the_papers_epsilon_are_within_the_papers_areas(
    geometric,
):
    for form in ("mean-value", "slope"):
        out = run(spec_for(3, form))
        assert geometric[3].outer_cm2 <= out.area_kept_cm2
        # ours at most the paper's figure, to its printed precision (0.1 cm^2)
        assert out.area_kept_cm2 <= paper_area(3, form) + 0.05
        assert out.area_inside_cm2 <= geometric[3].inner_cm2


def test_arc_distance_boundary_refinement_brackets_within_a_tenth_of_a_percent(geometric):
    out = run(spec_for(5, "arc-distance", refine_precision_cm=0.03125 / 256))
    assert out.area_inside_cm2 <= geometric[5].inner_cm2 <= geometric[5].outer_cm2
    assert geometric[5].outer_cm2 <= out.area_kept_cm2
    assert out.area_kept_cm2 - out.area_inside_cm2 < 1e-3 * geometric[5].area_cm2


def test_interval_form_refinement_keeps_inside_boxes_unsplit(geometric):
    coarse = run(spec_for(5, "slope", 0.0625))
    refined = run(spec_for(5, "slope", 0.0625, refine_precision_cm=0.0625 / 16))
    inside_before = coarse.boxes[coarse.status == 2]
    inside_after = refined.boxes[refined.status == 2]
    # every coarse inside box is still there, unsplit
    assert {tuple(b) for b in inside_before} <= {tuple(b) for b in inside_after}
    assert refined.area_kept_cm2 < coarse.area_kept_cm2
    assert refined.area_inside_cm2 > coarse.area_inside_cm2
    assert refined.area_inside_cm2 <= geometric[5].inner_cm2


def test_expanded_natural_extension_is_wider_than_the_compact_one():
    compact = run(spec_for(5, "natural", 0.0625))
    expanded = run(spec_for(5, "natural", 0.0625, expanded=True))
    assert expanded.area_kept_cm2 > compact.area_kept_cm2
    assert expanded.area_inside_cm2 == compact.area_inside_cm2


def test_explicit_coordinates_reproduce_the_paper_layout():
    explicit = Robot3RRR(
        base_joints=((0.0, 0.0), (120.0, 0.0), (60.0, 60.0 * math.sqrt(3.0))),
        platform_points=((0.0, 0.0), (40.0, 0.0), (20.0, 40.0)),
    )
    limits = spec_for(4, "geometric").limits_rad
    a = geometric_area(ROBOT, limits, math.radians(30.0))
    b = geometric_area(explicit, limits, math.radians(30.0))
    assert a.area_cm2 == pytest.approx(b.area_cm2, rel=1e-9)


@pytest.mark.parametrize("table", [3, 4])
def test_tables_3_and_4_every_form_at_the_papers_epsilon(table, geometric):
    for form in ("natural", "slope", "mean-value", "arc-distance"):
        out = run(spec_for(table, form))
        assert out.area_inside_cm2 <= geometric[table].inner_cm2
        assert geometric[table].outer_cm2 <= out.area_kept_cm2
        if form in ("slope", "mean-value", "natural"):
            assert out.area_kept_cm2 <= paper_area(table, form) + 0.05
        print(table, form, out.area_kept_cm2)


def test_table5_mean_value_over_the_papers_precisions(geometric):
    previous = math.inf
    for precision in ("0.03125", "0.01562", "0.00781", "0.00391"):
        eps = 0.03125 / 2 ** ("0.03125", "0.01562", "0.00781", "0.00391").index(precision)
        out = run(spec_for(5, "mean-value", eps))
        assert geometric[5].outer_cm2 <= out.area_kept_cm2 < previous
        assert out.area_kept_cm2 <= paper_area(5, "mean-value", precision) + 0.0005
        previous = out.area_kept_cm2


def test_arc_distance_paving_is_parallel_and_the_same_on_1_and_2_threads():
    """The arc-distance paving and its boundary refinement run level by level on every
    core (``arc_level`` is a ``prange`` kernel) with identical boxes, order and areas."""
    from planar_tui.kernels.workspace_arc import arc_level

    assert arc_level.targetoptions.get("parallel")
    spec = spec_for(4, "arc-distance", 0.625, refine_precision_cm=0.15625)
    one, two = on_one_and_two_threads(lambda: run(spec))
    assert len(one.boxes) > 1000  # a real paving: many levels and slices
    assert np.array_equal(one.boxes, two.boxes) and np.array_equal(one.status, two.status)
    assert (one.area_inside_cm2, one.area_kept_cm2) == (two.area_inside_cm2, two.area_kept_cm2)
    assert one.boxes_processed == two.boxes_processed


def test_the_box_estimate_and_the_exact_reference_are_computed_once_per_geometry(monkeypatch):
    """Paper B's Table 3 runs seven jobs on one geometry: the outer polygon of the box
    estimate and the exact bracket are each made once (the polygons counted), and the
    estimate's area and length are the polygon's own."""
    from planar_tui.workspace.rrr import geometry

    made = []
    real = geometry.workspace_polygon

    def counted(*args):
        made.append(args[3:])
        return real(*args)

    monkeypatch.setattr(geometry, "workspace_polygon", counted)
    limits = tuple((math.radians(lo), math.radians(hi)) for lo, hi in CASES[3][0])
    orientation_rad = 0.0123  # a geometry no other test caches
    area, length = geometry.outer_area_and_length(ROBOT, limits, orientation_rad)
    polygon = real(ROBOT, limits, orientation_rad, 64, True)
    assert (area, length) == (polygon.area, polygon.length)
    assert made == [(64, True)]
    same = geometry.outer_area_and_length(
        ROBOT, [list(pair) for pair in limits], np.float64(orientation_rad)
    )
    bracket = geometry.geometric_area(ROBOT, limits, orientation_rad)
    polygons = len(made)
    assert same == (area, length) and polygons > 2
    assert geometry.geometric_area(ROBOT, list(limits), orientation_rad) is bracket
    assert len(made) == polygons

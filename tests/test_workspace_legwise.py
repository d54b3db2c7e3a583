"""Leg-wise paving (issue 12, parts 1-2): certified brackets against the exact area for both
strategies, per-box decisions against the exact point test, thread-count independence."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from planar_tui.kernels.workspace_arc import limits_array, points_feasible
from planar_tui.kernels.workspace_union import union_area

from planar_tui.presets import load_preset
from planar_tui.progress import Progress
from planar_tui.workspace.paving.levels import BoxBudget
from planar_tui.workspace.rrr.compute import compute_workspace, estimate_boxes, kernel_parameters
from planar_tui.workspace.rrr.geometry import geometric_area
from planar_tui.workspace.rrr.job import WorkspaceSpec
from planar_tui.workspace.rrr.robot import Robot3RRR
from tests.conftest import PRESETS, on_one_and_two_threads

PAPER = Robot3RRR()
INTERVAL_FORMS = ("natural", "mean-value", "slope")
# (joint limits deg, phi deg, eps cm, search box): paper B Tables 3-5 and the 120° case
CASES = {
    3: (((20, 70), (110, 160), (245, 295)), 0.0, 0.1171875, ((0, 120), (0, 120))),
    4: (((-15, 75), (105, 195), (225, 315)), 30.0, 0.3125, ((-40, 120), (-40, 120))),
    5: (((50, 70), (140, 160), (260, 280)), 0.0, 0.03125, ((0, 128), (0, 128))),
    120: (((-30, 90), (90, 210), (210, 330)), -20.0, 0.05, None),
}


class _Job:
    def __init__(self, spec):
        self.spec, self.preset_path, self.label, self.key = spec, "test.toml", "t", "workspace"


def run(spec, robot=PAPER, progress=None):
    return compute_workspace(robot, spec, BoxBudget(_Job(spec), progress or Progress()))


def spec_for(case, form, strategy, precision=None, **extra):
    limits, phi, eps, box = CASES[case]
    return WorkspaceSpec(
        joint_limits_deg=limits,
        orientation_deg=phi,
        precision_cm=precision or eps,
        form=form,
        strategy=strategy,
        search_box_cm=box,
        geometric_reference=False,
        **extra,
    )


@pytest.fixture(scope="module")
def exact():
    """The geometric (shapely) bracket of each case: independent of the interval code."""
    return {
        case: geometric_area(
            PAPER, spec_for(case, "geometric", "legwise").limits_rad, math.radians(c[1])
        )
        for case, c in CASES.items()
    }


def assert_brackets(out, g):
    """``inside <= exact <= kept``: the geometric bracket is far narrower than ours."""
    assert out.area_inside_cm2 <= g.inner_cm2 <= g.outer_cm2 <= out.area_kept_cm2


def test_the_issues_120_degree_case_has_the_issues_exact_area(exact):
    """768.72 cm² by the shapely bracket and by Monte Carlo of the exact test."""
    g = exact[120]
    assert g.inner_cm2 <= 768.72 + 0.005 and g.outer_cm2 >= 768.72 - 0.005
    spec = spec_for(120, "mean-value", "legwise")
    xlo, xhi, ylo, yhi = PAPER.reach_box_cm(spec.orientation_rad)
    rng = np.random.default_rng(12)
    n = 400_000
    xs, ys = rng.uniform(xlo, xhi, n), rng.uniform(ylo, yhi, n)
    feasible = np.zeros(n, dtype=np.bool_)
    points_feasible(xs, ys, kernel_parameters(PAPER, spec), limits_array(spec.limits_rad), feasible)
    box_area = (xhi - xlo) * (yhi - ylo)
    fraction = feasible.mean()
    sigma = math.sqrt(fraction * (1 - fraction) / n) * box_area
    assert abs(fraction * box_area - 768.72) < 4.5 * sigma


@pytest.mark.parametrize("case", [3, 4, 5, 120])
def test_legwise_brackets_contain_the_exact_area_for_every_form(case, exact):
    for form in INTERVAL_FORMS:
        out = run(spec_for(case, form, "legwise"))
        assert out.strategy == "legwise" and out.xy_boxes > 0
        assert_brackets(out, exact[case])
        # both counts recorded: (x, y, θ_i) leg boxes evaluated >= 1 per (x, y) box
        assert out.boxes_processed >= out.xy_boxes
        # a paving: disjoint boxes, so the areas (sums) are those of the unions
        assert union_area(out.boxes) == pytest.approx(out.area_kept_cm2, rel=1e-12)
        inside = np.ascontiguousarray(out.boxes[out.status == 2])
        assert union_area(inside) == pytest.approx(out.area_inside_cm2, rel=1e-12)


@pytest.mark.parametrize("case", [3, 4])
def test_joint_brackets_at_the_papers_epsilon_reproduce_the_papers_figures(case, exact):
    """The paper's 5-D bisection (the bundled presets' strategy) stays as printed: kept
    area at most the paper's figure (to its printed precision) for slope and mean-value."""
    paper = {3: {"slope": 110.7, "mean-value": 110.8}, 4: {"slope": 511.3, "mean-value": 511.8}}
    for form in ("slope", "mean-value"):
        out = run(spec_for(case, form, "joint"))
        assert out.strategy == "joint"
        assert_brackets(out, exact[case])
        assert out.area_kept_cm2 <= paper[case][form] + 0.05


def test_joint_brackets_on_table_5_and_the_120_degree_case(exact):
    assert_brackets(run(spec_for(5, "mean-value", "joint")), exact[5])
    for form in INTERVAL_FORMS:  # coarse: the joint bisection multiplies the legs' θ pieces
        assert_brackets(run(spec_for(120, form, "joint", 0.8)), exact[120])


def test_legwise_is_at_least_as_tight_as_joint_with_far_fewer_boxes():
    joint = run(spec_for(120, "mean-value", "joint", 0.4))
    legwise = run(spec_for(120, "mean-value", "legwise", 0.4))
    assert legwise.area_kept_cm2 <= joint.area_kept_cm2
    assert legwise.area_inside_cm2 >= joint.area_inside_cm2
    assert legwise.boxes_processed * 10 < joint.boxes_processed


def test_the_bundled_paper_presets_pave_jointly():
    for table in (3, 4, 5):
        jobs = load_preset(PRESETS / f"paper-b-table{table}.toml").jobs
        assert all(j.spec.strategy == "joint" for j in jobs if j.spec.form in INTERVAL_FORMS)


def test_legwise_is_the_default():
    assert WorkspaceSpec(joint_limits_deg=CASES[3][0], precision_cm=1.0).strategy == "legwise"


@st.composite
def geometries(draw):
    """A random 3-RRR (base side a, platform side b, links l1, l2), limits and φ."""
    a = draw(st.floats(40.0, 150.0))
    b = draw(st.floats(5.0, 0.8 * a))
    l1 = draw(st.floats(0.3 * a, 0.6 * a))
    l2 = draw(st.floats(0.5 * l1, 1.5 * l1))
    phi = draw(st.floats(-60.0, 60.0))
    limits = []
    for centre in (30.0, 150.0, 270.0):  # the legs point roughly at the base's centre
        lo = draw(st.floats(centre - 90.0, centre))
        limits.append((lo, lo + draw(st.floats(10.0, 180.0))))
    form = draw(st.sampled_from(INTERVAL_FORMS))
    robot = Robot3RRR(base_side_cm=a, platform_side_cm=b, proximal_cm=l1, distal_cm=l2)
    return robot, tuple(limits), phi, form


@pytest.mark.slow
@settings(deadline=None, max_examples=12, suppress_health_check=[HealthCheck.too_slow])
@given(geometries())
def test_random_geometries_both_strategies_bracket_the_exact_area(geometry):
    robot, limits, phi, form = geometry
    eps = robot.proximal_cm / 16  # coarse, so that the joint bisection stays fast
    g = geometric_area(
        robot, [(math.radians(lo), math.radians(hi)) for lo, hi in limits], math.radians(phi)
    )
    outs = {}
    for strategy in ("legwise", "joint"):
        spec = WorkspaceSpec(
            joint_limits_deg=limits,
            orientation_deg=phi,
            precision_cm=eps,
            form=form,
            strategy=strategy,
            geometric_reference=False,
        )
        outs[strategy] = out = run(spec, robot)
        assert_brackets(out, g)
    # per box, against the exact point test (independent of the interval forms): points of
    # proved-inside boxes are feasible, feasible points lie in a kept box
    out = outs["legwise"]
    p = kernel_parameters(robot, spec)
    rng = np.random.default_rng(0)
    xlo, xhi, ylo, yhi = out.extent_cm
    xs, ys = rng.uniform(xlo, xhi, 4000), rng.uniform(ylo, yhi, 4000)
    inside = out.boxes[out.status == 2]
    if len(inside):
        pick = rng.integers(0, len(inside), 4000)
        xs = np.concatenate([xs, rng.uniform(inside[pick, 0], inside[pick, 1])])
        ys = np.concatenate([ys, rng.uniform(inside[pick, 2], inside[pick, 3])])
    feasible = np.zeros(len(xs), dtype=np.bool_)
    points_feasible(xs, ys, p, limits_array(spec.limits_rad), feasible)
    b = out.boxes
    within = (b[None, :, 0] <= xs[:, None]) & (xs[:, None] <= b[None, :, 1])
    within &= (b[None, :, 2] <= ys[:, None]) & (ys[:, None] <= b[None, :, 3])
    assert within[feasible].any(axis=1).all()
    assert feasible[within[:, out.status == 2].any(axis=1)].all()


def test_thread_count_does_not_change_boxes_or_areas():
    spec = spec_for(120, "slope", "legwise", 0.1, refine_precision_cm=0.05)
    one, two = on_one_and_two_threads(lambda: run(spec))
    assert np.array_equal(one.boxes, two.boxes) and np.array_equal(one.status, two.status)
    assert (one.area_inside_cm2, one.area_kept_cm2) == (two.area_inside_cm2, two.area_kept_cm2)
    assert one.boxes_processed == two.boxes_processed and one.xy_boxes == two.xy_boxes


def test_progress_shows_partial_boxes_with_status_and_the_estimate_is_near():
    spec = spec_for(5, "mean-value", "legwise", 0.015625)
    states = []
    out = run(spec, progress=Progress(on_update=states.append))
    estimate = estimate_boxes(PAPER, spec)
    assert out.boxes_processed / 3 < estimate < out.boxes_processed * 3
    partial = [s.partial for s in states if s.partial.get("boxes_cm") is not None]
    assert partial and all(not v["boxes_cm"].flags.writeable for v in partial)
    assert all(len(v["status"]) == len(v["boxes_cm"]) > 0 for v in partial)
    brackets = [
        (s.figures["area_lower_cm2"], s.figures["area_upper_cm2"])
        for s in states
        if "area_upper_cm2" in s.figures
    ]
    assert all(
        lo <= out.area_inside_cm2 + 1e-9 and hi >= out.area_kept_cm2 - 1e-9 for lo, hi in brackets
    )

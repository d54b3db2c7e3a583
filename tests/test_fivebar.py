"""The five-bar kind (``[robot5r]``, ``[[workspace5r]]``): its certified area bracket
against two independent references (the exact polygon geometry, and a fine grid of points
tested by closed-form inverse kinematics written here, with its error bound), its singular
boxes against a float trace of det A = 0 and of the type I circles, the singularity-free
circle against a brute-force search, thread-count invariance, bad input, the CLI, the
app's tab and the figure."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from planar_tui.jobkind import PreparedJob
from planar_tui.presets import load_preset
from planar_tui.progress import Progress
from tests.conftest import PRESETS, on_one_and_two_threads

PRESET = PRESETS / "fivebar-illustrative.toml"


def jobs():
    return load_preset(PRESET).jobs


def run(job, **changes):
    from planar_tui.workspace.fivebar.job import run_fivebar

    spec = dataclasses.replace(job.spec, **changes)
    return run_fivebar(PreparedJob(dataclasses.replace(job, spec=spec), None), Progress())


# -- independent float model (closed-form inverse kinematics, numpy) ------------------
def branch_angles(robot, leg, x, y):
    """Both inverse-kinematics angles of leg ``leg`` (NaN where it cannot close)."""
    ax, ay = (-0.5 * robot.base_separation_cm if leg == 0 else 0.5 * robot.base_separation_cm, 0)
    l1, l2 = robot.proximal_cm[leg], robot.distal_cm[leg]
    r = np.hypot(x - ax, y - ay)
    with np.errstate(invalid="ignore", divide="ignore"):
        beta = np.arccos((r * r + l1 * l1 - l2 * l2) / (2 * l1 * r))
    alpha = np.arctan2(y - ay, x - ax)
    return {1: alpha + beta, -1: alpha - beta}


def within(theta, lo_deg, hi_deg):
    lo, hi = math.radians(lo_deg), math.radians(hi_deg)
    return np.isfinite(theta) & (np.mod(theta - lo, 2 * math.pi) <= hi - lo)


def reached(robot, x, y, leg, sign=None):
    """Leg ``leg`` closes at ``(x, y)`` within its limits (in branch ``sign``, or either)."""
    angles = branch_angles(robot, leg, x, y)
    lo, hi = robot.joint_limits_deg[leg]
    signs = (1, -1) if sign is None else (sign,)
    return np.any([within(angles[s], lo, hi) for s in signs], axis=0)


def in_workspace(robot, x, y):
    elbows = robot.elbows
    return reached(robot, x, y, 0, elbows[0] or None) & reached(robot, x, y, 1, elbows[1] or None)


def det(robot, x, y, elbows):
    """u1 × u2 (u_i = P - B_i) in the mode ``elbows``."""
    u = []
    for leg in range(2):
        ax = -0.5 * robot.base_separation_cm if leg == 0 else 0.5 * robot.base_separation_cm
        theta = branch_angles(robot, leg, x, y)[elbows[leg]]
        l1 = robot.proximal_cm[leg]
        u.append((x - ax - l1 * np.cos(theta), y - l1 * np.sin(theta)))
    return u[0][0] * u[1][1] - u[0][1] * u[1][0]


def grid_area(robot, spacing):
    """``(area, bound)``: the cells whose centre is in the workspace, and a bound on the
    error (every cell that straddles the boundary lies within its diagonal of it: the tube
    of radius δ about boundary curves of total length L has area ≤ 2δL + πδ² per piece;
    L from the exact outer polygon, at most 16 arcs)."""
    from planar_tui.workspace.fivebar.robot import workspace_polygon

    xlo, xhi, ylo, yhi = robot.reach_box_cm()
    xs = np.arange(xlo + spacing / 2, xhi, spacing)
    ys = np.arange(ylo + spacing / 2, yhi, spacing)
    count = 0
    for y in ys:
        count += int(np.count_nonzero(in_workspace(robot, xs, np.full_like(xs, y))))
    length = workspace_polygon(robot, 256, True).length
    delta = spacing * math.sqrt(2.0)
    return count * spacing**2, 2 * delta * length + 16 * math.pi * delta**2


def test_the_mode_band_polygon_has_the_closed_form_area_of_a_leg():
    """One leg in a mode sweeps area 2 l1 l2 Δθ (∫ r Δθ dr over the annulus)."""
    from planar_tui.workspace.fivebar.robot import mode_band

    for l1, l2, sigma in ((45.0, 55.0, 1), (60.0, 25.0, -1), (30.0, 30.0, 1)):
        lo, hi = math.radians(-20), math.radians(150)
        band, sagitta = mode_band((3.0, -2.0), l1, l2, lo, hi, sigma, 4096)
        inner = band.buffer(-sagitta, join_style="mitre").area
        outer = band.buffer(sagitta, join_style="mitre").area
        assert inner <= 2 * l1 * l2 * (hi - lo) <= outer
        assert outer - inner < 1e-4 * outer


def check_bracket(robot, outcome, spacing):
    """The certified bracket holds the polygon reference and the grid reference."""
    from planar_tui.workspace.fivebar.robot import geometric_area

    exact = geometric_area(robot)
    assert outcome.area_inside_cm2 <= exact.outer_cm2
    assert outcome.area_kept_cm2 >= exact.inner_cm2
    grid, bound = grid_area(robot, spacing)
    assert outcome.area_inside_cm2 <= grid + bound
    assert outcome.area_kept_cm2 >= grid - bound
    assert abs(grid - exact.area_cm2) <= bound + exact.error_bound_cm2


def test_the_bundled_jobs_bracket_the_exact_area_within_2_percent():
    for job in jobs():
        result = run(job, precision_cm=0.1)
        outcome = result.outcome
        check_bracket(job.robot, outcome, 0.1)
        width = outcome.area_kept_cm2 - outcome.area_inside_cm2
        assert width <= 0.02 * outcome.geometric.area_cm2


@settings(max_examples=8, deadline=None)
@given(
    d=st.floats(0.0, 60.0),
    lengths=st.lists(st.floats(10.0, 60.0), min_size=4, max_size=4),
    lo=st.lists(st.floats(-180.0, 180.0), min_size=2, max_size=2),
    span=st.lists(st.floats(20.0, 360.0), min_size=2, max_size=2),
    mode=st.sampled_from(["any", "++", "+-", "-+", "--"]),
)
def test_random_geometries_bracket_the_exact_area(d, lengths, lo, span, mode):
    from planar_tui.workspace.fivebar.robot import Robot5R

    robot = Robot5R(
        base_separation_cm=max(d, 1e-3),
        proximal_cm=(lengths[0], lengths[1]),
        distal_cm=(lengths[2], lengths[3]),
        joint_limits_deg=tuple((a, a + s) for a, s in zip(lo, span, strict=True)),
        working_mode=mode,
    )
    job = dataclasses.replace(jobs()[0], robot=robot)
    result = run(job, precision_cm=0.5, refine_precision_cm=0.25)
    check_bracket(robot, result.outcome, 0.25)


def test_a_boundary_refinement_narrows_the_bracket():
    job = jobs()[1]
    coarse = run(
        job,
        precision_cm=0.8,
        singularities=False,
        singularity_free_circle=None,
        singularity_precision_cm=None,
    ).outcome
    refined = run(
        job,
        precision_cm=0.8,
        refine_precision_cm=0.2,
        singularities=False,
        singularity_free_circle=None,
        singularity_precision_cm=None,
    ).outcome
    assert coarse.area_inside_cm2 <= refined.area_inside_cm2
    assert refined.area_kept_cm2 <= coarse.area_kept_cm2
    check_bracket(job.robot, refined, 0.2)


# -- singularities --------------------------------------------------------------------------
def contains(boxes, x, y, slack=1e-9):
    return bool(
        np.any(
            (boxes[:, 0] - slack <= x)
            & (x <= boxes[:, 1] + slack)
            & (boxes[:, 2] - slack <= y)
            & (y <= boxes[:, 3] + slack)
        )
    )


def type2_trace(robot, elbows, lines=40, samples=3000):
    """Points with det A = 0 in the mode's workspace: sign changes of det along horizontal
    and vertical lines, each root refined by bisection (scipy's brentq)."""
    from scipy.optimize import brentq

    mode = dataclasses.replace(robot, working_mode="".join("+" if s > 0 else "-" for s in elbows))
    xlo, xhi, ylo, yhi = robot.reach_box_cm()
    points = []
    for vertical in (False, True):
        ts = np.linspace(ylo, yhi, samples) if vertical else np.linspace(xlo, xhi, samples)
        for level in np.linspace(*((xlo, xhi) if vertical else (ylo, yhi)), lines):

            def at(t, level=level, vertical=vertical):
                t, c = np.atleast_1d(t), np.full(np.shape(np.atleast_1d(t)), level)
                return (c, t) if vertical else (t, c)

            inside = in_workspace(mode, *at(ts))
            values = det(robot, *at(ts), elbows)
            change = inside[:-1] & inside[1:] & (np.sign(values[:-1]) != np.sign(values[1:]))
            for i in np.flatnonzero(change):
                if not in_workspace(mode, *at(0.5 * (ts[i] + ts[i + 1])))[0]:
                    continue
                root = brentq(lambda t: float(det(robot, *at(t), elbows)[0]), ts[i], ts[i + 1])
                x, y = at(root)
                points.append((float(x[0]), float(y[0])))
    return points


def type1_trace(robot, count=400):
    """Points of the workspace on a leg's extended circle |P - A_i| = l1 + l2."""
    points = []
    for leg in range(2):
        ax = -0.5 * robot.base_separation_cm if leg == 0 else 0.5 * robot.base_separation_cm
        radius = robot.proximal_cm[leg] + robot.distal_cm[leg]
        t = np.linspace(0, 2 * math.pi, count, endpoint=False)
        x, y = ax + radius * np.cos(t), radius * np.sin(t)
        keep = in_workspace(robot, x, y)
        points += list(zip(x[keep], y[keep], strict=True))
    return points


@pytest.mark.parametrize("index", [0, 1], ids=["any mode", "mode +-"])
def test_singular_boxes_hold_a_float_trace_of_both_types(index):
    from planar_tui.kernels.singularity5r import TYPE_I, TYPE_II

    job = jobs()[index]
    robot = job.robot
    result = run(
        job,
        precision_cm=0.5,
        singularities=True,
        singularity_precision_cm=0.5,
        singularity_free_circle=None,
    )
    singular = result.singularity
    type2 = singular.boxes[(singular.kinds & TYPE_II) != 0]
    type1 = singular.boxes[(singular.kinds & TYPE_I) != 0]
    modes = [(1, 1), (1, -1), (-1, 1), (-1, -1)] if robot.working_mode == "any" else [robot.elbows]
    traced = [p for elbows in modes for p in type2_trace(robot, elbows)]
    assert len(traced) > 20
    missing = [p for p in traced if not contains(type2, *p)]
    assert not missing, missing[:5]
    circles = type1_trace(robot)
    assert len(circles) > 20
    assert all(contains(type1, *p, slack=1e-6) for p in circles)


def test_the_circle_radius_brackets_a_brute_force_search():
    job = jobs()[1]
    robot = job.robot
    singular = run(job, precision_cm=0.5, singularity_precision_cm=0.1).singularity
    cx, cy = singular.centre_cm
    sign = np.sign(det(robot, np.array([cx]), np.array([cy]), robot.elbows)[0])
    angles = np.linspace(0, 2 * math.pi, 4000, endpoint=False)
    brute = math.inf
    for radius in np.arange(0.02, 80, 0.02):
        x, y = cx + radius * np.cos(angles), cy + radius * np.sin(angles)
        with np.errstate(invalid="ignore"):
            bad = ~in_workspace(robot, x, y) | (np.sign(det(robot, x, y, robot.elbows)) != sign)
        if bad.any():
            brute = radius
            break
    assert singular.radius_lo_cm <= brute <= singular.radius_hi_cm + 0.05
    assert singular.radius_hi_cm - singular.radius_lo_cm <= 0.5


def test_boxes_do_not_depend_on_the_thread_count():
    job = jobs()[1]

    def once():
        result = run(job, precision_cm=0.4, singularity_precision_cm=0.5)
        return result.outcome, result.singularity

    (a, sa), (b, sb) = on_one_and_two_threads(once)
    assert np.array_equal(a.boxes, b.boxes) and np.array_equal(a.status, b.status)
    assert np.array_equal(sa.boxes, sb.boxes) and np.array_equal(sa.kinds, sb.kinds)
    assert (sa.radius_lo_cm, sa.radius_hi_cm) == (sb.radius_lo_cm, sb.radius_hi_cm)


# -- bad input, CLI, app, figure ------------------------------------------------------------
ROBOT = '[robot5r]\nworking_mode = "+-"\n'
JOB = "[[workspace5r]]\nprecision_cm = 1.0\n"
BAD = {
    "base_separation_cm": (ROBOT + "base_separation_cm = -1\n" + JOB, "robot5r.base_separation_cm"),
    "proximal_cm": (ROBOT + "proximal_cm = [1]\n" + JOB, "robot5r.proximal_cm"),
    "distal_cm": (ROBOT + "distal_cm = [1, 0]\n" + JOB, "robot5r.distal_cm"),
    "joint_limits_deg": (
        ROBOT + "joint_limits_deg = [[10, 5], [0, 1]]\n" + JOB,
        "robot5r.joint_limits_deg",
    ),
    "working_mode": ('[robot5r]\nworking_mode = "+"\n' + JOB, "robot5r.working_mode"),
    "precision_cm": (ROBOT + "[[workspace5r]]\nprecision_cm = 0\n", "workspace5r[1].precision_cm"),
    "form": (ROBOT + JOB + 'form = "slope"\n', "workspace5r[1].form"),
    "refine_precision_cm": (
        ROBOT + JOB + "refine_precision_cm = 2\n",
        "workspace5r[1].refine_precision_cm",
    ),
    "search_box_cm": (
        ROBOT + JOB + "search_box_cm = [[-1, 1], [-1, 1]]\n",
        "workspace5r[1].search_box_cm",
    ),
    "box_budget": (ROBOT + JOB + "box_budget = 0\n", "workspace5r[1].box_budget"),
    "singularities": (ROBOT + JOB + "singularities = 1\n", "workspace5r[1].singularities"),
    "singularity_precision_cm": (
        ROBOT + JOB + "singularity_precision_cm = 0.5\n",
        "workspace5r[1].singularity_precision_cm",
    ),
    "geometric_reference": (
        ROBOT + JOB + 'geometric_reference = "yes"\n',
        "workspace5r[1].geometric_reference",
    ),
    "boxes_output": (
        ROBOT + JOB + 'boxes_output = "/tmp/abs.csv"\n',
        "workspace5r[1].boxes_output",
    ),
    "circle without singularities": (
        ROBOT + JOB + "singularity_free_circle = [0, 60]\n",
        "workspace5r[1].singularity_free_circle",
    ),
    "circle in any mode": (
        "[robot5r]\n" + JOB + "singularities = true\nsingularity_free_circle = [0, 60]\n",
        "workspace5r[1].singularity_free_circle",
    ),
    "circle out of reach": (
        ROBOT + JOB + "singularities = true\nsingularity_free_circle = [0, 500]\n",
        "workspace5r[1].singularity_free_circle",
    ),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_input_is_one_line_exit_2(case, cli, tmp_path):
    from tests.test_bad_input import refused_line

    text, key = BAD[case]
    refused_line(cli, tmp_path, text, key, "")


def test_the_command_writes_the_summary_and_boxes_csv(cli, tmp_path):
    import csv

    result = cli(
        "workspace5r",
        PRESET,
        "--precision",
        "1",
        "--boxes",
        tmp_path / "b.csv",
        "--out-dir",
        tmp_path,
        "--no-map",
    )
    assert result.exit_code == 0, result.output
    summaries = sorted(tmp_path.glob("fivebar-*.csv"))
    assert len(summaries) == 2
    with open(summaries[1], newline="", encoding="utf-8") as stream:
        rows = list(csv.DictReader(stream))
    assert float(rows[0]["area_inside_cm2"]) <= float(rows[0]["area_kept_cm2"])
    assert float(rows[0]["circle_radius_lo_cm"]) > 0
    with open(sorted(tmp_path.glob("b*.csv"))[0], newline="", encoding="utf-8") as stream:
        assert next(csv.reader(stream)) == ["x_lo_cm", "x_hi_cm", "y_lo_cm", "y_hi_cm", "status"]


@pytest.mark.slow
def test_the_app_shows_the_five_bar_tab_and_its_map(tmp_path):
    import asyncio

    from planar_tui.app.app import WorkbenchApp
    from planar_tui.app.widgets.parallel_panes import FiveBarPane
    from tests.test_app import run_tab

    assert ("5-bar", "workspace5r") in WorkbenchApp.tabs()
    assert WorkbenchApp.pane_classes()["workspace5r"] is FiveBarPane
    preset = tmp_path / "fivebar.toml"
    preset.write_text(PRESET.read_text().replace("precision_cm = 0.05", "precision_cm = 2.0"))
    from planar_tui.app.workbench import Workbench

    app = WorkbenchApp(Workbench.open(preset), output_dir=tmp_path)

    async def drive():
        async with app.run_test(size=(100, 40)) as pilot:
            await run_tab(app, pilot, "workspace5r")
            pane = app.query_one("#pane-workspace5r", FiveBarPane)
            assert pane.result is not None
            assert "working mode any" in pane.result.summary
            assert "█" in str(app.query_one("#pane-workspace5r #workspace-map").render())

    asyncio.run(drive())


def test_the_figure_draws_boxes_the_exact_boundary_a_pose_and_the_circle():
    from planar_tui.figures.fivebar import from_result

    job = jobs()[1]
    fig = from_result(job, run(job, precision_cm=1.0, singularity_precision_cm=1.0))
    gids = {
        artist.get_gid() for ax in fig.axes for artist in [*ax.lines, *ax.collections, *ax.patches]
    }
    assert {"exact", "leg", "inside", "singular", "circle"} <= gids


@pytest.mark.parametrize("mode", ["any", "++", "+-", "-+", "--"])
def test_the_kernels_point_test_agrees_with_the_closed_form_inverse_kinematics(mode):
    from planar_tui.kernels.workspace5r import point_in

    robot = dataclasses.replace(jobs()[0].robot, working_mode=mode)
    legs, limits = robot.leg_arrays()
    rng = np.random.default_rng(25)
    xlo, xhi, ylo, yhi = robot.reach_box_cm()
    x, y = rng.uniform(xlo, xhi, 3000), rng.uniform(ylo, yhi, 3000)
    expected = in_workspace(robot, x, y)
    got = np.array([point_in(a, b, legs, limits) for a, b in zip(x, y, strict=True)])
    assert 0 < expected.sum() < len(x)
    assert np.array_equal(got, expected)

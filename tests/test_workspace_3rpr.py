"""The 3-RPR's workspace (``[[workspace3rpr]]``): the exact polygon reference against closed
forms, the certified bracket against it and against an independent fine grid with its own
error bound, thread-count invariance, bad input, the CLI command and the app's tab."""

from __future__ import annotations

import csv
import dataclasses
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from planar_tui.presets import load_preset
from planar_tui.progress import Progress
from planar_tui.workspace.paving.levels import INSIDE, BoxBudget
from planar_tui.workspace.paving.runner import compute_planar
from tests.conftest import PRESETS, on_one_and_two_threads

JOB = """
[robot3rpr]
base_joints_cm = {base}
platform_points_cm = {platform}

[[workspace3rpr]]
leg_limits_cm = {limits}
orientation_deg = {phi}
precision_cm = {precision}
{extra}output = "rpr.csv"
"""
BASE = [[0, 0], [120, 0], [60, 103.9230485]]
PLATFORM = [[0, 0], [40, 0], [20, 40]]


def job_of(
    tmp_path,
    *,
    base=BASE,
    platform=PLATFORM,
    limits=((20, 80),) * 3,
    phi=0.0,
    precision=0.5,
    extra="",
):
    path = tmp_path / "rpr.toml"
    text = JOB.format(
        base=list(base),
        platform=list(platform),
        limits=[list(row) for row in limits],
        phi=phi,
        precision=precision,
        extra=extra,
    )
    path.write_text(text, encoding="utf-8")
    return load_preset(path).jobs[0]


def pave(job):
    return compute_planar(job.robot, job.spec, BoxBudget(job, Progress()))


def grid_bracket(job, cells=400):
    """An independent reference: the area of the grid cells certainly inside and of those
    not certainly outside. Each leg's signed margin ``min(|p - c| - lo, hi - |p - c|)`` is
    1-Lipschitz, so at a cell centre it decides the whole cell when it exceeds the cell's
    half-diagonal ``r`` (inside for every leg, or outside for one)."""
    robot, spec = job.robot, job.spec
    phi = math.radians(spec.orientation_deg)
    c, s = math.cos(phi), math.sin(phi)
    centres = [
        (ax - (c * qx - s * qy), ay - (s * qx + c * qy))
        for (ax, ay), (qx, qy) in zip(robot.base_joints_cm, robot.platform_points_cm, strict=True)
    ]
    hi_max = max(hi for _, hi in spec.leg_limits_cm)
    x0, x1 = centres[0][0] - hi_max, centres[0][0] + hi_max
    y0 = centres[0][1] - hi_max
    h = (x1 - x0) / cells
    xs, ys = np.meshgrid(x0 + h * (np.arange(cells) + 0.5), y0 + h * (np.arange(cells) + 0.5))
    margins = np.stack(
        [
            np.minimum(np.hypot(xs - cx, ys - cy) - lo, hi - np.hypot(xs - cx, ys - cy))
            for (cx, cy), (lo, hi) in zip(centres, spec.leg_limits_cm, strict=True)
        ]
    )
    r = h / math.sqrt(2.0) + 1e-9
    inside = np.all(margins >= r, axis=0)
    not_outside = np.all(margins >= -r, axis=0)
    return h * h * inside.sum(), h * h * not_outside.sum()


@pytest.mark.parametrize(
    ("limits", "exact"),
    [
        (((20, 80),) * 3, math.pi * (80**2 - 20**2)),  # one annulus, three times
        (((10, 80), (20, 70), (0, 75)), math.pi * (70**2 - 20**2)),  # concentric: [max lo, min hi]
        (((0, 10), (20, 30), (20, 30)), 0.0),  # a disc inside the others' hole
    ],
)
def test_concentric_annuli_have_the_closed_form_area(tmp_path, limits, exact):
    # base joint = platform point for every leg: the three annuli share the centre (0, 0)
    job = job_of(tmp_path, base=PLATFORM, limits=limits, precision=0.25)
    outcome = pave(job)
    g = outcome.geometric
    assert g.inner_cm2 - 1e-6 <= exact <= g.outer_cm2 + 1e-6
    assert abs(g.area_cm2 - exact) <= 1e-4 * max(exact, 1.0)
    assert outcome.area_inside_cm2 <= exact + 1e-9 <= outcome.area_kept_cm2 + 2e-9


def test_two_disjoint_annuli_have_no_workspace(tmp_path):
    base = [[0, 0], [500, 0], [0, 0]]
    job = job_of(tmp_path, base=base, platform=[[0, 0]] * 3, limits=((10, 50),) * 3)
    outcome = pave(job)
    assert outcome.geometric.outer_cm2 == 0.0
    assert outcome.area_kept_cm2 == 0.0 and len(outcome.boxes) == 0


@pytest.mark.parametrize("index", [0, 1])
def test_the_bundled_design_brackets_its_exact_area_within_two_percent(index):
    job = load_preset(PRESETS / "workspace-3rpr.toml").jobs[index]
    within_two_percent(pave(job), grid_bracket(job, 300))


def within_two_percent(outcome, grid):
    """The certified bracket holds the polygon bracket and is at most 2 % of the area wide;
    the grid's bracket ``(lower, upper)`` meets the polygon's."""
    g = outcome.geometric
    assert outcome.area_inside_cm2 <= g.inner_cm2 and g.outer_cm2 <= outcome.area_kept_cm2
    assert outcome.area_kept_cm2 - outcome.area_inside_cm2 <= 0.02 * g.area_cm2
    lower, upper = grid
    assert lower <= g.outer_cm2 and g.inner_cm2 <= upper


def points():
    return st.tuples(st.floats(-60, 60), st.floats(-60, 60))


@settings(deadline=None, max_examples=15, suppress_health_check=[HealthCheck.too_slow])
@given(
    base=st.tuples(points(), points(), points()),
    platform=st.tuples(points(), points(), points()),
    limits=st.lists(st.tuples(st.floats(0, 40), st.floats(5, 80)), min_size=3, max_size=3),
    phi=st.floats(-180, 180),
)
def test_random_geometries_bracket_the_polygon_and_grid_references(
    tmp_path_factory, base, platform, limits, phi
):
    limits = [(lo, lo + width) for lo, width in limits]
    job = job_of(
        tmp_path_factory.mktemp("rpr"),
        base=[list(p) for p in base],
        platform=[list(p) for p in platform],
        limits=limits,
        phi=phi,
        precision=1.0,
    )
    outcome = pave(job)
    g = outcome.geometric
    assert outcome.area_inside_cm2 <= g.outer_cm2 + 1e-6
    assert g.inner_cm2 <= outcome.area_kept_cm2 + 1e-6
    lower, upper = grid_bracket(job, 200)
    assert outcome.area_inside_cm2 <= upper + 1e-6 and lower <= outcome.area_kept_cm2 + 1e-6
    # every corner of a box proved inside is feasible by the plain float test
    inside = outcome.boxes[outcome.status == INSIDE]
    corners = [(b[i], b[j]) for b in inside[:200] for i in (0, 1) for j in (2, 3)]
    p = job.spec.mechanism.parameters(job.robot, job.spec)
    for x, y in corners:
        d2 = (x - p[:, 0]) ** 2 + (y - p[:, 1]) ** 2
        assert np.all(d2 >= p[:, 2] ** 2 * (1 - 1e-12)) and np.all(d2 <= p[:, 3] ** 2 * (1 + 1e-12))


def test_the_boxes_do_not_depend_on_the_thread_count(tmp_path):
    job = job_of(tmp_path, phi=17.0, precision=0.1)
    one, two = on_one_and_two_threads(lambda: pave(job))
    assert np.array_equal(one.boxes, two.boxes) and np.array_equal(one.status, two.status)


def test_refinement_narrows_the_bracket_and_keeps_the_inside_boxes(tmp_path):
    coarse = pave(job_of(tmp_path, precision=0.4))
    refined = pave(job_of(tmp_path, precision=0.4, extra="refine_precision_cm = 0.1\n"))
    exact = coarse.geometric.area_cm2
    assert refined.area_inside_cm2 >= coarse.area_inside_cm2
    assert refined.area_kept_cm2 <= coarse.area_kept_cm2
    assert refined.area_inside_cm2 <= exact <= refined.area_kept_cm2


def preset_text(robot: str = "", job: str = "") -> str:
    """A small 3-RPR preset; each line ``key = value`` of ``job`` replaces or adds a job key."""
    keys = {"leg_limits_cm": "[[20, 80], [20, 80], [20, 80]]", "precision_cm": "1"}
    for line in job.splitlines():
        key, value = line.split(" = ", 1)
        keys[key] = value
    lines = "".join(f"{key} = {value}\n" for key, value in keys.items())
    return f'[robot3rpr]\n{robot}\n[[workspace3rpr]]\n{lines}output = "o.csv"\n'


@pytest.mark.parametrize(
    ("robot", "job", "fragment"),
    [
        ("", "leg_limits_cm = [[20, 80], [20, 80]]", "workspace3rpr[1].leg_limits_cm: has 2 rows"),
        ("", "leg_limits_cm = [[20, 80], [80, 20], [20, 80]]", "leg 2 range [80, 20]"),
        ("", "leg_limits_cm = [[-1, 80], [20, 80], [20, 80]]", "leg 1 range [-1, 80]"),
        ("", 'orientation_deg = "x"', "workspace3rpr[1].orientation_deg"),
        ("", "precision_cm = 0", "workspace3rpr[1].precision_cm"),
        ("", 'form = "mean-value"', "workspace3rpr[1].form"),
        ("", "refine_precision_cm = 2", "refine_precision_cm: is 2 > precision_cm"),
        ("", "search_box_cm = [[0, 1], [0, 1]]", "search_box_cm: cannot contain the legs' reach"),
        ("", "box_budget = 0", "workspace3rpr[1].box_budget"),
        ("", 'geometric_reference = "yes"', "workspace3rpr[1].geometric_reference"),
        ("base_joints_cm = [[0, 0], [1, 0]]", "", "robot3rpr.base_joints_cm: has 2 points"),
        ("platform_points_cm = [[0, 0], [1, 0], [1]]", "", "robot3rpr.platform_points_cm"),
    ],
)
def test_bad_input_is_one_line_exit_2_and_nothing_written(cli, tmp_path, robot, job, fragment):
    refused(cli, tmp_path, "workspace3rpr", preset_text(robot, job), fragment)


def refused(cli, tmp_path, command, text, fragment):
    """The command refuses the preset ``text``: exit 2, one ``error:`` line holding
    ``fragment``, nothing written."""
    preset = tmp_path / "bad.toml"
    preset.write_text(text, encoding="utf-8")
    result = cli(command, preset, "--out-dir", tmp_path / "out")
    assert result.exit_code == 2, result.output
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: ") and fragment in lines[0], lines
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())


def test_the_command_writes_the_summary_and_boxes_csv_and_prints_the_map(cli, tmp_path):
    preset = tmp_path / "rpr.toml"
    preset.write_text(preset_text(), encoding="utf-8")
    result = cli("workspace3rpr", preset, "--out-dir", tmp_path, "--boxes", tmp_path / "b.csv")
    assert result.exit_code == 0, result.output
    with open(tmp_path / "o.csv", encoding="utf-8") as f:
        (row,) = list(csv.DictReader(f))
    exact = float(row["area_geometric_cm2"])
    assert float(row["area_inside_cm2"]) <= exact <= float(row["area_kept_cm2"])
    assert row["form"] == "natural"
    with open(tmp_path / "b.csv", encoding="utf-8") as f:
        boxes = list(csv.DictReader(f))
    assert boxes and {b["status"] for b in boxes} == {"inside", "boundary"}
    assert "x (cm)" in result.stdout


def test_the_app_has_the_kinds_tab_with_the_workspace_pane():
    from planar_tui.app.app import WorkbenchApp
    from planar_tui.app.widgets.workspace_pane import WorkspacePane

    assert ("3-RPR", "workspace3rpr") in WorkbenchApp.tabs()
    pane = WorkbenchApp.pane_classes()["workspace3rpr"]
    assert issubclass(pane, WorkspacePane) and pane.kind == "workspace3rpr"


def test_the_exact_polygon_is_the_figures_boundary(tmp_path):
    from planar_tui.batch import run_job
    from planar_tui.figures.workspace import from_planar_result

    job = job_of(tmp_path, precision=2.0)
    result = run_job(job, Progress())
    figure = from_planar_result(job, result)
    assert any(line.get_gid() == "exact" for line in figure.axes[0].lines)
    assert dataclasses.is_dataclass(job.spec)


@pytest.mark.slow
def test_the_app_tab_runs_the_job_and_shows_its_map(tmp_path):
    import asyncio

    from planar_tui.app.app import WorkbenchApp
    from planar_tui.app.workbench import Workbench
    from tests.test_app import run_tab

    preset = tmp_path / "rpr.toml"
    preset.write_text(
        preset_text(job="orientation_deg = 30\nsingularities = true"), encoding="utf-8"
    )
    app = WorkbenchApp(Workbench.open(preset), output_dir=tmp_path)

    async def drive():
        async with app.run_test(size=(100, 40)) as pilot:
            await run_tab(app, pilot, "workspace3rpr")
            screen = app.export_text()
            result = app.query_one("#pane-workspace3rpr").result
            assert result.summary[:24] in screen and "█" in screen and "▒" in screen
            assert "singularity-free" in result.summary
            g = result.outcome.geometric
            assert result.outcome.area_inside_cm2 <= g.area_cm2 <= result.outcome.area_kept_cm2

    asyncio.run(drive())


def test_a_leg_limit_of_1e199_cm_gives_the_exact_area_of_a_long_finite_one(tmp_path):
    """An upper leg limit far beyond the reach box leaves the intersection unchanged: the
    polygons of a 1e199 cm limit (capped at the reach box, else GEOS overflowed and the
    "exact" area came out 0) equal those of 1e4 cm, and the grid reference brackets them."""
    from planar_tui.workspace.rpr.robot import workspace_polygon

    huge = job_of(tmp_path, limits=((20, 1e199), (20, 80), (20, 80)))
    finite = job_of(tmp_path, limits=((20, 1e4), (20, 80), (20, 80)))
    for outward in (False, True):
        area = workspace_polygon(huge.robot, huge.spec, 256, outward).area
        assert area == pytest.approx(
            workspace_polygon(finite.robot, finite.spec, 256, outward).area, rel=1e-12
        )
        assert area > 0.0
    inside, kept = grid_bracket(finite)
    assert inside <= workspace_polygon(huge.robot, huge.spec, 256, True).area <= kept

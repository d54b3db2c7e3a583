"""The 3-PRR's workspace (``[[workspace3prr]]``): the leg criterion against brute-force
sampling of the stroke, the exact polygon reference against closed forms, the certified
bracket against it and against an independent grid with its error bound, thread-count
invariance, bad input, the CLI command and the app's tab."""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from planar_tui.kernels.workspace3prr import prr_point_feasible

from planar_tui.presets import load_preset
from tests.conftest import PRESETS, on_one_and_two_threads
from tests.test_workspace_3rpr import pave, refused, within_two_percent

JOB = """
[robot3prr]
slider_points_cm = {points}
slider_angles_deg = {angles}
strokes_cm = {strokes}
distal_cm = {distal}
platform_points_cm = {platform}

[[workspace3prr]]
orientation_deg = {phi}
precision_cm = {precision}
{extra}output = "prr.csv"
"""
TRIANGLE = [[0, 0], [120, 0], [60, 103.9230485]]


def job_of(
    tmp_path,
    *,
    points=TRIANGLE,
    angles=(0, 120, 240),
    strokes=((10, 110),) * 3,
    distal=(40, 40, 40),
    platform=((0, 0), (40, 0), (20, 40)),
    phi=0.0,
    precision=0.5,
    extra="",
):
    path = tmp_path / "prr.toml"
    path.write_text(
        JOB.format(
            points=[list(p) for p in points],
            angles=list(angles),
            strokes=[list(s) for s in strokes],
            distal=list(distal),
            platform=[list(p) for p in platform],
            phi=phi,
            precision=precision,
            extra=extra,
        ),
        encoding="utf-8",
    )
    return load_preset(path).jobs[0]


def legs(job):
    """Per leg, independently of the package: the shifted stroke ends and the length."""
    robot = job.robot
    phi = math.radians(job.spec.orientation_deg)
    c, s = math.cos(phi), math.sin(phi)
    result = []
    for (bx, by), angle, (lo, hi), length, (qx, qy) in zip(
        robot.slider_points_cm,
        robot.slider_angles_deg,
        robot.strokes_cm,
        robot.distal_cm,
        robot.platform_points_cm,
        strict=True,
    ):
        u = np.array([math.cos(math.radians(angle)), math.sin(math.radians(angle))])
        origin = np.array([bx - (c * qx - s * qy), by - (s * qx + c * qy)])
        result.append((origin + lo * u, origin + hi * u, length))
    return result


def margins(job, xs, ys):
    """Each leg's 1-Lipschitz signed margin ``min(l - d_seg, d_end - l)`` at the points."""
    out = []
    for e0, e1, length in legs(job):
        d = e1 - e0
        t = np.clip(((xs - e0[0]) * d[0] + (ys - e0[1]) * d[1]) / (d @ d), 0.0, 1.0)
        seg = np.hypot(xs - e0[0] - t * d[0], ys - e0[1] - t * d[1])
        end = np.maximum(np.hypot(xs - e0[0], ys - e0[1]), np.hypot(xs - e1[0], ys - e1[1]))
        out.append(np.minimum(length - seg, end - length))
    return np.stack(out)


def grid_bracket(job, cells=300):
    """Area of the grid cells certainly inside, and of those not certainly outside."""
    x0, x1, y0, y1 = job.spec.mechanism.reach_box(job.robot, job.spec)
    side = max(x1 - x0, y1 - y0, 1e-9)
    h = side / cells
    xs, ys = np.meshgrid(x0 + h * (np.arange(cells) + 0.5), y0 + h * (np.arange(cells) + 0.5))
    m = margins(job, xs, ys)
    r = h / math.sqrt(2.0) + 1e-9
    return h * h * np.all(m >= r, axis=0).sum(), h * h * np.all(m >= -r, axis=0).sum()


def test_the_leg_criterion_is_the_brute_force_range_of_the_stroke(tmp_path):
    """|C - B - s u| = l for some s in the stroke iff d_seg <= l <= d_end: checked against
    a fine sampling of s (the sampled range is within its step of the true one)."""
    job = job_of(tmp_path)
    rng = np.random.default_rng(7)
    p = job.spec.mechanism.parameters(job.robot, job.spec)
    s = np.linspace(0.0, 1.0, 20001)
    for _ in range(400):
        x, y = rng.uniform(-40, 160, size=2)
        closes = True
        decided = True
        for e0, e1, length in legs(job):
            d = np.hypot(x - (e0[0] + s * (e1 - e0)[0]), y - (e0[1] + s * (e1 - e0)[1]))
            step = np.linalg.norm(e1 - e0) / (len(s) - 1)
            if d.min() - step > length or d.max() + step < length:
                closes = False
            elif not (d.min() + step <= length <= d.max() - step):
                decided = False  # too near the leg's boundary for the sampling to tell
        if decided:
            assert prr_point_feasible(x, y, p) == closes, (x, y)


def single_leg_area(length_cm, stroke_cm):
    """Stadium minus lens: ``2 l L + π l²`` minus the lens of two discs ``L`` apart."""
    area = 2.0 * length_cm * stroke_cm + math.pi * length_cm**2
    if stroke_cm < 2.0 * length_cm:
        half = stroke_cm / 2.0
        lens = 2.0 * length_cm**2 * math.acos(half / length_cm) - stroke_cm * math.sqrt(
            length_cm**2 - half**2
        )
        area -= lens
    return area


@pytest.mark.parametrize(("length", "stroke"), [(40.0, 100.0), (40.0, 50.0), (30.0, 5.0)])
def test_three_identical_legs_have_the_closed_form_area(tmp_path, length, stroke):
    job = job_of(
        tmp_path,
        points=[[0, 0]] * 3,
        angles=(30, 30, 30),
        strokes=((0, stroke),) * 3,
        distal=(length,) * 3,
        platform=((0, 0),) * 3,
        precision=0.25,
    )
    exact = single_leg_area(length, stroke)
    outcome = pave(job)
    g = outcome.geometric
    assert g.inner_cm2 - 1e-6 <= exact <= g.outer_cm2 + 1e-6
    assert outcome.area_inside_cm2 <= exact <= outcome.area_kept_cm2


def test_the_bundled_design_brackets_its_exact_area_within_two_percent():
    job = load_preset(PRESETS / "workspace-3prr.toml").jobs[0]
    within_two_percent(pave(job), grid_bracket(job))


def points():
    return st.tuples(st.floats(-40, 40), st.floats(-40, 40))


@settings(deadline=None, max_examples=15, suppress_health_check=[HealthCheck.too_slow])
@given(
    base=st.tuples(points(), points(), points()),
    angles=st.tuples(*[st.floats(-180, 180)] * 3),
    strokes=st.lists(st.tuples(st.floats(-40, 40), st.floats(1, 80)), min_size=3, max_size=3),
    distal=st.tuples(*[st.floats(5, 60)] * 3),
    platform=st.tuples(points(), points(), points()),
    phi=st.floats(-180, 180),
)
def test_random_geometries_bracket_the_polygon_and_grid_references(
    tmp_path_factory, base, angles, strokes, distal, platform, phi
):
    job = job_of(
        tmp_path_factory.mktemp("prr"),
        points=[list(p) for p in base],
        angles=angles,
        strokes=[(lo, lo + w) for lo, w in strokes],
        distal=distal,
        platform=[list(p) for p in platform],
        phi=phi,
        precision=1.0,
    )
    outcome = pave(job)
    g = outcome.geometric
    assert outcome.area_inside_cm2 <= g.outer_cm2 + 1e-6
    assert g.inner_cm2 <= outcome.area_kept_cm2 + 1e-6
    lower, upper = grid_bracket(job, 200)
    assert outcome.area_inside_cm2 <= upper + 1e-6 and lower <= outcome.area_kept_cm2 + 1e-6
    inside = outcome.boxes[outcome.status == 2][:200]
    if len(inside):  # every corner of a box proved inside: every leg's margin >= 0
        xs = np.concatenate([inside[:, 0], inside[:, 1], inside[:, 0], inside[:, 1]])
        ys = np.concatenate([inside[:, 2], inside[:, 2], inside[:, 3], inside[:, 3]])
        assert np.all(margins(job, xs, ys) >= -1e-9)


def test_the_boxes_do_not_depend_on_the_thread_count(tmp_path):
    job = job_of(tmp_path, phi=11.0, precision=0.1)
    one, two = on_one_and_two_threads(lambda: pave(job))
    assert np.array_equal(one.boxes, two.boxes) and np.array_equal(one.status, two.status)


def preset_text(robot: str = "", job: str = "") -> str:
    return f'[robot3prr]\n{robot}\n[[workspace3prr]]\nprecision_cm = 1\n{job}\noutput = "o.csv"\n'


@pytest.mark.parametrize(
    ("robot", "job", "fragment"),
    [
        ("strokes_cm = [[0, 1], [0, 1]]", "", "robot3prr.strokes_cm: has 2 rows"),
        ("strokes_cm = [[0, 1], [1, 1], [0, 1]]", "", "leg 2 stroke [1, 1]"),
        ("slider_angles_deg = [0, 1]", "", "robot3prr.slider_angles_deg"),
        ("distal_cm = [40, 0, 40]", "", "robot3prr.distal_cm"),
        ("slider_points_cm = [[0, 0]]", "", "robot3prr.slider_points_cm: has 1 points"),
        ("platform_points_cm = 3", "", "robot3prr.platform_points_cm"),
        ("", 'form = "natural"', "workspace3prr[1].form"),
        ("", "refine_precision_cm = 2", "refine_precision_cm: is 2 > precision_cm"),
        ("", "search_box_cm = [[0, 1], [0, 1]]", "search_box_cm: cannot contain the legs' reach"),
    ],
)
def test_bad_input_is_one_line_exit_2_and_nothing_written(cli, tmp_path, robot, job, fragment):
    refused(cli, tmp_path, "workspace3prr", preset_text(robot, job), fragment)


def test_the_command_writes_the_summary_csv_and_prints_the_map(cli, tmp_path):
    preset = tmp_path / "prr.toml"
    preset.write_text(preset_text(), encoding="utf-8")
    result = cli("workspace3prr", preset, "--out-dir", tmp_path)
    assert result.exit_code == 0, result.output
    with open(tmp_path / "o.csv", encoding="utf-8") as f:
        (row,) = list(csv.DictReader(f))
    exact = float(row["area_geometric_cm2"])
    assert float(row["area_inside_cm2"]) <= exact <= float(row["area_kept_cm2"])
    assert row["form"] == "distance" and "x (cm)" in result.stdout


def test_the_app_has_the_kinds_tab_with_the_workspace_pane():
    from planar_tui.app.app import WorkbenchApp

    assert ("3-PRR", "workspace3prr") in WorkbenchApp.tabs()
    assert WorkbenchApp.pane_classes()["workspace3prr"].kind == "workspace3prr"

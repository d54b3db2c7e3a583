"""Tolerance-certified 3-RRR workspaces (issue 25, item 2), checked against robots sampled
within the tolerances with an independent float test (circle-circle intersection), the
nominal workspace eroded in constraint value (polygon geometry), the nominal paving at
zero tolerance, one and two threads, the CLI and bad input."""

from __future__ import annotations

import csv
import itertools
import math
from dataclasses import replace

import numpy as np
import pytest

from planar_tui.progress import Progress
from planar_tui.workspace.paving.levels import INSIDE, BoxBudget
from planar_tui.workspace.paving.tolerance import Tolerance, erosion_bound_cm, tolerance_of
from planar_tui.workspace.rrr.compute import compute_workspace
from planar_tui.workspace.rrr.job import WorkspaceSpec
from planar_tui.workspace.rrr.robot import Robot3RRR
from tests.conftest import on_one_and_two_threads

ROBOT = Robot3RRR()  # paper B, Table 2
LIMITS = ((20.0, 70.0), (110.0, 160.0), (245.0, 295.0))  # paper B, Table 3
PER_QUANTITY = (
    ("base_joints_cm", 0.05),
    ("distal_cm", 0.1),
    ("platform_points_cm", 0.02),
    ("proximal_cm", 0.08),
)


class _Job:
    def __init__(self, spec):
        self.spec, self.preset_path, self.label, self.key = spec, "test", "test", "workspace"


def spec_for(form="arc-distance", precision=0.25, phi=0.0, **extra) -> WorkspaceSpec:
    return WorkspaceSpec(
        joint_limits_deg=LIMITS,
        orientation_deg=phi,
        precision_cm=precision,
        form=form,
        geometric_reference=False,
        **extra,
    )


def run(spec):
    return compute_workspace(ROBOT, spec, BoxBudget(_Job(spec), Progress()))


# -- the independent float test -------------------------------------------------------------


def leg_closes(v, base, q, l1, l2, lim_deg, phi, slack):
    """Leg closure at platform positions ``v`` (N, 2) for one robot's leg, by the
    circle-circle intersection: the elbow angle β with cos β = (r² + l1² − l2²)/(2 r l1)
    and θ = α ± β on the joint range (``slack`` > 0 counts near misses as closing)."""
    c, s = math.cos(phi), math.sin(phi)
    rel = v + np.array([c * q[0] - s * q[1], s * q[0] + c * q[1]]) - np.asarray(base)
    r = np.hypot(rel[:, 0], rel[:, 1])
    cos_beta = (r * r + l1 * l1 - l2 * l2) / (2.0 * np.maximum(r, 1e-300) * l1)
    reach = np.abs(cos_beta) <= 1.0 + slack
    beta = np.arccos(np.clip(cos_beta, -1.0, 1.0))
    alpha = np.arctan2(rel[:, 1], rel[:, 0])
    lo, hi = np.radians(lim_deg)
    on_arc = np.zeros(len(v), dtype=bool)
    for theta in (alpha + beta, alpha - beta):
        shifted = lo + np.mod(theta - lo, 2.0 * np.pi)
        on_arc |= (shifted <= hi + slack) | (shifted - 2.0 * np.pi >= lo - slack)
    return reach & on_arc


def reaches(v, robot_params, phi, slack=0.0):
    """Every leg of one sampled robot (per leg: base, q, l1, l2) closes at ``v``."""
    ok = np.ones(len(v), dtype=bool)
    for (base, q, l1, l2), lim in zip(robot_params, LIMITS, strict=True):
        ok &= leg_closes(v, base, q, l1, l2, lim, phi, slack)
    return ok


def sampled_robots(tolerance: Tolerance, rng, n_random=12, n_vertex=12):
    """Robots within the tolerances, each leg's parts independent: vertices of the
    parameter box (every coordinate at ±its tolerance) and uniform random ones, plus the
    nominal robot."""
    t = tolerance.of
    nominal = list(zip(ROBOT.base_joints_cm(), ROBOT.platform_points_cm(), strict=True))
    widths = (
        [t("base_joints_cm")] * 2
        + [t("platform_points_cm")] * 2
        + [
            t("proximal_cm"),
            t("distal_cm"),
        ]
    )
    robots = [[(b, q, ROBOT.proximal_cm, ROBOT.distal_cm) for b, q in nominal]]
    for k in range(n_random + n_vertex):
        legs = []
        for base, q in nominal:
            u = rng.choice([-1.0, 1.0], 6) if k < n_vertex else rng.uniform(-1.0, 1.0, 6)
            d = u * np.array(widths)
            legs.append(
                (
                    (base[0] + d[0], base[1] + d[1]),
                    (q[0] + d[2], q[1] + d[3]),
                    ROBOT.proximal_cm + d[4],
                    ROBOT.distal_cm + d[5],
                )
            )
        robots.append(legs)
    return robots


def covered(points, boxes):
    """Which points lie in (or on) the union of the boxes (rows x_lo, x_hi, y_lo, y_hi)."""
    import shapely

    union = shapely.union_all(shapely.box(boxes[:, 0], boxes[:, 2], boxes[:, 1], boxes[:, 3]))
    return shapely.intersects_xy(union, points[:, 0], points[:, 1])


def points_in(boxes, rng, per_box=4):
    """Random points in each box plus its corners pulled in by 1e-7 cm."""
    lo, hi = boxes[:, [0, 2]], boxes[:, [1, 3]]
    pts = [lo + (hi - lo) * rng.uniform(0.0, 1.0, (len(boxes), 2)) for _ in range(per_box)]
    for cx, cy in itertools.product((0, 1), repeat=2):
        corner = np.where([cx, cy], hi - 1e-7, lo + 1e-7)
        pts.append(corner)
    return np.concatenate(pts)


def grid_points(outcome, n=220):
    xlo, xhi, ylo, yhi = outcome.extent_cm
    xs, ys = np.meshgrid(np.linspace(xlo, xhi, n), np.linspace(ylo, yhi, n))
    return np.column_stack([xs.ravel(), ys.ravel()])


CASES = [
    pytest.param("arc-distance", {"tolerance_cm": 0.1}, 0.0, id="arc-uniform"),
    pytest.param("mean-value", {"tolerance_cm": 0.1}, 0.0, id="mean-value-uniform"),
    pytest.param("slope", {"tolerances_cm": PER_QUANTITY}, 20.0, id="slope-per-quantity-phi20"),
    pytest.param("arc-distance", {"tolerances_cm": PER_QUANTITY}, 20.0, id="arc-per-quantity"),
]


@pytest.mark.parametrize(("form", "keys", "phi"), CASES)
def test_robust_inside_boxes_lie_in_every_sampled_robots_workspace(form, keys, phi):
    """``all``: every point of an inside box is reached by every sampled robot (vertices
    of the parameter box and random ones); the robust bracket lies within the nominal."""
    spec = spec_for(form, phi=phi, tolerance_mode="all", **keys)
    robust = run(spec)
    inside = robust.boxes[robust.status == INSIDE]
    assert len(inside) > 50
    rng = np.random.default_rng(1)
    points = points_in(inside, rng)
    for params in sampled_robots(tolerance_of(spec), rng):
        assert reaches(points, params, math.radians(phi), slack=1e-9).all()
    nominal = run(spec_for(form, phi=phi))
    assert robust.area_inside_cm2 < nominal.area_inside_cm2
    assert robust.area_kept_cm2 < nominal.area_kept_cm2


@pytest.mark.parametrize(("form", "keys", "phi"), CASES)
def test_some_kept_boxes_hold_every_sampled_robots_workspace(form, keys, phi):
    """``some``: a grid point any sampled robot reaches lies in a kept box; an inside
    box's points lie in the nominal workspace dilated in constraint value by the bound."""
    spec = spec_for(form, phi=phi, tolerance_mode="some", **keys)
    some = run(spec)
    rng = np.random.default_rng(2)
    points = grid_points(some)
    union = np.zeros(len(points), dtype=bool)
    for params in sampled_robots(tolerance_of(spec), rng):
        union |= reaches(points, params, math.radians(phi), slack=-1e-9)
    assert union.sum() > 1000
    assert covered(points[union], some.boxes).all()
    nominal = run(spec_for(form, phi=phi))
    assert some.area_inside_cm2 > nominal.area_inside_cm2
    assert some.area_kept_cm2 > nominal.area_kept_cm2
    # inside "some" boxes lie in the nominal workspace dilated in constraint value by B:
    # distances to a finely sampled arc (spacing h: D_min <= sampled min <= D_min + h/2)
    bound = erosion_bound_cm(tolerance_of(spec))
    inside = some.boxes[some.status == INSIDE]
    points = points_in(inside[rng.choice(len(inside), 100)], rng, 1)
    for (dx, dy), lim in zip(ROBOT.leg_offsets_cm(math.radians(phi)), LIMITS, strict=True):
        theta = np.linspace(*np.radians(lim), 4001)
        h = ROBOT.proximal_cm * (theta[1] - theta[0])
        arc = ROBOT.proximal_cm * np.column_stack([np.cos(theta), np.sin(theta)])
        rel = points + np.array([dx, dy])
        dist = np.hypot(*(rel[:, None, :] - arc[None, :, :]).transpose(2, 0, 1))
        assert (dist.min(axis=1) <= ROBOT.distal_cm + bound + h).all()
        assert (dist.max(axis=1) >= ROBOT.distal_cm - bound).all()


def eroded_polygon(bound_cm, phi):
    """The nominal workspace eroded in constraint value, exactly (inner polygons of
    :mod:`planar_tui.workspace.paving.geometry`): per leg ``d_min <= l2 - B`` and
    ``d_max >= l2 + B``, i.e. ``leg_region(l1, l2 - B) ∩ leg_region(l1, l2 + B)``."""
    from shapely import affinity, intersection_all

    from planar_tui.workspace.paving.geometry import leg_region

    regions = []
    l1, l2 = ROBOT.proximal_cm, ROBOT.distal_cm
    for (dx, dy), (lo, hi) in zip(ROBOT.leg_offsets_cm(phi), LIMITS, strict=True):
        lo, hi = math.radians(lo), math.radians(hi)
        shorter = leg_region(l1, l2 - bound_cm, lo, hi, 4096, False)
        longer = leg_region(l1, l2 + bound_cm, lo, hi, 4096, False)
        regions.append(affinity.translate(shorter.intersection(longer), -dx, -dy))
    return intersection_all(regions)


@pytest.mark.parametrize(("form", "keys", "phi"), CASES)
def test_robust_workspace_contains_the_nominal_eroded_by_the_bound(form, keys, phi):
    """Every leg's d_min and d_max move by at most σ over the tolerances and l2 by t2, so
    the robust workspace holds the nominal one eroded in constraint value by
    B = √2 (t_A + t_q) + t1 + t2: its points lie in kept boxes, its area is at most the
    kept area, and the proved area misses at most a band of two box diagonals along its
    boundary."""
    import shapely

    spec = spec_for(form, phi=phi, tolerance_mode="all", **keys)
    robust = run(spec)
    bound = erosion_bound_cm(tolerance_of(spec))
    eroded = eroded_polygon(bound, math.radians(phi))
    assert eroded.area > 30.0
    assert eroded.area <= robust.area_kept_cm2
    rng = np.random.default_rng(3)
    points = grid_points(robust, 300)
    inside_eroded = shapely.contains_xy(eroded, points[:, 0], points[:, 1])
    assert covered(points[inside_eroded], robust.boxes).all()
    band = eroded.length * 2.0 * math.sqrt(2.0) * spec.precision_cm
    assert robust.area_inside_cm2 >= eroded.area - band
    # the bound holds for the sampled robots too: the float test on the eroded set
    for params in sampled_robots(tolerance_of(spec), rng, 4, 4):
        assert reaches(points[inside_eroded], params, math.radians(phi), slack=1e-9).all()


@pytest.mark.parametrize("form", ["arc-distance", "mean-value", "natural"])
@pytest.mark.parametrize("mode", ["all", "some"])
def test_zero_tolerance_is_the_nominal_result(form, mode):
    """±0: the same boxes, status and areas as the nominal robot."""
    nominal = run(spec_for(form))
    zero = run(spec_for(form, tolerance_cm=0.0, tolerance_mode=mode))
    assert np.array_equal(zero.boxes, nominal.boxes)
    assert np.array_equal(zero.status, nominal.status)
    assert (zero.area_inside_cm2, zero.area_kept_cm2) == (
        nominal.area_inside_cm2,
        nominal.area_kept_cm2,
    )


def test_tolerance_brackets_nest_as_the_sets_do():
    """R(1 mm) ⊂ R(0.1 mm) ⊂ W ⊂ S(0.1 mm) ⊂ S(1 mm) (R robust, S "some", W nominal), so
    each proved area is at most the next set's kept area and the exact nominal area lies
    between the robust proved and the "some" kept areas; at ±1 mm the loss is real: the
    robust kept area is below the exact nominal area."""
    from planar_tui.workspace.rrr.geometry import geometric_area

    exact = geometric_area(ROBOT, spec_for().limits_rad, 0.0).area_cm2
    robust_1, robust_01, some_01, some_1 = (
        run(spec_for(precision=0.0625, tolerance_cm=t, tolerance_mode=m))
        for t, m in ((0.1, "all"), (0.01, "all"), (0.01, "some"), (0.1, "some"))
    )
    assert robust_1.area_inside_cm2 <= robust_01.area_kept_cm2
    assert robust_01.area_inside_cm2 <= exact <= some_01.area_kept_cm2
    assert some_01.area_inside_cm2 <= some_1.area_kept_cm2
    assert robust_1.area_kept_cm2 < exact < some_1.area_inside_cm2


def test_vertex_robot_moves_the_distance_by_the_first_order_maximum():
    """The kernels' first-order shift m = max n·ξ over the tolerances equals a brute-force
    maximum over the vertices of the parameter box, the vertex robot attains it, and its
    parameters lie within the tolerances."""
    from planar_tui.kernels.workspace_tolerance import (
        ALL,
        first_order_shift,
        tolerance_vector,
        unit_gradient,
        vertex_shift,
    )

    rng = np.random.default_rng(4)
    for _ in range(50):
        t_a, t_q, t_1 = rng.uniform(0.0, 0.2, 3)
        phi = rng.uniform(-math.pi, math.pi)
        tol = tolerance_vector(ALL, t_a, t_q, t_1, 0.0, phi)
        px, py = rng.uniform(-60.0, 60.0, 2)
        angle = rng.uniform(-math.pi, math.pi)
        nx, ny, ex, ey = unit_gradient(px, py, 30.0, angle)
        c, s = math.cos(phi), math.sin(phi)
        best = -math.inf
        for ax, ay, bx, by, tau in itertools.product((-1, 1), repeat=5):
            dx = -ax * t_a + c * bx * t_q - s * by * t_q  # ξ = -a + R b - τ e
            dy = -ay * t_a + s * bx * t_q + c * by * t_q
            best = max(best, nx * (dx - tau * t_1 * ex) + ny * (dy - tau * t_1 * ey))
        assert first_order_shift(px, py, 30.0, angle, tol) == pytest.approx(best, abs=1e-12)
        dx, dy, tau = vertex_shift(px, py, 30.0, angle, 1.0, tol)
        assert nx * (dx - tau * ex) + ny * (dy - tau * ey) == pytest.approx(best, abs=1e-6)
        assert abs(tau) <= t_1


def test_paving_is_the_same_on_one_and_two_threads():
    for form in ("arc-distance", "mean-value"):
        spec = spec_for(form, precision=0.125, tolerance_cm=0.05, tolerance_mode="all")
        one, two = on_one_and_two_threads(lambda s=spec: run(s))
        assert np.array_equal(one.boxes, two.boxes) and np.array_equal(one.status, two.status)
        assert one.boxes_processed == two.boxes_processed


# -- the job: keys, CLI, bad input ----------------------------------------------------------

PRESET = """
[robot3rrr]
name = "paper B, Table 2"
base_side_cm = 120
platform_side_cm = 40
proximal_cm = 30
distal_cm = 30
[workspace]
joint_limits_deg = [[20, 70], [110, 160], [245, 295]]
precision_cm = 0.25
{extra}output = "ws.csv"
"""


def write(tmp_path, extra):
    path = tmp_path / "ws.toml"
    if "form =" not in extra:
        extra = 'form = "arc-distance"\n' + extra
    path.write_text(PRESET.format(extra=extra), encoding="utf-8")
    return path


def read_rows(path):
    with open(path, encoding="utf-8") as f:
        return list(csv.DictReader(f))


def test_cli_writes_the_tolerance_columns_and_the_map_layers(cli, tmp_path):
    preset = write(tmp_path, 'tolerance_cm = 0.1\ntolerance_mode = "all"\n')
    result = cli("workspace", preset, "--out-dir", tmp_path)
    assert result.exit_code == 0, result.output
    (row,) = read_rows(tmp_path / "ws.csv")
    assert row["tolerance_mode"] == "all" and float(row["tolerance_distal_cm"]) == 0.1
    direct = run(spec_for(tolerance_cm=0.1, tolerance_mode="all"))
    assert float(row["area_inside_cm2"]) == pytest.approx(direct.area_inside_cm2, rel=1e-12)
    assert "tolerance all ±0.1 cm" in result.stdout
    assert "▓ nominal robot only" in result.stdout and "░ some robot only" in result.stdout
    # The summary's result cell wraps at 80 columns: its words read across the table's rows.
    words = " ".join(result.output.replace("│", " ").split())
    assert "nominal [" in words and "some [" in words


def test_cli_options_override_the_tolerance_keys(cli, tmp_path):
    preset = write(tmp_path, "tolerance_cm = 0.1\n")
    result = cli(
        "workspace",
        preset,
        "--tolerance",
        "0.01",
        "--tolerance-mode",
        "some",
        "--out-dir",
        tmp_path,
        "--no-map",
    )
    assert result.exit_code == 0, result.output
    (written,) = [p for p in tmp_path.glob("ws*.csv")]
    (row,) = read_rows(written)
    assert row["tolerance_mode"] == "some" and float(row["tolerance_base_joints_cm"]) == 0.01


def test_without_tolerance_keys_the_summary_is_unchanged(cli, tmp_path):
    """No tolerance: the nominal summary columns only (the bundled presets' CSVs)."""
    from planar_tui.workspace.paving.levels import SUMMARY_HEADER

    result = cli("workspace", write(tmp_path, ""), "--out-dir", tmp_path, "--no-map")
    assert result.exit_code == 0, result.output
    with open(tmp_path / "ws.csv", encoding="utf-8") as f:
        header = next(csv.reader(f))
    assert not any(name.startswith("tolerance") for name in header)
    assert header[0] == SUMMARY_HEADER[0] and header[-1] == SUMMARY_HEADER[-1]


@pytest.mark.parametrize(
    ("extra", "fragment"),
    [
        ('tolerance_mode = "all"\n', "tolerance_mode"),
        ('tolerance_cm = 0.1\ntolerance_mode = "every"\n', "tolerance_mode"),
        ("tolerance_cm = -0.1\n", "tolerance_cm"),
        ('tolerance_cm = "a"\n', "tolerance_cm"),
        ("tolerances_cm = { l3_cm = 0.1 }\n", "tolerances_cm.l3_cm"),
        ("tolerances_cm = { distal_cm = -1 }\n", "tolerances_cm.distal_cm"),
        ("tolerances_cm = { distal_cm = true }\n", "tolerances_cm.distal_cm"),
        ("tolerances_cm = 0.1\n", "tolerances_cm"),
        ("tolerance_cm = 0.1\nsingularities = true\n", "singularities"),
        ("tolerance_cm = 30\n", "tolerance_cm"),
        ("tolerances_cm = { proximal_cm = 31 }\n", "tolerances_cm"),
        ('tolerance_cm = 0.1\nform = "geometric"\n', "form"),
        ('tolerance_cm = 0.1\nform = "mean-value"\nstrategy = "joint"\n', "strategy"),
        (
            'tolerance_cm = 0.1\norientation_deg = [-1, 1]\norientation_mode = "total"\n',
            "orientation_deg",
        ),
    ],
)
def test_bad_tolerance_input_is_one_line_exit_2_and_nothing_written(cli, tmp_path, extra, fragment):
    preset = write(tmp_path, extra)
    result = cli("workspace", preset, "--out-dir", tmp_path)
    assert result.exit_code == 2, result.output
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: ") and fragment in lines[0]
    assert str(preset) in lines[0]
    assert not (tmp_path / "ws.csv").exists()


def test_per_quantity_tolerances_override_the_uniform_one():
    spec = spec_for(tolerance_cm=0.1, tolerances_cm=(("distal_cm", 0.0),))
    tolerance = tolerance_of(spec)
    assert tolerance.mode == "all" or spec.tolerance_mode is None
    assert tolerance.of("distal_cm") == 0.0 and tolerance.of("proximal_cm") == 0.1
    assert erosion_bound_cm(tolerance) == pytest.approx(math.sqrt(2.0) * 0.2 + 0.1)
    assert tolerance_of(replace(spec, tolerance_cm=None, tolerances_cm=None)) is None


def test_the_figure_overlays_nominal_robust_and_some(tmp_path):
    from planar_tui.workspace.paving.result import WorkspaceResult
    from planar_tui.workspace.paving.tolerance import tolerance_companions

    spec = spec_for(tolerance_cm=0.1, tolerance_mode="all")
    job = _Job(spec)
    job.robot = ROBOT
    outcome = run(spec)
    companions = tolerance_companions(
        ROBOT, spec, lambda: BoxBudget(job, Progress()), compute_workspace
    )
    assert set(companions) == {"nominal", "some"}
    from planar_tui.csvio import CsvTable
    from planar_tui.figures.workspace import from_result

    result = WorkspaceResult(
        table=CsvTable(("a",), []), summary="s", outcome=outcome, companions=companions
    )
    fig = from_result(job, result)
    gids = {c.get_gid() for c in fig.axes[0].collections}
    assert {"some-kept", "nominal-kept", "all-kept", "all-inside"} <= gids
    fig.savefig(tmp_path / "t.png")


def test_the_bundled_study_reads_its_tolerances_and_loses_area_at_one_millimetre():
    """``paper-b-tolerance``: Table 3's design at ±0.1 mm and ±1 mm, robust mode; at a
    coarse ε (no refinement) the ±1 mm robust kept area is already below the exact
    nominal area, and the ±0.1 mm one's bracket is above the ±1 mm one's."""
    from planar_tui.presets import load_preset
    from planar_tui.workspace.rrr.geometry import geometric_area
    from tests.conftest import PRESETS

    jobs = load_preset(PRESETS / "paper-b-tolerance.toml").jobs
    tolerances = [tolerance_of(job.spec) for job in jobs]
    assert [(t.mode, t.of("distal_cm"), t.of("base_joints_cm")) for t in tolerances] == [
        ("all", 0.01, 0.01),
        ("all", 0.1, 0.1),
    ]
    fine, coarse = (
        run(replace(job.spec, precision_cm=0.234375, refine_precision_cm=None)) for job in jobs
    )
    exact = geometric_area(jobs[0].robot, jobs[0].spec.limits_rad, 0.0).area_cm2
    assert coarse.area_kept_cm2 < exact
    assert coarse.area_kept_cm2 < fine.area_inside_cm2

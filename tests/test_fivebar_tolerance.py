"""Tolerance-certified five-bar workspaces (``tolerance_cm``, ``tolerances_cm``,
``tolerance_mode`` on ``[[workspace5r]]``): robust boxes against robots sampled within the
tolerances (corners of the parameter box and random ones, a closed-form inverse-kinematics
test written here), the "some" region against every sampled robot's workspace, the robust
region against the nominal workspace eroded by the derived bound (shapely geometry), zero
tolerance against the nominal paving, one and two threads, and bad input."""

from __future__ import annotations

import dataclasses
import itertools
import math

import numpy as np
import pytest

from planar_tui.jobkind import PreparedJob
from planar_tui.presets import load_preset
from planar_tui.progress import Progress
from planar_tui.workspace.paving.levels import INSIDE
from tests.conftest import PRESETS, on_one_and_two_threads

T_BASE_CM, T_PROXIMAL_CM, T_DISTAL_CM = 0.4, 0.3, 0.5
TOLERANCES = (
    ("base_joints_cm", T_BASE_CM),
    ("distal_cm", T_DISTAL_CM),
    ("proximal_cm", T_PROXIMAL_CM),
)
#: The derived bound B = √2 t_A + t_1 + t_2 (planar_tui.workspace.fivebar.tolerance).
BOUND_CM = math.sqrt(2.0) * T_BASE_CM + T_PROXIMAL_CM + T_DISTAL_CM
PRECISION_CM = 0.5


def robot_of(mode):
    """The bundled illustrative five-bar in working mode ``mode`` (``any`` or ``+-``)."""
    job = load_preset(PRESETS / "fivebar-illustrative.toml").jobs[0]
    return dataclasses.replace(job, robot=dataclasses.replace(job.robot, working_mode=mode))


def run(mode, tolerance_mode=None, tolerances=TOLERANCES, precision=PRECISION_CM):
    from planar_tui.workspace.fivebar.job import run_fivebar

    job = robot_of(mode)
    changes = {"precision_cm": precision, "geometric_reference": False}
    if tolerance_mode is not None:
        changes.update(tolerances_cm=tolerances, tolerance_mode=tolerance_mode)
    job = dataclasses.replace(job, spec=dataclasses.replace(job.spec, **changes))
    return run_fivebar(PreparedJob(job, None), Progress())


# -- the independent float model: closed-form inverse kinematics, one robot per row -------
def leg_reaches(points, base, l1, l2, limits_deg, sign, slack):
    """(robots, points): the leg (base ``(robots, 2)``, lengths ``(robots,)``) closes at
    each point with θ = α + s β (s = ``sign``, or either when 0) within the limits;
    ``slack`` > 0 counts near misses as closing, < 0 near hits as missing."""
    rel = points[None, :, :] - base[:, None, :]
    r = np.hypot(rel[..., 0], rel[..., 1])
    l1, l2 = l1[:, None], l2[:, None]
    cos_beta = (r * r + l1 * l1 - l2 * l2) / (2.0 * l1 * np.maximum(r, 1e-300))
    beta = np.arccos(np.clip(cos_beta, -1.0, 1.0))
    alpha = np.arctan2(rel[..., 1], rel[..., 0])
    lo, hi = np.radians(limits_deg)
    on_arc = np.zeros(r.shape, dtype=bool)
    for s in (1.0, -1.0) if sign == 0 else (float(sign),):
        shifted = np.mod(alpha + s * beta - lo, 2.0 * np.pi)
        on_arc |= (shifted <= hi - lo + slack) | (shifted >= 2.0 * np.pi - slack)
    return (np.abs(cos_beta) <= 1.0 + slack) & on_arc


def robots(rng, count):
    """Per robot and leg ``a_x, a_y, tau, kappa`` (robots, 2, 4): every sign pattern of a
    leg's four shifts at the tolerances' corners (on both legs, and crossed between legs),
    then random vertices and random robots inside the box."""
    corners = np.array(list(itertools.product((-1.0, 1.0), repeat=4)))
    rows = [np.stack([c, c]) for c in corners] + [np.stack([c, -c]) for c in corners]
    rows += [rng.choice([-1.0, 1.0], size=(2, 4)) for _ in range(count)]
    rows += [rng.uniform(-1.0, 1.0, size=(2, 4)) for _ in range(count)]
    return np.array(rows) * np.array([T_BASE_CM, T_BASE_CM, T_PROXIMAL_CM, T_DISTAL_CM])


def reached(robot, points, shifts, slack):
    """(robots, points): both legs of each shifted robot close (in the robot's mode)."""
    ok = np.ones((len(shifts), len(points)), dtype=bool)
    for leg in range(2):
        base = np.array(robot.base_joints_cm()[leg]) + shifts[:, leg, :2]
        l1 = robot.proximal_cm[leg] + shifts[:, leg, 2]
        l2 = robot.distal_cm[leg] + shifts[:, leg, 3]
        sign = robot.elbows[leg]
        ok &= leg_reaches(points, base, l1, l2, robot.joint_limits_deg[leg], sign, slack)
    return ok


def points_in(boxes, rng, per_box=2):
    """Each box's corners pulled in by 1e-7 cm and ``per_box`` random points."""
    lo, hi = boxes[:, [0, 2]], boxes[:, [1, 3]]
    pts = [np.where([cx, cy], hi - 1e-7, lo + 1e-7) for cx, cy in itertools.product((0, 1), (0, 1))]
    pts += [lo + (hi - lo) * rng.uniform(0.0, 1.0, (len(boxes), 2)) for _ in range(per_box)]
    return np.concatenate(pts)


def grid_points(outcome, n=170):
    xlo, xhi, ylo, yhi = outcome.extent_cm
    xs, ys = np.meshgrid(np.linspace(xlo, xhi, n), np.linspace(ylo, yhi, n))
    return np.column_stack([xs.ravel(), ys.ravel()])


def covered(points, boxes):
    """Which points lie in (or on) a box (rows x_lo, x_hi, y_lo, y_hi)."""
    hit = np.zeros(len(points), dtype=bool)
    for chunk in np.array_split(np.arange(len(points)), max(1, len(points) // 2000)):
        x, y = points[chunk, :1], points[chunk, 1:]
        hit[chunk] = np.any(
            (x >= boxes[:, 0]) & (x <= boxes[:, 1]) & (y >= boxes[:, 2]) & (y <= boxes[:, 3]),
            axis=1,
        )
    return hit


MODES = ["any", "+-"]


@pytest.mark.parametrize("mode", MODES)
def test_robust_inside_boxes_are_reached_by_every_sampled_robot(mode):
    """``all``: every point of an inside box is reached by every corner and random robot.
    Checked to fail with the bound zeroed: with ``shift_bound`` and ``boundary_shift`` of
    kernels/workspace_tolerance.py and kernels/workspace5r_tolerance.py returning 0.0 (and
    the Numba cache cleared), corner robots miss points of inside boxes in both modes; with
    only ``boundary_shift`` made too small (times 0.85, or 0.5, or 0; rechecked after the
    vertex robots were tried on boxes of every size), this test and
    ``test_the_some_kept_boxes_hold_every_sampled_robots_workspace`` fail in mode ``+-``."""
    result = run(mode, "all")
    inside = result.outcome.boxes[result.outcome.status == INSIDE]
    assert len(inside) > 200
    rng = np.random.default_rng(1)
    assert reached(robot_of(mode).robot, points_in(inside, rng), robots(rng, 20), 1e-9).all()


@pytest.mark.parametrize("mode", MODES)
def test_the_some_kept_boxes_hold_every_sampled_robots_workspace(mode):
    result = run(mode, "some")
    rng = np.random.default_rng(2)
    points = grid_points(result.outcome)
    kept = result.outcome.boxes
    edge = kept[result.outcome.status != INSIDE] + np.array([-1.0, 1.0, -1.0, 1.0])
    points = np.concatenate([points, points_in(edge, rng, 1)])  # near the region's edge
    by_one = reached(robot_of(mode).robot, points, robots(rng, 6), -1e-9).any(axis=0)
    assert by_one.sum() > 5000 and not by_one.all()
    assert covered(points[by_one], kept).all()


def leg_candidates():
    """The robots the existential certificates may exhibit, per leg ``a_x, a_y, tau, kappa``
    (19, 4): the 16 corners of the leg's parameter box, the nominal leg and the nominal
    leg with either extreme distal."""
    corners = list(itertools.product((-1.0, 1.0), repeat=4))
    rows = [*corners, (0.0, 0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0), (0.0, 0.0, 0.0, -1.0)]
    return np.array(rows) * np.array([T_BASE_CM, T_BASE_CM, T_PROXIMAL_CM, T_DISTAL_CM])


def legs_reached_by_candidates(robot, points, slack):
    """(2, candidates, points): leg ``i`` of each candidate closes at each point."""
    shifts = leg_candidates()
    out = []
    for leg in range(2):
        base = np.array(robot.base_joints_cm()[leg]) + shifts[:, :2]
        l1 = robot.proximal_cm[leg] + shifts[:, 2]
        l2 = robot.distal_cm[leg] + shifts[:, 3]
        limits = robot.joint_limits_deg[leg]
        out.append(leg_reaches(points, base, l1, l2, limits, robot.elbows[leg], slack))
    return np.array(out)


@pytest.mark.parametrize("mode", MODES)
def test_the_existential_certificates_are_some_robots(mode):
    """``all``: every grid point outside the robust kept boxes is missed by one robot of
    the tolerances (one leg of a corner robot, or of the nominal one with an extreme
    distal); ``some``: every point of an inside box is reached by one robot (per leg; the
    legs' parameters are independent). Checked to fail (mode ``+-``) with
    ``vertex_mode_label`` of kernels/workspace5r_tolerance.py certifying without a robot."""
    robot = robot_of(mode).robot
    robust = run(mode, "all").outcome
    points = grid_points(robust)
    outside = points[~covered(points, robust.boxes)]
    closes = legs_reached_by_candidates(robot, outside, -1e-9)
    assert len(outside) > 5000 and (~closes).any(axis=1).any(axis=0).all()
    some = run(mode, "some").outcome
    inside = some.boxes[some.status == INSIDE]
    points = points_in(inside, np.random.default_rng(4), 1)
    assert legs_reached_by_candidates(robot, points, 1e-9).any(axis=1).all()


@pytest.mark.parametrize("tolerance_mode", ["all", "some"])
def test_the_vertex_robots_decide_the_band_above_the_leaves(tolerance_mode):
    """Mode ``+-``: the band between the nominal boundary and the boundary shifted by ``h``
    is decided by the vertex robots on boxes of every size (their soundness is
    ``test_the_existential_certificates_are_some_robots``), so the certified paving
    processes at most 1.6x the nominal paving's boxes (a count, not a time: 1.12x robust,
    1.28x "some" at ε = 0.2 cm). Checked to fail with the vertex robots tried on leaf boxes
    only (the earlier kernel: 2.2x robust, 4.1x "some")."""
    nominal = run("+-", precision=0.2).outcome.boxes_processed
    certified = run("+-", tolerance_mode, precision=0.2).outcome.boxes_processed
    assert nominal < certified <= 1.6 * nominal


def test_the_circle_family_bound_holds_for_every_sampled_circle():
    """``circle_family_far`` (the per-direction bound of a mode's universal certificates):
    where it proves a point farther than ``rho`` from every circle of centre ``a`` in the
    square ``|a_x|, |a_y| <= t_a`` and radius in ``[max(0, r - s), r + s]``, no sampled
    circle (centres on the square's edges, 256 a side, and inside it; the extreme and
    random radii) comes within ``rho``; and it proves more than the isotropic bound
    ``| |q| - r | > rho + sqrt(2) t_a + s`` does. Checked to fail with ``t_a`` or
    ``spread`` times 0.85 inside ``circle_family_far``."""
    from planar_tui.kernels.workspace5r import circle_family_far

    rng = np.random.default_rng(5)
    side = np.linspace(-1.0, 1.0, 256)
    ones = np.ones_like(side)
    square = np.vstack(
        [
            np.column_stack(pair)
            for pair in ((side, ones), (side, -ones), (ones, side), (-ones, side))
        ]
    )
    square = np.vstack([square, rng.uniform(-1.0, 1.0, (64, 2))])
    proved = isotropic = 0
    for _ in range(4000):
        t_a, spread, rho = rng.uniform(0.0, 1.0), rng.uniform(0.0, 1.0), rng.uniform(0.0, 2.0)
        radius = rng.uniform(0.0, 20.0)
        qx, qy = rng.uniform(-25.0, 25.0, 2)
        isotropic += abs(math.hypot(qx, qy) - radius) > rho + math.sqrt(2.0) * t_a + spread
        if not circle_family_far(qx, qy, t_a, radius, spread, rho):
            continue
        proved += 1
        centres = t_a * square
        to_centre = np.hypot(qx - centres[:, 0], qy - centres[:, 1])
        radii = np.concatenate(
            [
                [max(radius - spread, 0.0), radius + spread],
                rng.uniform(max(radius - spread, 0.0), radius + spread, 8),
            ]
        )
        assert np.abs(to_centre[:, None] - radii[None, :]).min() > rho
    assert proved > isotropic > 1000


def arc(centre, radius, start, stop, n=2000):
    """Points of the arc ``centre + radius e(t)``, t in [start, stop] (a signed radius)."""
    t = np.linspace(start, stop, n)
    return np.column_stack([centre[0] + radius * np.cos(t), centre[1] + radius * np.sin(t)])


def eroded_workspace(robot, bound):
    """The nominal workspace eroded by ``bound``, by shapely geometry: per leg, in any
    branch ``d_min <= l2 - B`` and ``d_max >= l2 + B`` (the leg regions of the distals
    ``l2 ∓ B``: :func:`planar_tui.workspace.paving.geometry.leg_region`, inner polygons); in a
    working mode its region (the mode band, eroded by the chords' sagitta) less the points
    within ``B`` (+ the chords' sagitta) of its four boundary arcs, drawn here."""
    from shapely import LineString, affinity, intersection_all, union_all

    from planar_tui.workspace.fivebar.robot import mode_band
    from planar_tui.workspace.paving.geometry import leg_region

    regions = []
    for leg, a in enumerate(robot.base_joints_cm()):
        l1, l2 = robot.proximal_cm[leg], robot.distal_cm[leg]
        lo, hi = robot.limits_rad[leg]
        sign = robot.elbows[leg]
        if sign == 0:
            shorter = leg_region(l1, l2 - bound, lo, hi, 4096, False)
            longer = leg_region(l1, l2 + bound, lo, hi, 4096, False)
            regions.append(affinity.translate(shorter.intersection(longer), *a))
            continue
        band, sagitta = mode_band(a, l1, l2, lo, hi, sign, 4096)
        elbows = [(a[0] + l1 * math.cos(t), a[1] + l1 * math.sin(t)) for t in (lo, hi)]
        # the distal's half turn in the mode: P = B + l2 e(θ + ψ), ψ in [-π, 0] for σ = 1
        turns = [(t - math.pi, t) if sign > 0 else (t, t + math.pi) for t in (lo, hi)]
        arcs = [arc(a, l1 + l2, lo, hi), arc(a, l1 - l2, lo, hi)]
        arcs += [arc(b, l2, *turn) for b, turn in zip(elbows, turns, strict=True)]
        near = [LineString(points).buffer(bound + 0.01) for points in arcs]  # chords: 1e-3 cm
        regions.append(band.buffer(-sagitta).difference(union_all(near)))
    return intersection_all(regions)


@pytest.mark.parametrize("mode", MODES)
def test_the_robust_workspace_contains_the_nominal_eroded_by_the_bound(mode):
    """The nominal workspace eroded by B = √2 t_A + t_1 + t_2 lies in the robust kept boxes
    (grid points), its area is at most the robust kept area and the proved area misses at
    most a band of two box diagonals along its boundary; the sampled robots reach it."""
    import shapely

    result = run(mode, "all")
    robot = robot_of(mode).robot
    eroded = eroded_workspace(robot, BOUND_CM)
    assert eroded.area > 5000.0
    outcome = result.outcome
    assert eroded.area <= outcome.area_kept_cm2
    band = eroded.length * 2.0 * math.sqrt(2.0) * PRECISION_CM
    assert outcome.area_inside_cm2 >= eroded.area - band
    points = grid_points(outcome)
    in_eroded = points[shapely.contains_xy(eroded, points[:, 0], points[:, 1])]
    assert covered(in_eroded, outcome.boxes).all()
    rng = np.random.default_rng(3)
    assert reached(robot, in_eroded, robots(rng, 5), 1e-9).all()


@pytest.mark.parametrize("mode", MODES)
def test_the_brackets_nest_robust_nominal_some(mode):
    robust, some, nominal = (run(mode, m).outcome for m in ("all", "some", None))
    assert robust.area_kept_cm2 < nominal.area_kept_cm2 < some.area_kept_cm2
    assert robust.area_inside_cm2 < nominal.area_inside_cm2 <= some.area_inside_cm2


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("tolerance_mode", ["all", "some"])
def test_zero_tolerance_is_the_nominal_paving_bit_for_bit(mode, tolerance_mode):
    zero = run(mode, tolerance_mode, tolerances=(("base_joints_cm", 0.0),)).outcome
    nominal = run(mode).outcome
    same = [np.array_equal(getattr(zero, k), getattr(nominal, k)) for k in ("boxes", "status")]
    assert all(same) and zero.area_inside_cm2 == nominal.area_inside_cm2
    assert zero.area_kept_cm2 == nominal.area_kept_cm2


def test_the_paving_is_the_same_on_one_and_two_threads():
    for tolerance_mode in ("all", "some"):
        one, two = on_one_and_two_threads(lambda m=tolerance_mode: run("+-", m).outcome)
        assert np.array_equal(one.boxes, two.boxes) and np.array_equal(one.status, two.status)


PRESET = """[robot5r]
working_mode = "+-"
[[workspace5r]]
precision_cm = 1
{extra}
output = "ws.csv"
"""


@pytest.mark.parametrize(
    ("extra", "fragment"),
    [
        ('tolerance_mode = "all"', "tolerance_mode: is set without a tolerance"),
        ("tolerance_cm = -0.1", "workspace5r[1].tolerance_cm"),
        ('tolerance_cm = 0.1\ntolerance_mode = "most"', "workspace5r[1].tolerance_mode"),
        ("tolerances_cm = { platform_points_cm = 0.1 }", "platform_points_cm: unknown quantity"),
        ("tolerance_cm = 45", "tolerance_cm: is ±45 cm on proximal_cm = 45 cm"),
        ("tolerance_cm = 0.1\nsingularities = true", "singularities: is True with a tolerance"),
        ("tolerance_cm = 0.1\ngeometric_reference = true", "geometric_reference: is true with"),
        ('tolerance_cm = 0.1\nform = "geometric"', "form: is 'geometric' with a tolerance"),
    ],
)
def test_bad_tolerance_input_is_one_line_exit_2(cli, tmp_path, extra, fragment):
    from tests.test_workspace_3rpr import refused

    refused(cli, tmp_path, "workspace5r", PRESET.format(extra=extra), fragment)


def test_the_bundled_study_reads_its_tolerances_and_loses_area_at_one_millimetre():
    """``fivebar-tolerance``: the "+-" five-bar at ±0.1 mm and ±1 mm, robust mode; at a
    coarse ε (no refinement) the ±1 mm robust kept area is already below the exact nominal
    area (polygon geometry), and below the ±0.1 mm one's."""
    from planar_tui.workspace.fivebar.job import compute_fivebar
    from planar_tui.workspace.fivebar.robot import geometric_area
    from planar_tui.workspace.paving.levels import BoxBudget
    from planar_tui.workspace.paving.tolerance import tolerance_of

    jobs = load_preset(PRESETS / "fivebar-tolerance.toml").jobs
    read = [
        (t.mode, *map(t.of, ("base_joints_cm", "proximal_cm", "distal_cm")))
        for t in map(tolerance_of, [job.spec for job in jobs])
    ]
    assert read == [("all", 0.01, 0.01, 0.01), ("all", 0.1, 0.1, 0.1)]
    fine, coarse = (
        compute_fivebar(job.robot, spec, BoxBudget(job, Progress()))
        for job in jobs
        for spec in [dataclasses.replace(job.spec, precision_cm=0.2, refine_precision_cm=None)]
    )
    exact = geometric_area(jobs[0].robot)
    assert coarse.area_kept_cm2 < exact.inner_cm2
    assert coarse.area_kept_cm2 < fine.area_kept_cm2

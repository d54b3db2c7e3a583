"""Certified interference-free regions (``leg_width_cm``) against exact segment distances.

The reference builds each 3-RRR leg's elbow as the intersection of the circles about A_i
(l1) and C_i (l2), on the side the elbow sign asks for, and measures every checked pair
(docs/interference.md) with its own closed-form segment-segment distance (the clamped
closest points of Ericson's *Real-Time Collision Detection*, 5.1.9), not the kernel's
end-to-segment form: links of different chains at least ``w`` apart, each link at least
``w / 2`` from the platform triangle (a link jointed to it: the edge opposite its joint,
and its free end from the whole triangle).
Checks: every sample of a box said interference-free holds the clearance; every grid point
with clearance to spare lies in a kept box; the area bracket holds a fine grid's estimate.
Each check fails when the gap enclosure is shrunk by 1 % (:func:`shrunk`).
"""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest

from planar_tui.batch import prepare_jobs, run_job
from planar_tui.presets import load_preset
from planar_tui.workspace.paving import interference

#: A compact 3-RRR whose legs collide over about half its workspace (full-turn joints).
COMPACT = """
[robot3rrr]
base_side_cm = 80
platform_side_cm = 40
proximal_cm = 30
distal_cm = 30
[workspace]
joint_limits_deg = [[-180, 180], [-180, 180], [-180, 180]]
precision_cm = {precision}
form = "arc-distance"
geometric_reference = false
elbow = [1, 1, 1]
{extra}output = "ws.csv"
"""
WIDTH_CM = 6.0


def run(tmp_path, text):
    path = tmp_path / "i.toml"
    path.write_text(text, encoding="utf-8")
    (job,) = prepare_jobs(load_preset(path).jobs)
    return job, run_job(job)


def dot(u, v):
    return u[..., 0] * v[..., 0] + u[..., 1] * v[..., 1]


def segment_distance(p0, p1, q0, q1):
    """The exact distance between the segments p0p1 and q0q1 (arrays (..., 2), non-zero
    lengths): the closest points' parameters clamped to [0, 1] in turn."""
    d1, d2, r = p1 - p0, q1 - q0, p0 - q0
    a, e, f = dot(d1, d1), dot(d2, d2), dot(d2, r)
    c, b = dot(d1, r), dot(d1, d2)
    denom = a * e - b * b
    with np.errstate(divide="ignore", invalid="ignore"):
        s = np.where(denom > 1e-12 * a * e, np.clip((b * f - c * e) / denom, 0.0, 1.0), 0.0)
        t = (b * s + f) / e
        s = np.where(
            t < 0.0, np.clip(-c / a, 0.0, 1.0), np.where(t > 1.0, np.clip((b - c) / a, 0.0, 1.0), s)
        )
    t = np.clip(t, 0.0, 1.0)
    gap = p0 + s[..., None] * d1 - q0 - t[..., None] * d2
    return np.hypot(gap[..., 0], gap[..., 1])


def point_distance(p, q0, q1):
    """The exact distance from the point p to the segment q0q1 (non-zero length)."""
    d = q1 - q0
    t = np.clip(dot(p - q0, d) / dot(d, d), 0.0, 1.0)
    gap = p - q0 - t[..., None] * d
    return np.hypot(gap[..., 0], gap[..., 1])


def inside_triangle(p, a, b, c):
    """Whether p lies in the triangle abc (either orientation)."""

    def side(u, v):
        return (v[..., 0] - u[..., 0]) * (p[..., 1] - u[..., 1]) - (v[..., 1] - u[..., 1]) * (
            p[..., 0] - u[..., 0]
        )

    s1, s2, s3 = side(a, b), side(b, c), side(c, a)
    return ((s1 >= 0) & (s2 >= 0) & (s3 >= 0)) | ((s1 <= 0) & (s2 <= 0) & (s3 <= 0))


def legs_of(job):
    """Per leg ``(A, q, l1, l2, sign, (lo, hi))`` and whether the robot has a platform
    triangle (the 3-RRR) or its distal links meet at one point (the five-bar)."""
    robot = job.robot
    if hasattr(robot, "elbows"):  # the five-bar
        limits = [(math.radians(lo), math.radians(hi)) for lo, hi in robot.joint_limits_deg]
        legs = zip(
            robot.base_joints_cm(),
            robot.proximal_cm,
            robot.distal_cm,
            robot.elbows,
            limits,
            strict=True,
        )
        return [(a, (0.0, 0.0), l1, l2, s, lim) for a, l1, l2, s, lim in legs], False
    l1, l2 = robot.proximal_cm, robot.distal_cm
    legs = zip(
        robot.base_joints_cm(),
        robot.platform_points_cm(),
        job.spec.elbow if job.prepared.circle is None else job.prepared.circle.elbow,
        job.spec.limits_rad,
        strict=True,
    )
    return [(a, q, l1, l2, sign, lim) for a, q, sign, lim in legs], True


def turned(q, phi):
    """The platform point ``q`` turned by ``phi`` (rad): its offset from the platform's
    reference point."""
    c, s = math.cos(phi), math.sin(phi)
    return c * q[0] - s * q[1], s * q[0] + c * q[1]


def rpr_links(job, x, y, phi=0.0):
    """A 3-RPR's validity (every leg's length within its limits) and links A_i C_i."""
    robot = job.robot
    valid = np.ones(np.shape(x), dtype=bool)
    links, c_ = [], []
    for i, ((ax, ay), (qx, qy), (lo, hi)) in enumerate(
        zip(robot.base_joints_cm, robot.platform_points_cm, job.spec.leg_limits_cm, strict=True)
    ):
        qx, qy = turned((qx, qy), phi)
        cx, cy = x + qx, y + qy
        rho = np.hypot(cx - ax, cy - ay)
        valid &= (lo <= rho) & (rho <= hi)
        a = np.stack([np.full(np.shape(x), ax), np.full(np.shape(x), ay)], axis=-1)
        c_.append(np.stack([cx, cy], axis=-1))
        links.append((i, a, c_[i], i))
    return valid, links, c_


def prr_links(job, x, y, phi=0.0):
    """A 3-PRR's validity (every slider in its mode within its stroke) and moving links
    S_i C_i: the slider S_i = b_i + s u_i on its line at distance l from C_i, ahead of
    (sign 1) or behind the foot of the perpendicular from C_i."""
    robot = job.robot
    valid = np.ones(np.shape(x), dtype=bool)
    links, c_ = [], []
    legs = zip(
        robot.slider_points_cm,
        robot.slider_angles_deg,
        robot.strokes_cm,
        robot.distal_cm,
        robot.platform_points_cm,
        job.spec.slider_modes,
        strict=True,
    )
    for i, ((bx, by), angle, (lo, hi), length, (qx, qy), sign) in enumerate(legs):
        ux, uy = math.cos(math.radians(angle)), math.sin(math.radians(angle))
        qx, qy = turned((qx, qy), phi)
        cx, cy = x + qx, y + qy
        foot = (cx - bx) * ux + (cy - by) * uy
        off = -(cx - bx) * uy + (cy - by) * ux
        valid &= off * off <= length * length
        s = foot + sign * np.sqrt(np.maximum(length * length - off * off, 0.0))
        valid &= (lo <= s) & (s <= hi)
        c_.append(np.stack([cx, cy], axis=-1))
        links.append((i, np.stack([bx + s * ux, by + s * uy], axis=-1), c_[i], i))
    return valid, links, c_


def reference(job, x, y, phi=0.0):
    """Validity (every leg closes in its mode within its limits) and the gap
    min(d - d_req) over the checked pairs at the poses (x, y, phi) (phi in rad)."""
    if hasattr(job.robot, "centres_cm"):  # the 3-RPR
        valid, links, c_ = rpr_links(job, x, y, phi)
        return valid, link_gap(links, c_, True)
    if hasattr(job.robot, "slider_points_cm"):  # the 3-PRR
        valid, links, c_ = prr_links(job, x, y, phi)
        return valid, link_gap(links, c_, True)
    legs, triangle = legs_of(job)
    valid = np.ones(np.shape(x), dtype=bool)
    a_, b_, c_ = [], [], []
    for (ax, ay), q, l1, l2, sign, (lo, hi) in legs:
        qx, qy = turned(q, phi)
        cx, cy = x + qx, y + qy
        dx, dy = cx - ax, cy - ay
        d = np.hypot(dx, dy)
        along = (l1 * l1 - l2 * l2 + d * d) / (2 * d)
        h = np.sqrt(np.maximum(l1 * l1 - along * along, 0.0))
        valid &= (d < l1 + l2) & (d > abs(l1 - l2))
        bx = ax + along * dx / d - sign * h * dy / d
        by = ay + along * dy / d + sign * h * dx / d
        valid &= np.mod(np.arctan2(by - ay, bx - ax) - lo, 2 * np.pi) <= hi - lo
        a_.append(np.stack([np.full(np.shape(x), ax), np.full(np.shape(x), ay)], axis=-1))
        b_.append(np.stack([bx, by], axis=-1))
        c_.append(np.stack([cx, cy], axis=-1))
    n = len(legs)
    joints = range(n) if triangle else [0] * n  # the five-bar's distal links share one
    links = [(i, a_[i], b_[i], None) for i in range(n)]
    links += [(i, b_[i], c_[i], j) for i, j in zip(range(n), joints, strict=True)]
    return valid, link_gap(links, c_, triangle)


def link_gap(links, c_, triangle):
    """The gap over the checked pairs of ``links`` (chain, end 0, end 1, joint or None),
    the platform triangle ``c_`` when ``triangle``."""
    gap = np.full(np.shape(c_[0])[:-1], np.inf)
    for k, (chain, p0, p1, joint) in enumerate(links):
        for other, q0, q1, shared in links[k + 1 :]:
            if other != chain and (joint is None or shared != joint):
                gap = np.minimum(gap, segment_distance(p0, p1, q0, q1) - WIDTH_CM)
        if not triangle:
            continue
        to_platform = np.where(inside_triangle(p0, *c_), 0.0, np.inf)
        for v, w in [(0, 1), (1, 2), (2, 0)]:
            if joint in (v, w):  # an edge at the link's joint: from its free end p0 only
                d = point_distance(p0, c_[v], c_[w])
            else:
                d = segment_distance(p0, p1, c_[v], c_[w])
            to_platform = np.minimum(to_platform, d)
        gap = np.minimum(gap, to_platform - 0.5 * WIDTH_CM)
    return gap


def samples(boxes, n=3):
    """An n x n grid of points in each box (its corners and centre for n = 3)."""
    t = np.linspace(0.0, 1.0, n)
    x = boxes[:, :1] + (boxes[:, 1:2] - boxes[:, :1]) * t
    y = boxes[:, 2:3] + (boxes[:, 3:4] - boxes[:, 2:3]) * t
    return np.repeat(x, n, axis=1).ravel(), np.tile(y, (1, n)).ravel()


def grid(extent, step_cm):
    """Cell centres ``xs``, ``ys`` of a grid of step ``step_cm`` over the paved extent."""
    xlo, xhi, ylo, yhi = extent
    xs = np.arange(xlo, xhi - 0.5 * step_cm, step_cm) + 0.5 * step_cm
    return xs, np.arange(ylo, yhi - 0.5 * step_cm, step_cm) + 0.5 * step_cm


def covered(boxes, xs, ys):
    mask = np.zeros((len(ys), len(xs)), dtype=bool)
    for xlo, xhi, ylo, yhi in boxes:
        i0, i1 = np.searchsorted(xs, xlo, "left"), np.searchsorted(xs, xhi, "right")
        j0, j1 = np.searchsorted(ys, ylo, "left"), np.searchsorted(ys, yhi, "right")
        mask[j0:j1, i0:i1] = True
    return mask.ravel()


def check_inside_boxes(job, outcome):
    """Every sample of a box said interference-free: in the workspace, gap >= 0."""
    x, y = samples(outcome.boxes[outcome.status == 2], 4)
    valid, gap = reference(job, x, y)
    ok = valid & (gap >= -1e-9)
    assert ok.all(), f"{np.count_nonzero(~ok)} samples of interference-free boxes interfere"


def check_free_points_kept(job, outcome, extent, step_cm):
    """Every grid point in the workspace with gap > 1e-6 cm lies in a kept box."""
    xs, ys = grid(extent, step_cm)
    x, y = (a.ravel() for a in np.meshgrid(xs, ys))
    valid, gap = reference(job, x, y)
    lost = valid & (gap > 1e-6) & ~covered(outcome.boxes, xs, ys)
    assert not lost.any(), f"{np.count_nonzero(lost)} interference-free points in no kept box"


def check_bracket(job, outcome, extent, step_cm):
    """The bracket holds the grid's estimate up to one cell per boundary crossing."""
    xs, ys = grid(extent, step_cm)
    x, y = (a.ravel() for a in np.meshgrid(xs, ys))
    valid, gap = reference(job, x, y)
    good = (valid & (gap >= 0)).reshape(len(ys), len(xs))
    estimate = good.sum() * step_cm**2
    edge = (good[1:, :] != good[:-1, :]).sum() + (good[:, 1:] != good[:, :-1]).sum()
    slack = 0.5 * edge * step_cm**2
    assert outcome.area_inside_cm2 <= estimate + slack
    assert estimate - slack <= outcome.area_kept_cm2
    return estimate


def shrunk(monkeypatch, fraction):
    """Shrink every gap enclosure the paving sees by ``fraction`` of the leg width at each
    end (the distances' bounds moved 1 % of the clearance inwards: a mutation the checks
    must catch)."""
    original = interference.as_bound

    def as_bound(evaluate):
        def narrowed(boxes):
            verdict, gap = evaluate(boxes)
            shift = fraction * WIDTH_CM
            return verdict, np.stack([gap[:, 0] + shift, gap[:, 1] - shift], axis=1)

        return original(narrowed)

    monkeypatch.setattr(interference, "as_bound", as_bound)


EXTRA = f"leg_width_cm = {WIDTH_CM}\n"
FIVEBAR = """
[robot5r]
base_separation_cm = 40
proximal_cm = [45, 45]
distal_cm = [55, 55]
joint_limits_deg = [[-180, 180], [-180, 180]]
working_mode = "{mode}"
[[workspace5r]]
precision_cm = {precision}
geometric_reference = false
{extra}output = "fb.csv"
"""


@pytest.fixture(scope="module")
def compact(tmp_path_factory):
    return run(tmp_path_factory.mktemp("t3"), COMPACT.format(precision=0.5, extra=EXTRA))


def test_the_reference_distance_is_exact_on_known_pairs():
    p = np.array
    assert segment_distance(p([0.0, 0]), p([2.0, 0]), p([1.0, 1]), p([1.0, 3])) == 1.0
    assert segment_distance(p([0.0, 0]), p([2.0, 2]), p([0.0, 2]), p([2.0, 0])) == 0.0
    assert segment_distance(p([0.0, 0]), p([1.0, 0]), p([4.0, 4]), p([5.0, 4])) == 5.0
    assert segment_distance(p([0.0, 0]), p([4.0, 0]), p([1.0, 2]), p([3.0, 2])) == 2.0


@pytest.mark.slow
def test_boxes_said_interference_free_hold_the_clearance(compact):
    job, result = compact
    check_inside_boxes(job, result.interference)


@pytest.mark.slow
def test_every_interference_free_point_lies_in_a_kept_box(compact):
    job, result = compact
    check_free_points_kept(job, result.interference, result.outcome.extent_cm, 0.1)


@pytest.mark.slow
def test_the_bracket_holds_the_grid_estimate(compact):
    job, result = compact
    outcome = result.interference
    estimate = check_bracket(job, outcome, result.outcome.extent_cm, 0.1)
    assert outcome.area_inside_cm2 > 0.85 * estimate  # and it is not vacuous
    assert outcome.area_kept_cm2 < 1.15 * estimate
    workspace = result.outcome
    assert outcome.area_kept_cm2 < 0.7 * workspace.area_inside_cm2  # the legs do collide


#: A square across the boundary of the compact robot's interference (gap 0 near (41, 11)).
PATCH = (38.0, 44.0, 8.0, 14.0)


def pave_patch(job, precision_cm):
    """The interference paving of :data:`PATCH` alone (fine boxes, few of them)."""
    from planar_tui.progress import Progress
    from planar_tui.workspace.paving.levels import BoxBudget

    evaluate = job.spec.mechanism.interference(job, job.prepared)
    budget = BoxBudget(job, Progress())
    return interference.compute_interference(
        evaluate, PATCH, precision_cm, WIDTH_CM, "1 1 1", budget
    )


@pytest.fixture(scope="module")
def coarse(tmp_path_factory):
    return run(tmp_path_factory.mktemp("c"), COMPACT.format(precision=4.0, extra=EXTRA))


@pytest.fixture(scope="module")
def patch(coarse):
    job, _ = coarse
    return job, pave_patch(job, 0.04)


def test_fine_boxes_across_the_boundary_against_the_reference(patch):
    job, outcome = patch
    assert 0 < outcome.area_inside_cm2 < outcome.area_kept_cm2 < 36.0
    check_inside_boxes(job, outcome)
    check_free_points_kept(job, outcome, PATCH, 0.01)
    check_bracket(job, outcome, PATCH, 0.01)


def test_a_shrunk_enclosure_fails_the_checks(coarse, monkeypatch):
    shrunk(monkeypatch, 0.01)
    job, _ = coarse
    outcome = pave_patch(job, 0.04)
    with pytest.raises(AssertionError, match="interfere"):
        check_inside_boxes(job, outcome)
    with pytest.raises(AssertionError, match="in no kept box"):
        check_free_points_kept(job, outcome, PATCH, 0.01)


@pytest.mark.parametrize("mode", ["+-", pytest.param("-+", marks=pytest.mark.slow)])
def test_the_five_bar_region_against_the_reference(tmp_path, mode):
    job, result = run(tmp_path, FIVEBAR.format(mode=mode, precision=1.0, extra=EXTRA))
    outcome, extent = result.interference, result.outcome.extent_cm
    check_inside_boxes(job, outcome)
    check_free_points_kept(job, outcome, extent, 0.25)
    estimate = check_bracket(job, outcome, extent, 0.25)
    assert outcome.area_inside_cm2 > 0.5 * estimate > 0
    assert outcome.area_kept_cm2 < 0.9 * result.outcome.area_inside_cm2  # legs do collide
    header, (row,) = result.table.header, result.table.rows
    assert dict(zip(header, row, strict=True))["leg_width_cm"] == WIDTH_CM


def test_the_cli_writes_the_columns_labels_the_boxes_and_draws_the_map(cli, tmp_path):
    path = tmp_path / "i.toml"
    text = COMPACT.format(precision=2.0, extra=EXTRA + 'boxes_output = "b.csv"\n')
    path.write_text(text, encoding="utf-8")
    result = cli("workspace", path, "--out-dir", tmp_path)
    assert result.exit_code == 0, result.output
    assert "interference-free (links 6 cm wide): area in [" in result.output
    with open(tmp_path / "ws.csv", encoding="utf-8") as f:
        (row,) = list(csv.DictReader(f))
    assert float(row["leg_width_cm"]) == WIDTH_CM
    lo, hi = (float(row[f"interference_free_area_{k}_cm2"]) for k in ("inside", "kept"))
    assert 0 < lo <= hi
    with open(tmp_path / "b.csv", encoding="utf-8") as f:
        labels = {r["status"] for r in csv.DictReader(f)}
    assert {"inside", "boundary", "interference-free", "interference-boundary"} <= labels


def test_a_job_without_the_key_writes_the_columns_it_wrote_before(cli, tmp_path):
    from planar_tui.workspace.paving.circle import HEADER as CIRCLE
    from planar_tui.workspace.paving.levels import SUMMARY_HEADER
    from planar_tui.workspace.paving.orientation import ORIENTATION_HEADER

    path = tmp_path / "i.toml"
    text = COMPACT.format(precision=4.0, extra='boxes_output = "b.csv"\n')
    path.write_text(text.replace("elbow = [1, 1, 1]\n", ""), encoding="utf-8")
    result = cli("workspace", path, "--out-dir", tmp_path)
    assert result.exit_code == 0, result.output
    with open(tmp_path / "ws.csv", encoding="utf-8") as f:
        header = next(csv.reader(f))
    assert header == [*SUMMARY_HEADER[:-1], *ORIENTATION_HEADER, *CIRCLE, SUMMARY_HEADER[-1]]
    with open(tmp_path / "b.csv", encoding="utf-8") as f:
        assert {r["status"] for r in csv.DictReader(f)} == {"inside", "boundary"}
    assert "interference" not in result.output


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("leg_width_cm = 0\n", "workspace.leg_width_cm:"),
        ("leg_width_cm = -2\n", "workspace.leg_width_cm:"),
        ('leg_width_cm = "wide"\n', "workspace.leg_width_cm:"),
        ('leg_width_cm = 2\nform = "geometric"\n', 'leg_width_cm: is set with form = "geometric"'),
        (
            'leg_width_cm = 2\norientation_deg = [0, 5]\norientation_mode = "total"\n',
            "elbow: is not set with leg_width_cm and orientation_deg = [lo, hi]",
        ),
    ],
)
def test_bad_width_exits_2_with_one_line(cli, tmp_path, text, message):
    path = tmp_path / "i.toml"
    path.write_text(
        "[robot3rrr]\n[workspace]\njoint_limits_deg = [[20, 70], [110, 160], [245, 295]]\n"
        f'precision_cm = 1.0\noutput = "ws.csv"\n{text}',
        encoding="utf-8",
    )
    result = cli("workspace", path, "--out-dir", tmp_path)
    assert result.exit_code == 2, result.output
    assert result.output.startswith("error: ") and result.output.count("\n") == 1
    assert message in result.output


RPR = """
[robot3rpr]
[[workspace3rpr]]
leg_limits_cm = [[5, 100], [5, 100], [5, 100]]
precision_cm = {precision}
{extra}output = "a.csv"
"""


def test_the_3rpr_region_against_the_reference(tmp_path):
    job, result = run(tmp_path, RPR.format(precision=2.0, extra=EXTRA))
    outcome, extent = result.interference, result.outcome.extent_cm
    check_inside_boxes(job, outcome)
    check_free_points_kept(job, outcome, extent, 0.25)
    estimate = check_bracket(job, outcome, extent, 0.25)
    assert outcome.area_inside_cm2 > 0.9 * estimate > 0
    _, gap = reference(job, *samples(result.outcome.boxes, 2))
    assert (gap < 0).mean() > 0.02  # the legs do collide
    assert list(result.table.header)[-4:] == [*interference.HEADER, "seconds"]


PRR = """
[robot3prr]
[[workspace3prr]]
precision_cm = {precision}
slider_modes = [1, 1, 1]
{extra}output = "a.csv"
"""


def test_the_3prr_region_against_the_reference(tmp_path):
    job, result = run(tmp_path, PRR.format(precision=2.0, extra=EXTRA))
    outcome, extent = result.interference, result.outcome.extent_cm
    check_inside_boxes(job, outcome)
    check_free_points_kept(job, outcome, extent, 0.25)
    estimate = check_bracket(job, outcome, extent, 0.25)
    assert outcome.area_inside_cm2 > 0.8 * estimate > 0
    assert outcome.area_kept_cm2 < 0.9 * result.outcome.area_inside_cm2  # legs do collide
    assert list(result.table.header)[-4:] == [*interference.HEADER, "seconds"]

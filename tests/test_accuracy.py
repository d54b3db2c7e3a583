"""Certified worst-case accuracy (``accuracy``) of the 3-RRR, five-bar, 3-RPR and 3-PRR against
Monte-Carlo robots.

Each robot (errors within the bounds: uniform, random vertices and the linearised worst
vertices) is solved by the independent Newton method of :mod:`accuracy_reference` from the
nominal pose, its actuators at the nominal pose's inverse kinematics (the elbow built here
as the intersection of two circles, not the kernels' θ = α ± β). Checks: every sample's
pose error lies inside the enclosure of its box; at a regular point with small errors the
enclosure is at most 1.5 times the sampled extremes; the enclosure shrunk by 1 % fails
(some sample outside it). The 100 000-robot checks take a few seconds each (numpy), so
they run in the fast loop.
"""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest

from planar_tui.batch import prepare_jobs
from planar_tui.presets import load_preset
from planar_tui.workspace.paving.accuracy import AccuracySpec
from tests.accuracy_reference import Model, box_points, pose_errors

TABLE3 = """
[robot3rrr]
base_side_cm = 120
platform_side_cm = 40
proximal_cm = 30
distal_cm = 30
[workspace]
joint_limits_deg = [[20, 70], [110, 160], [245, 295]]
precision_cm = {precision}
form = "arc-distance"
geometric_reference = false
elbow = [1, -1, 1]
accuracy = {{ actuator_deg = {actuator}, tolerance_cm = {tolerance} }}
{extra}output = "ws.csv"
"""
CENTROID = (40.0, 7.15292951566201)


def job_from_text(path, text):
    """The one job of the preset ``text``, written to ``path``, prepared."""
    path.write_text(text, encoding="utf-8")
    (job,) = prepare_jobs(load_preset(path).jobs)
    return job


def prepared(tmp_path, actuator=0.1, tolerance=0.01, precision=4.0, extra=""):
    text = TABLE3.format(precision=precision, actuator=actuator, tolerance=tolerance, extra=extra)
    return job_from_text(tmp_path / "a.toml", text)


def rr_model(job, pose):
    """The 3-RRR's :class:`Model` at ``pose`` (x, y, phi): per leg ``theta, A, c, l1, l2``
    with the nominal theta of the job's elbow signs."""
    robot, spec = job.robot, job.spec
    circle = job.prepared.circle
    acc = AccuracySpec.of(spec.accuracy, "deg")
    signs = spec.elbow if circle is None else circle.elbow  # a range's given elbow
    l1, l2 = robot.proximal_cm, robot.distal_cm
    nominal, widths = [], []
    x, y, phi = pose
    for a, c, sign in zip(robot.base_joints_cm(), robot.platform_points_cm(), signs, strict=True):
        cx = x + math.cos(phi) * c[0] - math.sin(phi) * c[1]
        cy = y + math.sin(phi) * c[0] + math.cos(phi) * c[1]
        dx, dy = cx - a[0], cy - a[1]
        d = math.hypot(dx, dy)
        along = (l1 * l1 - l2 * l2 + d * d) / (2 * d)
        h = math.sqrt(l1 * l1 - along * along)
        bx = a[0] + along * dx / d - sign * h * dy / d
        by = a[1] + along * dy / d + sign * h * dx / d
        nominal += [math.atan2(by - a[1], bx - a[0]), *a, *c, l1, l2]
        t = acc.tolerance_cm
        widths += [math.radians(acc.actuator), t, t, t, t, t, t]
    return Model(rr_residual, np.array(nominal, dtype=float), np.array(widths))


def rr_residual(pose, params):
    x, y, phi = pose[:, 0], pose[:, 1], pose[:, 2]
    out = np.empty_like(pose)
    for i in range(3):
        theta, ax, ay, qx, qy, l1, l2 = params[:, 7 * i : 7 * i + 7].T
        cx = x + np.cos(phi) * qx - np.sin(phi) * qy
        cy = y + np.sin(phi) * qx + np.cos(phi) * qy
        ux = cx - ax - l1 * np.cos(theta)
        uy = cy - ay - l1 * np.sin(theta)
        out[:, i] = ux * ux + uy * uy - l2 * l2
    return out


def enclosure(job, box):
    """The evaluator's bounds over ``box`` (|Δx| cm, |Δy| cm, |Δφ| rad)."""
    verdict, bound = job.spec.mechanism.accuracy(job, job.prepared)(np.array([box]))
    assert verdict[0] == 2
    return bound[0]


def sampled(job, box, count, extra_points, seed=1):
    rng = np.random.default_rng(seed)
    points = box_points(box, extra_points, rng, orientation=job.spec.orientation_rad)
    return pose_errors(lambda p: rr_model(job, p), points, count, rng).max(axis=0)


def shrink(bound, factor=0.99):
    """The enclosure narrowed by 1 % (a mutation the checks must catch)."""
    return bound * factor


SMALL_BOX = (CENTROID[0] - 0.1, CENTROID[0] + 0.1, CENTROID[1] - 0.1, CENTROID[1] + 0.1)
POINT = (CENTROID[0], CENTROID[0], CENTROID[1], CENTROID[1])


def test_every_robot_of_a_box_lies_inside_its_enclosure(tmp_path):
    job = prepared(tmp_path)
    bound = enclosure(job, SMALL_BOX)
    assert np.all(np.isfinite(bound))
    worst = sampled(job, SMALL_BOX, 400, 3)
    assert np.all(worst <= bound), (worst, bound)


def test_the_enclosure_is_sharp_at_a_regular_point_and_fails_shrunk(tmp_path):
    job = prepared(tmp_path, actuator=0.005, tolerance=0.0005)
    bound = enclosure(job, POINT)
    worst = sampled(job, POINT, 200, 0)
    assert np.all(worst <= bound)
    assert np.all(bound <= 1.5 * worst), (bound, worst)
    assert np.any(worst > shrink(bound))


def test_a_box_near_a_singularity_is_not_certified(tmp_path):
    """At the edge of a leg's reach (a type I singularity) no finite enclosure holds."""
    job = prepared(tmp_path)
    robot = job.robot
    a, c = robot.base_joints_cm()[0], robot.platform_points_cm()[0]
    reach = robot.proximal_cm + robot.distal_cm - 1e-3  # leg 1 nearly stretched
    angle = math.radians(45.0)
    x = a[0] + reach * math.cos(angle) - c[0]
    y = a[1] + reach * math.sin(angle) - c[1]
    _, bound = job.spec.mechanism.accuracy(job, job.prepared)(np.array([[x, x, y, y]]))
    assert not np.all(np.isfinite(bound[0]))


def test_the_job_writes_columns_and_labels_boxes_inside_their_enclosures(tmp_path, cli):
    path = tmp_path / "a.toml"
    extra = 'search_box_cm = [[0, 120], [0, 120]]\nboxes_output = "b.csv"\n'
    text = TABLE3.format(precision=1.875, actuator=0.05, tolerance=0.005, extra=extra)
    path.write_text(text, encoding="utf-8")
    result = cli("workspace", path, "--out-dir", tmp_path)
    assert result.exit_code == 0, result.output
    assert "accuracy: |Δx| ≤" in result.output
    assert result.output.count("accuracy: |Δx| ≤") == 2  # the summary and the map's title
    assert "error map, x in [" in result.output and "? not certified" in result.output
    with open(tmp_path / "ws.csv", encoding="utf-8") as f:
        (row,) = list(csv.DictReader(f))
    assert float(row["accuracy_actuator_deg"]) == 0.05 and row["accuracy_actuator_cm"] == ""
    assert float(row["accuracy_certified_area_cm2"]) > 0
    assert float(row["accuracy_uncertified_area_cm2"]) > 0
    with open(tmp_path / "b.csv", encoding="utf-8") as f:
        rows = [r for r in csv.DictReader(f) if r["status"] == "accuracy-certified"]
    assert rows and {"dx_max_cm", "dy_max_cm", "dphi_max_deg"} <= set(rows[0])
    dx_max = max(float(r["dx_max_cm"]) for r in rows)
    assert dx_max == pytest.approx(float(row["accuracy_dx_max_cm"]))
    job = prepared(tmp_path, actuator=0.05, tolerance=0.005)
    worst = max(rows, key=lambda r: float(r["dphi_max_deg"]))
    box = tuple(float(worst[k]) for k in ("x_lo_cm", "x_hi_cm", "y_lo_cm", "y_hi_cm"))
    bound = [float(worst[k]) for k in ("dx_max_cm", "dy_max_cm", "dphi_max_deg")]
    errors = sampled(job, box, 300, 2)
    assert np.all(errors <= [bound[0], bound[1], math.radians(bound[2])])


def test_the_error_map_bands_each_cell_by_its_worst_box():
    from planar_tui.workspace.paving.accuracy import AccuracyOutcome, render_error_map

    boxes = np.array([[0.0, 1.0, 0.0, 1.0], [1.0, 2.0, 0.0, 1.0], [2.0, 3.0, 0.0, 1.0]])
    bound = np.array([[0.1, 0.05, 0.01], [0.4, 0.2, 0.01], [np.inf, np.inf, np.inf]])
    spec = AccuracySpec(0.1, "deg", 0.01)
    outcome = AccuracyOutcome(boxes, np.array([2, 2, 1]), bound, spec, "", 0.0)
    lines = render_error_map(outcome, width=32)
    row = max((line[1:].strip() for line in lines[1:-1]), key=len)
    assert set(row) == {"1", "4", "?"}  # 0.1 in the first quarter of 0.4, 0.4 the last
    assert row[0] == "1" and row[-1] == "?" and row.index("4") > row.rindex("1")
    assert lines[-1].startswith("1 ≤ 0.1 cm")
    assert outcome.worst == (0.4, 0.2, pytest.approx(math.degrees(0.01)))


@pytest.mark.parametrize(
    ("text", "message"),
    [
        (
            "accuracy = { actuator_cm = 0.1 }\n",
            "workspace.accuracy.actuator_cm: is set: this robot's actuators are revolute",
        ),
        ("accuracy = { actuator_deg = -1 }\n", "workspace.accuracy.actuator_deg: is -1"),
        ("accuracy = {}\n", "workspace.accuracy: is not a non-empty table"),
        ("accuracy = 0.1\n", "workspace.accuracy: is not a non-empty table"),
        ("accuracy = { backlash_deg = 1 }\n", "workspace.accuracy.backlash_deg: unknown key"),
        (
            'accuracy = { tolerance_cm = 0.1 }\nform = "geometric"\n',
            'accuracy: is set with form = "geometric"',
        ),
    ],
)
def test_bad_accuracy_exits_2_with_one_line(cli, tmp_path, text, message):
    path = tmp_path / "a.toml"
    path.write_text(
        "[robot3rrr]\n[workspace]\njoint_limits_deg = [[20, 70], [110, 160], [245, 295]]\n"
        f'precision_cm = 1.0\nelbow = [1, -1, 1]\noutput = "ws.csv"\n{text}',
        encoding="utf-8",
    )
    result = cli("workspace", path, "--out-dir", tmp_path)
    assert result.exit_code == 2, result.output
    assert result.output.startswith("error: ") and result.output.count("\n") == 1
    assert message in result.output
    assert not (tmp_path / "ws.csv").exists()


def test_100000_robots_lie_inside_the_enclosure(tmp_path):
    job = prepared(tmp_path)
    bound = enclosure(job, SMALL_BOX)
    assert np.all(np.isfinite(bound))
    worst = sampled(job, SMALL_BOX, 5000, 15, seed=7)  # 20 poses x 5000 robots
    assert np.all(worst <= bound), (worst, bound)
    assert np.all(bound <= 2.0 * worst), (worst, bound)  # over a 2 mm box: not vacuous


FIVEBAR = """
[robot5r]
base_separation_cm = 40
proximal_cm = [45, 45]
distal_cm = [55, 55]
joint_limits_deg = [[-60, 180], [0, 240]]
working_mode = "+-"
[[workspace5r]]
precision_cm = {precision}
geometric_reference = false
accuracy = {{ actuator_deg = {actuator}, tolerance_cm = {tolerance} }}
{extra}output = "fb.csv"
"""
FIVEBAR_POINT = (0.0, 60.0)


def fivebar_job(tmp_path, actuator=0.1, tolerance=0.01, precision=8.0, extra=""):
    text = FIVEBAR.format(precision=precision, actuator=actuator, tolerance=tolerance, extra=extra)
    return job_from_text(tmp_path / "f.toml", text)


def fivebar_model(job, pose):
    """The five-bar's :class:`Model` at ``pose`` (x, y): per leg ``theta, A, l1, l2``, the
    nominal theta on the side of the robot's working mode (its ``elbows``)."""
    robot = job.robot
    acc = AccuracySpec.of(job.spec.accuracy, "deg")
    nominal, widths = [], []
    x, y = pose
    for a, l1, l2, sign in zip(
        robot.base_joints_cm(), robot.proximal_cm, robot.distal_cm, robot.elbows, strict=True
    ):
        dx, dy = x - a[0], y - a[1]
        d = math.hypot(dx, dy)
        along = (l1 * l1 - l2 * l2 + d * d) / (2 * d)
        h = math.sqrt(l1 * l1 - along * along)
        bx = a[0] + along * dx / d - sign * h * dy / d
        by = a[1] + along * dy / d + sign * h * dx / d
        nominal += [math.atan2(by - a[1], bx - a[0]), *a, l1, l2]
        t = acc.tolerance_cm
        widths += [math.radians(acc.actuator), t, t, t, t]
    return Model(fivebar_residual, np.array(nominal, dtype=float), np.array(widths))


def fivebar_residual(pose, params):
    out = np.empty_like(pose)
    for i in range(2):
        theta, ax, ay, l1, l2 = params[:, 5 * i : 5 * i + 5].T
        ux = pose[:, 0] - ax - l1 * np.cos(theta)
        uy = pose[:, 1] - ay - l1 * np.sin(theta)
        out[:, i] = ux * ux + uy * uy - l2 * l2
    return out


def fivebar_sampled(job, box, count, extra_points, seed=3):
    rng = np.random.default_rng(seed)
    points = box_points(box, extra_points, rng)
    return pose_errors(lambda p: fivebar_model(job, p), points, count, rng).max(axis=0)


def test_the_five_bar_box_point_and_shrunk_enclosure(tmp_path):
    x, y = FIVEBAR_POINT
    job = fivebar_job(tmp_path)
    box = (x - 0.2, x + 0.2, y - 0.2, y + 0.2)
    bound = enclosure(job, box)
    assert bound.shape == (2,) and np.all(np.isfinite(bound))
    assert np.all(fivebar_sampled(job, box, 400, 3) <= bound)
    job = fivebar_job(tmp_path, actuator=0.005, tolerance=0.0005)
    bound = enclosure(job, (x, x, y, y))
    worst = fivebar_sampled(job, (x, x, y, y), 200, 0)
    assert np.all(worst <= bound)
    assert np.all(bound <= 1.5 * worst), (bound, worst)
    assert np.any(worst > shrink(bound))


def test_the_five_bar_needs_a_working_mode(cli, tmp_path):
    path = tmp_path / "f.toml"
    text = FIVEBAR.format(precision=4.0, actuator=0.05, tolerance=0.005, extra="")
    path.write_text(text.replace('working_mode = "+-"', 'working_mode = "any"'), encoding="utf-8")
    result = cli("workspace5r", path, "--out-dir", tmp_path)
    assert result.exit_code == 2, result.output
    assert "workspace5r[1].accuracy: needs a working mode" in result.output
    assert result.output.count("\n") == 1 and not (tmp_path / "fb.csv").exists()


def test_the_five_bar_job_writes_its_columns(cli, tmp_path):
    path = tmp_path / "f.toml"
    text = FIVEBAR.format(precision=4.0, actuator=0.05, tolerance=0.005, extra="")
    path.write_text(text, encoding="utf-8")
    result = cli("workspace5r", path, "--out-dir", tmp_path, "--no-map")
    assert result.exit_code == 0, result.output
    with open(tmp_path / "fb.csv", encoding="utf-8") as f:
        (row,) = list(csv.DictReader(f))
    assert float(row["accuracy_dx_max_cm"]) > 0 and row["accuracy_dphi_max_deg"] == ""
    assert float(row["accuracy_certified_area_cm2"]) > 0


def test_100000_five_bar_robots_lie_inside_the_enclosure(tmp_path):
    x, y = FIVEBAR_POINT
    job = fivebar_job(tmp_path)
    box = (x - 0.2, x + 0.2, y - 0.2, y + 0.2)
    bound = enclosure(job, box)
    assert np.all(np.isfinite(bound))
    worst = fivebar_sampled(job, box, 5000, 15, seed=11)  # 20 poses x 5000 robots
    assert np.all(worst <= bound), (worst, bound)


PRISMATIC = {
    "rpr": "[robot3rpr]\n[[workspace3rpr]]\nleg_limits_cm = [[5, 100], [5, 100], [5, 100]]\n",
    "prr": "[robot3prr]\n[[workspace3prr]]\n",
}
#: A regular point of each one's workspace at phi = 0 (the default 3-RPR is poorly
#: conditioned, κ ≈ 14 there: smaller errors).
PRISMATIC_POINT = {"rpr": (10.0, 40.0), "prr": (40.0, 20.0)}
PRISMATIC_ERROR_CM = {"rpr": 0.002, "prr": 0.01}


def prismatic_job(tmp_path, kind, actuator=0.01, tolerance=0.01, precision=8.0, extra=""):
    text = PRISMATIC[kind] + (
        f"orientation_deg = 0\nprecision_cm = {precision}\ngeometric_reference = false\n"
        f"accuracy = {{ actuator_cm = {actuator}, tolerance_cm = {tolerance} }}\n"
        f'{extra}output = "{kind}.csv"\n'
    )
    return job_from_text(tmp_path / f"{kind}.toml", text)


def platform_points(x, y, phi, points):
    return [
        (x + math.cos(phi) * qx - math.sin(phi) * qy, y + math.sin(phi) * qx + math.cos(phi) * qy)
        for qx, qy in points
    ]


def rpr_model(job, pose):
    """The 3-RPR's :class:`Model`: per leg ``rho, A, c`` (rho its length at ``pose``)."""
    robot, acc = job.robot, AccuracySpec.of(job.spec.accuracy, "cm")
    nominal, widths = [], []
    corners = platform_points(*pose, robot.platform_points_cm)
    for a, c, (cx, cy) in zip(robot.base_joints_cm, robot.platform_points_cm, corners, strict=True):
        nominal += [math.hypot(cx - a[0], cy - a[1]), *a, *c]
        t = acc.tolerance_cm
        widths += [acc.actuator, t, t, t, t]
    return Model(rpr_residual, np.array(nominal, dtype=float), np.array(widths))


def rpr_residual(pose, params):
    x, y, phi = pose.T
    out = np.empty_like(pose)
    for i in range(3):
        rho, ax, ay, qx, qy = params[:, 5 * i : 5 * i + 5].T
        cx = x + np.cos(phi) * qx - np.sin(phi) * qy
        cy = y + np.sin(phi) * qx + np.cos(phi) * qy
        out[:, i] = (cx - ax) ** 2 + (cy - ay) ** 2 - rho * rho
    return out


def prr_model(job, pose, modes):
    """The 3-PRR's :class:`Model`: per leg ``s, P, c, l`` with the slider ``s`` where the
    circle of radius ``l`` about ``C_i`` meets the line ``P + s u`` on the mode's side."""
    robot, acc = job.robot, AccuracySpec.of(job.spec.accuracy, "cm")
    nominal, widths = [], []
    corners = platform_points(*pose, robot.platform_points_cm)
    legs = zip(
        robot.slider_points_cm,
        robot.slider_angles_deg,
        robot.platform_points_cm,
        robot.distal_cm,
        corners,
        modes,
        strict=True,
    )
    directions = []
    for p, angle, c, length, (cx, cy), sign in legs:
        u = (math.cos(math.radians(angle)), math.sin(math.radians(angle)))
        wx, wy = cx - p[0], cy - p[1]
        off_line = wx * u[1] - wy * u[0]
        s = wx * u[0] + wy * u[1] + sign * math.sqrt(length * length - off_line * off_line)
        nominal += [s, *p, *c, length]
        directions.append(u)
        t = acc.tolerance_cm
        widths += [acc.actuator, t, t, t, t, t]
    rails = np.array(directions)

    def residual(pose, params):
        x, y, phi = pose.T
        out = np.empty_like(pose)
        for i in range(3):
            s, px, py, qx, qy, length = params[:, 6 * i : 6 * i + 6].T
            cx = x + np.cos(phi) * qx - np.sin(phi) * qy
            cy = y + np.sin(phi) * qx + np.cos(phi) * qy
            dx = cx - px - s * rails[i, 0]
            dy = cy - py - s * rails[i, 1]
            out[:, i] = dx * dx + dy * dy - length * length
        return out

    return Model(residual, np.array(nominal, dtype=float), np.array(widths))


def prismatic_check(kind, job, box, count, extra_points, seed=5):
    """The evaluator's bounds over ``box`` and the sampled extremes there."""
    from planar_tui.workspace.prr.dexterity import working_modes

    verdict, bound = job.spec.mechanism.accuracy(job.job, job.prepared)(np.array([box]))
    assert verdict[0] == 2
    if kind == "rpr":
        model_at = lambda pose: rpr_model(job, pose)  # noqa: E731
    else:
        modes = working_modes(job.job, job.prepared)
        model_at = lambda pose: prr_model(job, pose, modes)  # noqa: E731
    rng = np.random.default_rng(seed)
    points = box_points(box, extra_points, rng, orientation=0.0)
    return bound[0], pose_errors(model_at, points, count, rng).max(axis=0)


@pytest.mark.parametrize("kind", ["rpr", "prr"])
def test_the_prismatic_robots_box_point_and_shrunk_enclosure(tmp_path, kind):
    x, y = PRISMATIC_POINT[kind]
    box = (x - 0.1, x + 0.1, y - 0.1, y + 0.1)
    error = PRISMATIC_ERROR_CM[kind]
    job = prismatic_job(tmp_path, kind, actuator=error, tolerance=error)
    bound, worst = prismatic_check(kind, job, box, 400, 3)
    assert np.all(np.isfinite(bound)) and np.all(worst <= bound), (worst, bound)
    job = prismatic_job(tmp_path, kind, actuator=0.0005, tolerance=0.0005)
    bound, worst = prismatic_check(kind, job, (x, x, y, y), 200, 0)
    assert np.all(worst <= bound)
    assert np.all(bound <= 1.5 * worst), (bound, worst)
    assert np.any(worst > shrink(bound))


@pytest.mark.parametrize("kind", ["rpr", "prr"])
def test_the_prismatic_jobs_write_their_columns_and_refuse_degrees(cli, tmp_path, kind):
    error = PRISMATIC_ERROR_CM[kind]
    job = prismatic_job(tmp_path, kind, actuator=error, tolerance=error, precision=4.0)
    result = cli(f"workspace3{kind}", tmp_path / f"{kind}.toml", "--out-dir", tmp_path, "--no-map")
    assert result.exit_code == 0, result.output
    with open(tmp_path / f"{kind}.csv", encoding="utf-8") as f:
        (row,) = list(csv.DictReader(f))
    assert float(row["accuracy_actuator_cm"]) == error and row["accuracy_actuator_deg"] == ""
    assert float(row["accuracy_certified_area_cm2"]) > 0
    assert float(row["accuracy_dphi_max_deg"]) > 0
    assert job.spec.accuracy is not None
    path = tmp_path / f"{kind}.toml"
    text = path.read_text(encoding="utf-8").replace("actuator_cm", "actuator_deg")
    path.write_text(text, encoding="utf-8")
    result = cli(f"workspace3{kind}", path, "--out-dir", tmp_path / "bad")
    assert result.exit_code == 2, result.output
    assert "accuracy.actuator_deg: is set: this robot's actuators are prismatic" in result.output
    assert result.output.count("\n") == 1


@pytest.mark.parametrize("kind", ["rpr", "prr"])
def test_100000_prismatic_robots_lie_inside_the_enclosure(tmp_path, kind):
    x, y = PRISMATIC_POINT[kind]
    box = (x - 0.1, x + 0.1, y - 0.1, y + 0.1)
    error = PRISMATIC_ERROR_CM[kind]
    job = prismatic_job(tmp_path, kind, actuator=error, tolerance=error)
    bound, worst = prismatic_check(kind, job, box, 5000, 15, seed=13)  # 20 x 5000 robots
    assert np.all(np.isfinite(bound)) and np.all(worst <= bound), (worst, bound)

"""Type II singularities and the singularity-free circle against dense float references.

The references build each leg's elbow as the intersection of the circles about A_i (l1) and
C_i (l2), on the side the elbow sign asks for, and take det A with numpy: a different
construction from the interval kernel's θ = α ± β."""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest

from planar_tui.batch import prepare_jobs, run_job
from planar_tui.presets import load_preset
from planar_tui.workspace.rrr.robot import Robot3RRR

TABLE3 = """
[robot3rrr]
[workspace]
joint_limits_deg = [[20, 70], [110, 160], [245, 295]]
orientation_deg = {phi}
precision_cm = {precision}
form = "arc-distance"
geometric_reference = false
singularities = true
{extra}output = "ws.csv"
"""


def run(tmp_path, extra="elbow = [1, -1, 1]\n", phi=0, precision=0.25, limits=None, robot=""):
    text = TABLE3.format(extra=extra, phi=phi, precision=precision)
    text = text.replace("[robot3rrr]\n", f"[robot3rrr]\n{robot}")
    if limits is not None:
        text = text.replace("[[20, 70], [110, 160], [245, 295]]", limits)
    path = tmp_path / "s.toml"
    path.write_text(text, encoding="utf-8")
    (job,) = prepare_jobs(load_preset(path).jobs)
    return job, run_job(job)


def legs(robot, phi_rad, x, y, elbow, limits_rad):
    """Vectorised: validity (every leg closes in its mode within limits) and det A."""
    c, s = math.cos(phi_rad), math.sin(phi_rad)
    l1, l2 = robot.proximal_cm, robot.distal_cm
    valid = np.ones(x.shape, dtype=bool)
    rows = []
    for (qx, qy), (ax, ay), sign, (lo, hi) in zip(
        robot.platform_points_cm(), robot.base_joints_cm(), elbow, limits_rad, strict=True
    ):
        rx, ry = c * qx - s * qy, s * qx + c * qy
        cx, cy = x + rx, y + ry
        dx, dy = cx - ax, cy - ay
        d = np.hypot(dx, dy)
        a = (l1 * l1 - l2 * l2 + d * d) / (2 * d)
        h = np.sqrt(np.maximum(l1 * l1 - a * a, 0.0))
        valid &= (d <= l1 + l2) & (d >= abs(l1 - l2)) & (d > 0)
        bx = ax + a * dx / d - sign * h * dy / d
        by = ay + a * dy / d + sign * h * dx / d
        theta = np.arctan2(by - ay, bx - ax)
        valid &= np.mod(theta - lo, 2 * np.pi) <= hi - lo
        ux, uy = cx - bx, cy - by
        rows.append(np.stack([ux, uy, ux * ry - uy * rx], axis=-1))
    matrix = np.stack(rows, axis=-2)
    return valid, np.linalg.det(matrix)


def _inputs(job):
    robot = job.robot
    return robot, job.spec.orientation_rad, job.prepared.circle.elbow, job.spec.limits_rad


def traced_curve(job, extent, n=300):
    """Points of det A = 0 between sign-changing neighbours of an n x n grid (bisected)."""
    robot, phi, elbow, limits = _inputs(job)
    xs = np.linspace(extent[0], extent[1], n)
    ys = np.linspace(extent[2], extent[3], n)
    gx, gy = np.meshgrid(xs, ys)
    valid, det = legs(robot, phi, gx, gy, elbow, limits)
    points = []
    for axis in (0, 1):
        a = (slice(None, -1), slice(None)) if axis == 0 else (slice(None), slice(None, -1))
        b = (slice(1, None), slice(None)) if axis == 0 else (slice(None), slice(1, None))
        change = valid[a] & valid[b] & (np.sign(det[a]) != np.sign(det[b]))
        lo_x, lo_y, hi_x, hi_y = gx[a][change], gy[a][change], gx[b][change], gy[b][change]
        lo_det = det[a][change]
        for _ in range(45):
            mx, my = 0.5 * (lo_x + hi_x), 0.5 * (lo_y + hi_y)
            _, mdet = legs(robot, phi, mx, my, elbow, limits)
            same = np.sign(mdet) == np.sign(lo_det)
            lo_x, lo_y = np.where(same, mx, lo_x), np.where(same, my, lo_y)
            hi_x, hi_y = np.where(same, hi_x, mx), np.where(same, hi_y, my)
        ok, _ = legs(robot, phi, lo_x, lo_y, elbow, limits)
        points.append(np.stack([lo_x, lo_y], axis=1)[ok])
    return np.concatenate(points)


def ray_radius(job, centre, reach, directions=720, step=0.004):
    """min over directions of the first bad point along the ray (bisected to 1e-9 cm)."""
    robot, phi, elbow, limits = _inputs(job)
    _, det0 = legs(robot, phi, np.array(centre[0]), np.array(centre[1]), elbow, limits)
    psi = np.linspace(0, 2 * np.pi, directions, endpoint=False)[:, None]
    t = np.arange(1, int(reach / step) + 1)[None, :] * step
    x, y = centre[0] + t * np.cos(psi), centre[1] + t * np.sin(psi)
    valid, det = legs(robot, phi, x, y, elbow, limits)
    bad = ~valid | (np.sign(det) != np.sign(det0))
    hit = bad.any(axis=1)  # rays finding nothing within reach do not set the minimum
    assert hit.any()
    bad, psi = bad[hit], psi[hit]
    first = bad.argmax(axis=1)
    hi = t[0, first]
    lo = hi - step
    direction = psi[:, 0]
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        v, d = legs(
            robot,
            phi,
            centre[0] + mid * np.cos(direction),
            centre[1] + mid * np.sin(direction),
            elbow,
            limits,
        )
        is_bad = ~v | (np.sign(d) != np.sign(det0))
        hi, lo = np.where(is_bad, mid, hi), np.where(is_bad, lo, mid)
    return float(hi.min())


WIDE = "[[-30, 90], [90, 210], [210, 330]]"  # the 120° ranges (φ = -20°)


#: A geometry drawn at random (numpy seed 1, 4th draw): a, b, l1, l2 in cm.
RANDOM_ROBOT = (
    "base_side_cm = 108.1\nplatform_side_cm = 23.4\nproximal_cm = 34.9\ndistal_cm = 31.5\n"
)


@pytest.mark.slow
@pytest.mark.parametrize(
    ("elbow", "phi", "limits", "robot", "least_points"),
    [
        ("[1, -1, 1]", 0, None, "", 2),  # paper B Table 3: the curve hugs the workspace's edge
        ("[1, -1, 1]", -20, WIDE, "", 100),
        ("[-1, -1, 1]", -20, WIDE, "", 100),
        ("[1, -1, 1]", -10, WIDE, RANDOM_ROBOT, 100),
    ],
)
def test_dense_float_trace_and_ray_search_agree_with_the_certified_paving(
    tmp_path, elbow, phi, limits, robot, least_points
):
    job, result = run(
        tmp_path, f"elbow = {elbow}\n", phi=phi, precision=0.5, limits=limits, robot=robot
    )
    singular = result.singularity
    leaves = singular.singular_boxes
    points = traced_curve(job, result.outcome.extent_cm)
    assert len(points) >= least_points  # singular poses in the workspace: the check bites
    slack = 1e-9
    for chunk in np.array_split(points, max(1, len(points) // 500)):
        inside = (
            (leaves[None, :, 0] - slack <= chunk[:, None, 0])
            & (chunk[:, None, 0] <= leaves[None, :, 1] + slack)
            & (leaves[None, :, 2] - slack <= chunk[:, None, 1])
            & (chunk[:, None, 1] <= leaves[None, :, 3] + slack)
        )
        assert inside.any(axis=1).all()
    r_in, r_out = singular.radius_lo_cm, singular.radius_hi_cm
    assert 0.0 < r_in <= r_out <= r_in + 2.0 * math.sqrt(2.0) * singular.precision_cm
    r_ref = ray_radius(job, singular.centre_cm, reach=r_out + 1.0)
    assert r_in <= r_ref <= r_out + 1e-3


def test_the_map_and_the_summary_show_the_singularities_and_the_circle(cli, tmp_path):
    path = tmp_path / "s.toml"
    path.write_text(TABLE3.format(extra="elbow = [1, -1, 1]\n", phi=0, precision=1.0))
    result = cli("workspace", path, "--out-dir", tmp_path)
    assert result.exit_code == 0, result.output
    assert "×" in result.output and "o" in result.output and "+" in result.output
    assert "singularity-free: r ∈ [" in result.output
    with open(tmp_path / "ws.csv", encoding="utf-8") as f:
        (row,) = list(csv.DictReader(f))
    assert float(row["circle_radius_lo_cm"]) <= float(row["circle_radius_hi_cm"])
    assert float(row["circle_centre_x_cm"]) == pytest.approx(40.0)
    assert row["elbow"] == "1 -1 1"  # the working mode the radius holds for
    assert list(row)[-2:] == ["elbow", "seconds"]


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        ("elbow = [1, -1, 1]\ncircle_centre_cm = [0, 0]\n", "(0, 0) cm is not reachable"),
        ("elbow = [-1, -1, 1]\n", "leg 1 cannot close in its elbow -1 mode"),
        ("", "workspace.elbow: is not set and leg 3 reaches the workspace's centroid"),
        ("elbow = [1, 0, 1]\n", "each 1 or -1"),
    ],
)
def test_bad_centres_and_modes_are_refused_before_any_job_runs(cli, tmp_path, extra, message):
    path = tmp_path / "s.toml"
    path.write_text(TABLE3.format(extra=extra, phi=0, precision=1.0))
    result = cli("workspace", path, "--out-dir", tmp_path)
    assert result.exit_code == 2, result.output
    assert result.output.startswith("error: ") and result.output.count("\n") == 1
    assert message in result.output
    assert not (tmp_path / "ws.csv").exists()


@pytest.mark.parametrize(
    ("extra", "line"),
    [
        (
            "elbow = [1, 1]\n",
            "workspace.elbow: has 2 values (expected 3 signs, each 1 or -1 (one per leg))",
        ),
        (
            "elbow = [1, -1, 1]\ncircle_centre_cm = [1]\n",
            "workspace.circle_centre_cm: has 1 values (expected a point [x, y] in cm)",
        ),
    ],
)
def test_wrong_lengths_name_what_the_key_holds(cli, tmp_path, extra, line):
    path = tmp_path / "s.toml"
    path.write_text(TABLE3.format(extra=extra, phi=0, precision=1.0))
    result = cli("workspace", path, "--out-dir", tmp_path)
    assert result.exit_code == 2, result.output
    assert result.output == f"error: {path}: {line}\n"
    assert not (tmp_path / "ws.csv").exists()


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("singularities = false\nelbow = [1, 1, 1]\n", "elbow: is set without singularities"),
        (
            'singularities = true\norientation_deg = [0, 5]\norientation_mode = "total"\n',
            "singularities: is true with orientation_deg = [lo, hi]",
        ),
    ],
)
def test_singularity_keys_need_singularities_and_one_orientation(cli, tmp_path, text, message):
    path = tmp_path / "s.toml"
    path.write_text(
        "[robot3rrr]\n[workspace]\njoint_limits_deg = [[20, 70], [110, 160], [245, 295]]\n"
        f"precision_cm = 1.0\n{text}"
    )
    result = cli("workspace", path, "--out-dir", tmp_path)
    assert result.exit_code == 2 and message in result.output, result.output


def test_float_model_reproduces_the_kernels_det_at_points():
    """The kernel's point enclosure holds the reference's float det (a loose cross-check
    of the two constructions on random reachable points)."""
    from planar_tui.kernels.singularity3rrr import box_status

    from planar_tui.workspace.rrr.singularity import Circle, kernel_inputs

    class Spec:
        orientation_rad = 0.3
        limits_rad = tuple(
            (math.radians(a), math.radians(b)) for a, b in ((-15, 75), (105, 195), (225, 315))
        )

    robot = Robot3RRR()
    g, r, elbow, limits = kernel_inputs(robot, Spec, Circle(0.0, 0.0, (1, 1, 1)))
    rng = np.random.default_rng(5)
    checked = 0
    for x, y in rng.uniform(0, 120, size=(3000, 2)):
        valid, det = legs(robot, 0.3, np.array(x), np.array(y), (1, 1, 1), Spec.limits_rad)
        if not valid:
            continue
        _in_w, out_w, lo, hi = box_status(x, x, y, y, g, r, elbow, limits)
        assert not out_w
        assert lo - 1e-9 * abs(det) <= det <= hi + 1e-9 * abs(det)
        assert hi - lo <= 1e-6 * max(1.0, abs(det))
        checked += 1
    assert checked > 50

"""Certified dexterous regions (``kappa_max``) against an independent float reference.

The reference builds each leg's elbow as the intersection of the circles about A_i (l1) and
C_i (l2), on the side the elbow sign asks for (not the kernels' θ = α ± β), and takes the
inverse Jacobian :math:`J^{-1} = \\partial\\theta / \\partial(x, y, L\\varphi)` by central
finite differences of those joint angles; κ is the ratio of its extreme singular values
(numpy's SVD). Checks: every sample of a box said dexterous is dexterous; every dexterous
grid point lies in a kept box; the certified area bracket holds a fine grid's estimate. Each
check fails when the κ enclosure is shrunk by 1 % (:func:`shrunk`).
"""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest

from planar_tui.batch import prepare_jobs, run_job
from planar_tui.presets import load_preset
from planar_tui.workspace.paving import dexterity

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
kappa_max = {kappa}
{extra}output = "ws.csv"
"""
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
kappa_max = {kappa}
{extra}output = "fb.csv"
"""


def run(tmp_path, text):
    path = tmp_path / "d.toml"
    path.write_text(text, encoding="utf-8")
    (job,) = prepare_jobs(load_preset(path).jobs)
    return job, run_job(job)


def joint_angles(legs, x, y, phi):
    """Per leg ``(A, Q, l1, l2, sign, (lo, hi))``: validity (every leg closes in its mode
    within its limits) and the joint angles (legs, ...) at platform poses ``(x, y, phi)``."""
    valid = np.ones(np.shape(x), dtype=bool)
    angles = []
    for (ax, ay), (qx, qy), l1, l2, sign, (lo, hi) in legs:
        cx = x + np.cos(phi) * qx - np.sin(phi) * qy
        cy = y + np.sin(phi) * qx + np.cos(phi) * qy
        dx, dy = cx - ax, cy - ay
        d = np.hypot(dx, dy)
        a = (l1 * l1 - l2 * l2 + d * d) / (2 * d)
        h = np.sqrt(np.maximum(l1 * l1 - a * a, 0.0))
        valid &= (d < l1 + l2) & (d > abs(l1 - l2))
        bx = ax + a * dx / d - sign * h * dy / d
        by = ay + a * dy / d + sign * h * dx / d
        theta = np.arctan2(by - ay, bx - ax)
        valid &= np.mod(theta - lo, 2 * np.pi) <= hi - lo
        angles.append(theta)
    return valid, np.array(angles)


def kappa_reference(legs, x, y, length_cm, step_cm=1e-6):
    """Validity and κ at the points ``(x, y)`` (φ = 0) by central differences; a planar
    five-bar (``length_cm = None``) has the 2 x 2 Jacobian of (x, y)."""
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    valid, _ = joint_angles(legs, x, y, 0.0)
    moves = [(step_cm, 0.0, 0.0), (0.0, step_cm, 0.0)]
    if length_cm is not None:
        moves.append((0.0, 0.0, step_cm / length_cm))
    columns = []
    for dx, dy, dphi in moves:
        _, ahead = joint_angles(legs, x + dx, y + dy, dphi)
        _, behind = joint_angles(legs, x - dx, y - dy, -dphi)
        columns.append(np.angle(np.exp(1j * (ahead - behind))) / (2 * step_cm))
    inverse = np.moveaxis(np.array(columns), (0, 1), (-1, -2))  # (..., legs, moves)
    sigma = np.linalg.svd(inverse, compute_uv=False)
    with np.errstate(divide="ignore", invalid="ignore"):
        kappa = sigma[..., 0] / sigma[..., -1]
    return valid, np.where(np.isfinite(kappa), kappa, np.inf)


def rrr_legs(job):
    robot, spec = job.robot, job.spec
    l1, l2 = robot.proximal_cm, robot.distal_cm
    return [
        (a, q, l1, l2, sign, limits)
        for a, q, sign, limits in zip(
            robot.base_joints_cm(),
            robot.platform_points_cm(),
            job.prepared.circle.elbow,
            spec.limits_rad,
            strict=True,
        )
    ]


def fivebar_legs(job):
    robot = job.robot
    limits = [(math.radians(lo), math.radians(hi)) for lo, hi in robot.joint_limits_deg]
    return [
        (robot.base_joints_cm()[i], (0.0, 0.0), *lengths, robot.elbows[i], limits[i])
        for i, lengths in enumerate(zip(robot.proximal_cm, robot.distal_cm, strict=True))
    ]


def samples(boxes, n=3):
    """An n x n grid of points in each box (its corners and centre for n = 3)."""
    t = np.linspace(0.0, 1.0, n)
    x = boxes[:, :1] + (boxes[:, 1:2] - boxes[:, :1]) * t
    y = boxes[:, 2:3] + (boxes[:, 3:4] - boxes[:, 2:3]) * t
    return np.repeat(x, n, axis=1).ravel(), np.tile(y, (1, n)).ravel()


def covered(boxes, xs, ys):
    """Whether each point of the grid ``xs`` x ``ys`` (rows: y) lies in some box (closed),
    box by box over the grid indices it spans."""
    mask = np.zeros((len(ys), len(xs)), dtype=bool)
    for xlo, xhi, ylo, yhi in boxes:
        i0, i1 = np.searchsorted(xs, xlo, "left"), np.searchsorted(xs, xhi, "right")
        j0, j1 = np.searchsorted(ys, ylo, "left"), np.searchsorted(ys, yhi, "right")
        mask[j0:j1, i0:i1] = True
    return mask.ravel()


def check_inside_boxes(outcome, legs, length_cm):
    """Every sample of a box said dexterous: in the mode's workspace, κ <= kappa_max."""
    x, y = samples(outcome.boxes[outcome.status == 2])
    valid, kappa = kappa_reference(legs, x, y, length_cm)
    ok = valid & (kappa <= outcome.kappa_max * (1 + 1e-6))
    assert ok.all(), f"{np.count_nonzero(~ok)} samples of dexterous boxes are not dexterous"


def grid(outcome, step_cm):
    """Cell centres ``xs``, ``ys`` of a grid of step ``step_cm`` about the kept boxes."""
    xlo, ylo = outcome.boxes[:, 0].min() - 1.0, outcome.boxes[:, 2].min() - 1.0
    xhi, yhi = outcome.boxes[:, 1].max() + 1.0, outcome.boxes[:, 3].max() + 1.0
    return np.arange(xlo, xhi, step_cm) + 0.5 * step_cm, np.arange(
        ylo, yhi, step_cm
    ) + 0.5 * step_cm


def check_dexterous_points_kept(outcome, legs, length_cm, step_cm):
    """Every grid point with κ < kappa_max in the mode's workspace lies in a kept box."""
    xs, ys = grid(outcome, step_cm)
    x, y = (a.ravel() for a in np.meshgrid(xs, ys))
    valid, kappa = kappa_reference(legs, x, y, length_cm)
    good = valid & (kappa < outcome.kappa_max * (1 - 1e-6))
    lost = good & ~covered(outcome.boxes, xs, ys)
    assert not lost.any(), f"{np.count_nonzero(lost)} dexterous points in no kept box"


def check_bracket(outcome, legs, length_cm, step_cm):
    """The bracket holds the grid's estimate up to the grid's own error (one cell per
    boundary crossing: cells whose sample and a neighbour disagree)."""
    xs, ys = grid(outcome, step_cm)
    x, y = (a.ravel() for a in np.meshgrid(xs, ys))
    valid, kappa = kappa_reference(legs, x, y, length_cm)
    good = (valid & (kappa <= outcome.kappa_max)).reshape(len(ys), len(xs))
    estimate = good.sum() * step_cm**2
    edge = (good[1:, :] != good[:-1, :]).sum() + (good[:, 1:] != good[:, :-1]).sum()
    slack = 0.5 * edge * step_cm**2
    assert outcome.area_inside_cm2 <= estimate + slack
    assert estimate - slack <= outcome.area_kept_cm2
    return estimate


def shrunk(monkeypatch, lower_factor, upper_factor):
    """Shrink every κ enclosure the paving sees (its labels and the boxes it records as
    outside): ``lo * lower_factor``, ``hi * upper_factor`` (a mutation the checks must
    catch)."""
    original = dexterity.recording_outside

    def recording(evaluate, kappa_max, outside):
        def narrowed(boxes):
            verdict, kappa = evaluate(boxes)
            kappa = kappa.copy()
            kappa[:, 0] *= lower_factor
            kappa[:, 1] *= upper_factor
            return verdict, kappa

        return original(narrowed, kappa_max, outside)

    monkeypatch.setattr(dexterity, "recording_outside", recording)


@pytest.fixture(scope="module")
def table3(tmp_path_factory):
    job, result = run(
        tmp_path_factory.mktemp("t3"), TABLE3.format(precision=0.2, kappa=4, extra="")
    )
    return job, result


def test_boxes_said_dexterous_are_dexterous_at_every_sample(table3):
    job, result = table3
    check_inside_boxes(result.dexterity, rrr_legs(job), 25.0)


def test_every_dexterous_point_lies_in_a_kept_box(table3):
    job, result = table3
    check_dexterous_points_kept(result.dexterity, rrr_legs(job), 25.0, 0.05)


def test_the_bracket_holds_the_grid_estimate(table3):
    job, result = table3
    estimate = check_bracket(result.dexterity, rrr_legs(job), 25.0, 0.02)
    outcome = result.dexterity
    assert outcome.area_inside_cm2 > 0.9 * estimate  # and it is not vacuous
    assert outcome.area_kept_cm2 < 1.1 * estimate


def test_the_default_length_is_the_platform_circumradius(table3):
    _, result = table3
    header, (row,) = result.table.header, result.table.rows
    cells = dict(zip(header, row, strict=True))
    assert cells["characteristic_length_cm"] == pytest.approx(25.0)  # 40-wide, 40-high
    assert cells["kappa_max"] == 4.0
    assert list(header)[-13:-9] == list(dexterity.HEADER)  # then the disc's, the time


def test_a_shrunk_upper_bound_labels_non_dexterous_points_dexterous(tmp_path, monkeypatch):
    shrunk(monkeypatch, 1.0, 0.99)
    job, result = run(tmp_path, TABLE3.format(precision=0.2, kappa=4, extra=""))
    with pytest.raises(AssertionError, match="are not dexterous"):
        check_inside_boxes(result.dexterity, rrr_legs(job), 25.0)


def test_a_shrunk_lower_bound_drops_dexterous_points(tmp_path, monkeypatch):
    shrunk(monkeypatch, 1.01, 1.0)
    job, result = run(tmp_path, TABLE3.format(precision=0.2, kappa=4, extra=""))
    with pytest.raises(AssertionError, match="in no kept box"):
        check_dexterous_points_kept(result.dexterity, rrr_legs(job), 25.0, 0.05)


@pytest.fixture(scope="module")
def fivebar(tmp_path_factory):
    return run(tmp_path_factory.mktemp("fb"), FIVEBAR.format(precision=0.25, kappa=3, extra=""))


def test_the_five_bar_region_against_the_reference(fivebar):
    job, result = fivebar
    outcome, legs = result.dexterity, fivebar_legs(job)
    check_inside_boxes(outcome, legs, None)
    check_dexterous_points_kept(outcome, legs, None, 0.5)
    check_bracket(outcome, legs, None, 0.25)
    header, (row,) = result.table.header, result.table.rows
    cells = dict(zip(header, row, strict=True))
    assert cells["characteristic_length_cm"] == ""  # no orientation: no L


def test_the_five_bar_check_fails_with_a_shrunk_enclosure(tmp_path, monkeypatch):
    shrunk(monkeypatch, 1.0, 0.99)
    job, result = run(tmp_path, FIVEBAR.format(precision=0.25, kappa=3, extra=""))
    with pytest.raises(AssertionError, match="are not dexterous"):
        check_inside_boxes(result.dexterity, fivebar_legs(job), None)


def test_the_cli_writes_the_columns_labels_the_boxes_and_draws_the_maps(cli, tmp_path):
    path = tmp_path / "d.toml"
    text = TABLE3.format(precision=0.5, kappa=4, extra='boxes_output = "b.csv"\n')
    path.write_text(text, encoding="utf-8")
    result = cli("workspace", path, "--out-dir", tmp_path)
    assert result.exit_code == 0, result.output
    assert "dexterous (κ ≤ 4, L = 25 cm): area in [" in result.output
    assert "κ map" in result.output and "4 κ ≤ 4" in result.output
    with open(tmp_path / "ws.csv", encoding="utf-8") as f:
        (row,) = list(csv.DictReader(f))
    assert float(row["dexterous_area_inside_cm2"]) <= float(row["dexterous_area_kept_cm2"])
    with open(tmp_path / "b.csv", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    labels = {r["status"] for r in rows}
    assert {"inside", "boundary", "dexterous", "dexterous-boundary"} <= labels
    for r in rows:
        if r["status"] == "dexterous":
            assert 1.0 <= float(r["kappa_lo"]) <= float(r["kappa_hi"]) <= 4.0
        elif r["status"] in ("inside", "boundary"):
            assert r["kappa_lo"] == r["kappa_hi"] == ""


def test_the_length_changes_kappa_as_the_reference_does(tmp_path):
    job, result = run(
        tmp_path,
        TABLE3.format(precision=0.5, kappa=4, extra="characteristic_length_cm = 10\n"),
    )
    check_inside_boxes(result.dexterity, rrr_legs(job), 10.0)
    assert result.dexterity.length_cm == 10.0


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("kappa_max = 1\n", "workspace.kappa_max: is 1: κ is at least 1 (expected a number > 1)"),
        ("kappa_max = 0.5\n", "workspace.kappa_max: is 0.5"),
        ('kappa_max = "four"\n', "workspace.kappa_max:"),
        ("kappa_max = 4\ncharacteristic_length_cm = 0\n", "characteristic_length_cm:"),
        ("kappa_max = 4\ncharacteristic_length_cm = -2\n", "characteristic_length_cm:"),
        ("characteristic_length_cm = 20\n", "characteristic_length_cm: is set without kappa_max"),
        ('kappa_max = 4\nform = "geometric"\n', 'kappa_max: is set with form = "geometric"'),
    ],
)
def test_bad_dexterity_keys_exit_2_with_one_line(cli, tmp_path, text, message):
    path = tmp_path / "d.toml"
    path.write_text(
        "[robot3rrr]\n[workspace]\njoint_limits_deg = [[20, 70], [110, 160], [245, 295]]\n"
        f'precision_cm = 1.0\noutput = "ws.csv"\n{text}',
        encoding="utf-8",
    )
    result = cli("workspace", path, "--out-dir", tmp_path)
    assert result.exit_code == 2, result.output
    assert result.output.startswith("error: ") and result.output.count("\n") == 1
    assert message in result.output
    assert not (tmp_path / "ws.csv").exists()


def test_a_five_bar_in_any_mode_is_refused(cli, tmp_path):
    path = tmp_path / "f.toml"
    text = FIVEBAR.format(precision=1.0, kappa=3, extra="").replace('"+-"', '"any"')
    path.write_text(text, encoding="utf-8")
    result = cli("workspace5r", path, "--out-dir", tmp_path)
    assert result.exit_code == 2, result.output
    assert "kappa_max: needs a working mode" in result.output


def test_circumradius_of_known_triangles():
    assert dexterity.circumradius_cm([(0, 0), (40, 0), (20, 40)]) == pytest.approx(25.0)
    side = 10.0  # equilateral: side / sqrt(3)
    points = [(0, 0), (side, 0), (side / 2, side * math.sqrt(3) / 2)]
    assert dexterity.circumradius_cm(points) == pytest.approx(side / math.sqrt(3))
    assert dexterity.circumradius_cm([(0, 0), (1, 0), (3, 0)]) == pytest.approx(1.5)

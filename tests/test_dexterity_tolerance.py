"""Dexterous regions with tolerances (``kappa_max`` with ``tolerance_cm``): in mode
``all`` a point is dexterous when every robot within the tolerances is, in mode ``some``
when one is.

Checked against robots sampled inside the tolerance box (per leg and independently: base
joint, platform point, proximal and distal length), among them the nominal robot and the
vertices with every link length at its upper or lower tolerance (the robots the
certificates exhibit), each with the float reference of :mod:`tests.test_dexterity` (the
elbows as circle intersections, κ by central differences):

- ``all``: every sample of a box said dexterous is dexterous for every sampled robot; every
  grid point where some sampled robot has κ > kappa_max (1 + 1e-3) lies in no dexterous box;
  every grid point dexterous for every sampled robot with a margin lies in a kept box;
- ``some``: every sample of a box said dexterous is dexterous for some sampled robot; every
  grid point where some sampled robot is dexterous with a margin lies in a kept box;
- tiny boxes with a tiny tolerance are never proved dexterous with kappa_max 0.1 % below
  the sampled robots' worst (``all``) or best (``some``) κ, nor outside 0.1 % above; with
  the κ enclosures shrunk by 1 % that check fails (asserted).
"""

from __future__ import annotations

import csv
import dataclasses

import numpy as np
import pytest

from planar_tui.batch import prepare_jobs
from planar_tui.presets import load_preset
from planar_tui.workspace.paving.dexterity import label_boxes
from planar_tui.workspace.rrr import dexterity as rrr_dexterity
from planar_tui.workspace.rrr.dexterity import evaluator
from tests.test_dexterity import covered, grid, kappa_reference, rrr_legs, run, samples

RRR = """
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
kappa_max = 4
tolerance_cm = {tolerance}
tolerance_mode = "{mode}"
{extra}output = "ws.csv"
"""
LENGTH_CM = 25.0  # the Table-3 platform's circumradius
ROBOTS = 24


def sampled_robots(job, count=ROBOTS, seed=3):
    """Legs lists (:func:`tests.test_dexterity.rrr_legs`) of robots within the job's
    tolerance: the nominal one, the two length vertices, then random vertices and random
    inner robots, every leg's quantities drawn independently."""
    t = dict(job.spec.tolerances_cm or ())
    uniform = job.spec.tolerance_cm or 0.0
    t_a, t_q, t_1, t_2 = (
        t.get(k, uniform)
        for k in ("base_joints_cm", "platform_points_cm", "proximal_cm", "distal_cm")
    )
    nominal = rrr_legs(job)
    rng = np.random.default_rng(seed)
    shrink = 1.0 - 1e-6  # as the certificates' vertices: inside the box
    robots = [nominal]
    for sign in (1.0, -1.0):
        robots.append(
            [
                (a, q, l1 + sign * shrink * t_1, l2 + sign * shrink * t_2, s, lim)
                for a, q, l1, l2, s, lim in nominal
            ]
        )
    while len(robots) < count:
        vertex = len(robots) % 2 == 0
        legs = []
        for a, q, l1, l2, s, lim in nominal:
            d = rng.choice([-1.0, 1.0], 6) if vertex else rng.uniform(-1.0, 1.0, 6)
            d = d * shrink
            legs.append(
                (
                    (a[0] + d[0] * t_a, a[1] + d[1] * t_a),
                    (q[0] + d[2] * t_q, q[1] + d[3] * t_q),
                    l1 + d[4] * t_1,
                    l2 + d[5] * t_2,
                    s,
                    lim,
                )
            )
        robots.append(legs)
    return robots


def kappas(robots, x, y):
    """κ (robots, points) of each robot at the points, ``inf`` where it does not close."""
    rows = []
    for legs in robots:
        valid, kappa = kappa_reference(legs, x, y, LENGTH_CM)
        rows.append(np.where(valid, kappa, np.inf))
    return np.array(rows)


def check_region(job, outcome, step_cm):
    """The module docstring's region checks of the job's mode."""
    kmax = outcome.kappa_max
    robots = sampled_robots(job)
    dexterous = outcome.boxes[outcome.status == 2]
    x, y = samples(dexterous)
    at_samples = kappas(robots, x, y)
    xs, ys = grid(outcome, step_cm)
    gx, gy = (a.ravel() for a in np.meshgrid(xs, ys))
    at_grid = kappas(robots, gx, gy)
    if job.spec.tolerance_mode == "all":
        bad = at_samples.max(axis=0) > kmax * (1 + 1e-6)
        assert not bad.any(), f"{np.count_nonzero(bad)} samples of dexterous boxes fail"
        failing = at_grid.max(axis=0) > kmax * (1 + 1e-3)
        wrong = failing & covered(dexterous, xs, ys)
        assert not wrong.any(), f"{np.count_nonzero(wrong)} failing points in dexterous boxes"
        good = at_grid.max(axis=0) < kmax * (1 - 1e-3)
    else:
        bad = at_samples.min(axis=0) > kmax * (1 + 1e-6)
        assert not bad.any(), f"{np.count_nonzero(bad)} samples of dexterous boxes fail"
        good = at_grid.min(axis=0) < kmax * (1 - 1e-3)
    lost = good & ~covered(outcome.boxes, xs, ys)
    assert not lost.any(), f"{np.count_nonzero(lost)} dexterous points in no kept box"
    return good


@pytest.mark.parametrize("mode", ["all", "some"])
def test_the_region_holds_for_the_sampled_robots(tmp_path, mode):
    text = RRR.format(precision=0.25, tolerance=0.02, mode=mode, extra="")
    job, result = run(tmp_path, text)
    outcome = result.dexterity
    good = check_region(job, outcome, 0.05)
    assert outcome.area_inside_cm2 > 0.0 and good.any()  # not vacuous


def tiny_boxes(job, count=12, seed=5, half_cm=1e-4):
    """Tiny boxes about points where every sampled robot closes with a finite κ."""
    rng = np.random.default_rng(seed)
    robots = sampled_robots(job)
    x, y = rng.uniform(30.0, 42.0, 400), rng.uniform(4.0, 16.0, 400)
    k = kappas(robots, x, y)
    keep = np.flatnonzero(np.isfinite(k).all(axis=0))[:count]
    assert len(keep) == count
    boxes = np.column_stack(
        [x[keep] - half_cm, x[keep] + half_cm, y[keep] - half_cm, y[keep] + half_cm]
    )
    return boxes, k[:, keep]


def check_tiny_boxes(job):
    """Never dexterous 0.1 % below the sampled worst (``all``) or best (``some``) κ, never
    outside 0.1 % above; most proved dexterous 5 % above."""
    boxes, k = tiny_boxes(job)
    ref = k.max(axis=0) if job.spec.tolerance_mode == "all" else k.min(axis=0)
    proved = 0
    for box, value in zip(boxes, ref, strict=True):

        def label(kmax, box=box):
            spec = dataclasses.replace(job.spec, kappa_max=kmax)
            evaluate = evaluator(job.robot, spec, job.prepared.circle)
            return int(label_boxes(evaluate, box[None, :], kmax)[0])

        assert label(value / 1.001) != 2, "proved dexterous below its κ"
        assert label(value * 1.001) != 0, "proved outside above its κ"
        proved += label(value * 1.05) == 2
    assert proved >= len(boxes) // 2


def shrink_kernel(monkeypatch, factor=0.01):
    """Shrink every κ enclosure of the 3-RRR's kernel by ``factor`` (a mutation)."""
    original = rrr_dexterity.kernel_evaluator

    def shrunk(*args):
        evaluate = original(*args)

        def narrowed(boxes):
            verdict, kappa = evaluate(boxes)
            kappa = kappa.copy()
            kappa[:, 0] *= 1.0 + factor
            kappa[:, 1] *= 1.0 - factor
            return verdict, kappa

        return narrowed

    monkeypatch.setattr(rrr_dexterity, "kernel_evaluator", shrunk)


@pytest.mark.parametrize("mode", ["all", "some"])
@pytest.mark.parametrize("shrink", [False, True])
def test_tiny_boxes_are_decided_about_the_sampled_kappa(tmp_path, monkeypatch, mode, shrink):
    path = tmp_path / "d.toml"
    path.write_text(RRR.format(precision=1.0, tolerance=1e-5, mode=mode, extra=""), "utf-8")
    (job,) = prepare_jobs(load_preset(path).jobs)
    if not shrink:
        check_tiny_boxes(job)
        return
    shrink_kernel(monkeypatch)
    with pytest.raises(AssertionError, match="proved"):
        check_tiny_boxes(job)


def test_the_cli_writes_the_columns_and_labels_the_boxes(cli, tmp_path):
    path = tmp_path / "d.toml"
    extra = 'boxes_output = "b.csv"\n'
    path.write_text(
        RRR.format(precision=0.5, tolerance=0.02, mode="all", extra=extra), encoding="utf-8"
    )
    result = cli("run", path, "--out-dir", tmp_path)
    assert result.exit_code == 0, result.output
    with open(tmp_path / "ws.csv", encoding="utf-8") as f:
        (row,) = list(csv.DictReader(f))
    assert row["tolerance_mode"] == "all"
    inside, kept = float(row["dexterous_area_inside_cm2"]), float(row["dexterous_area_kept_cm2"])
    assert 0.0 < inside <= kept
    with open(tmp_path / "b.csv", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    assert {"dexterous", "dexterous-boundary"} <= {r["status"] for r in rows}
    for r in rows:
        if r["status"] == "dexterous":
            assert 1.0 <= float(r["kappa_lo"]) <= float(r["kappa_hi"]) <= 4.0


RANGE = 'elbow = [1, -1, 1]\norientation_deg = [-2, 2]\norientation_mode = "total"'
RPR = """
[robot3rpr]
[[workspace3rpr]]
leg_limits_cm = [[20, 100], [20, 100], [20, 100]]
precision_cm = 1.0
kappa_max = 2
tolerance_cm = 0.01
output = "rpr.csv"
"""


@pytest.mark.parametrize(
    ("command", "text", "message"),
    [
        (
            "workspace",
            RRR.format(precision=1.0, tolerance=0.02, mode="all", extra="").replace(
                "elbow = [1, -1, 1]", RANGE
            ),
            "orientation_deg: is",
        ),
        ("workspace3rpr", RPR, "kappa_max: is set with a tolerance"),
    ],
)
def test_what_stays_refused_exits_2_with_one_line(cli, tmp_path, command, text, message):
    path = tmp_path / "d.toml"
    path.write_text(text, encoding="utf-8")
    result = cli(command, path, "--out-dir", tmp_path)
    assert result.exit_code == 2, result.output
    assert result.output.startswith("error: ") and result.output.count("\n") == 1
    assert message in result.output
    assert not list(tmp_path.glob("*.csv"))

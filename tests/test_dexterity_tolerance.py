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
from typing import Any

import numpy as np
import pytest
from planar_tui.kernels import dexterity_prismatic, dexterity_rr

from planar_tui.batch import prepare_jobs
from planar_tui.presets import load_preset
from planar_tui.workspace.fivebar.dexterity import evaluator as fivebar_evaluator
from planar_tui.workspace.paving.dexterity import label_boxes
from planar_tui.workspace.prr.dexterity import evaluator as prr_evaluator
from planar_tui.workspace.prr.dexterity import working_modes
from planar_tui.workspace.rpr.dexterity import evaluator as rpr_evaluator
from planar_tui.workspace.rrr.dexterity import evaluator as rrr_evaluator
from tests.test_dexterity import (
    covered,
    fivebar_legs,
    grid,
    kappa_reference,
    rrr_legs,
    run,
    samples,
)
from tests.test_dexterity_prismatic import kappa_reference as prismatic_kappa

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
kappa_max = 3
tolerance_cm = {tolerance}
tolerance_mode = "{mode}"
{extra}output = "ws.csv"
"""
RPR = """
[robot3rpr]
base_joints_cm = [[0, 0], [120, 0], [60, 103.92]]
platform_points_cm = [[0, 23.09], [-20, -11.55], [20, -11.55]]
[[workspace3rpr]]
leg_limits_cm = [[20, 100], [20, 100], [20, 100]]
precision_cm = {precision}
geometric_reference = false
kappa_max = 1.5
characteristic_length_cm = 25
tolerance_cm = {tolerance}
tolerance_mode = "{mode}"
{extra}output = "ws.csv"
"""
PRR = """
[robot3prr]
[[workspace3prr]]
precision_cm = {precision}
geometric_reference = false
kappa_max = 6
tolerance_cm = {tolerance}
tolerance_mode = "{mode}"
{extra}output = "ws.csv"
"""
ROBOTS = 24
#: The quantities of a leg that are points (the others: lengths).
POINTS = ("base_joints_cm", "platform_points_cm", "slider_points_cm")


def rr_kappas(length_cm):
    """κ of an RR-legged robot (legs: dicts as :func:`rr_nominal` gives) at points."""

    def kappas(legs, x, y):
        keys = ("base_joints_cm", "platform_points_cm", "proximal_cm", "distal_cm")
        tuples = [(*(leg[k] for k in keys), leg["sign"], leg["limits"]) for leg in legs]
        return kappa_reference(tuples, x, y, length_cm)

    return kappas


def rr_nominal(job):
    """Per leg: the quantities of :func:`tests.test_dexterity.rrr_legs` (or
    ``fivebar_legs``) by their tolerance keys, the elbow sign and the joint limits."""
    legs = rrr_legs(job) if hasattr(job.prepared, "circle") else fivebar_legs(job)
    keys = ("base_joints_cm", "platform_points_cm", "proximal_cm", "distal_cm", "sign", "limits")
    return [dict(zip(keys, leg, strict=True)) for leg in legs]


def rpr_nominal(job):
    robot = job.robot
    return [
        {"base_joints_cm": a, "platform_points_cm": q, "limits": limits}
        for a, q, limits in zip(
            robot.base_joints_cm, robot.platform_points_cm, job.spec.leg_limits_cm, strict=True
        )
    ]


def rpr_kappas(legs, x, y):
    def actuators(x, y, phi):
        valid, out = np.ones(np.shape(x), dtype=bool), []
        for leg in legs:
            (ax, ay), (qx, qy), (lo, hi) = (
                leg["base_joints_cm"],
                leg["platform_points_cm"],
                leg["limits"],
            )
            rho = np.hypot(
                x + np.cos(phi) * qx - np.sin(phi) * qy - ax,
                y + np.sin(phi) * qx + np.cos(phi) * qy - ay,
            )
            valid &= (lo <= rho) & (rho <= hi)
            out.append(rho)
        return valid, np.array(out)

    return prismatic_kappa(actuators, x, y, 25.0)


def prr_nominal(job):
    robot, modes = job.robot, working_modes(job.job, job.prepared)
    return [
        {
            "slider_points_cm": b,
            "angle": angle,
            "stroke": stroke,
            "distal_cm": length,
            "platform_points_cm": q,
            "sign": sign,
        }
        for b, angle, stroke, length, q, sign in zip(
            robot.slider_points_cm,
            robot.slider_angles_deg,
            robot.strokes_cm,
            robot.distal_cm,
            robot.platform_points_cm,
            modes,
            strict=True,
        )
    ]


def prr_kappas(legs, x, y):
    def actuators(x, y, phi):
        valid, out = np.ones(np.shape(x), dtype=bool), []
        for leg in legs:
            (bx, by), (qx, qy) = leg["slider_points_cm"], leg["platform_points_cm"]
            (lo, hi), length = leg["stroke"], leg["distal_cm"]
            ux, uy = np.cos(np.radians(leg["angle"])), np.sin(np.radians(leg["angle"]))
            cx = x + np.cos(phi) * qx - np.sin(phi) * qy - bx
            cy = y + np.sin(phi) * qx + np.cos(phi) * qy - by
            along = cx * ux + cy * uy  # |B + s u - C| = l on the line B + s u
            disc = along**2 - (cx**2 + cy**2 - length**2)
            slider = along + leg["sign"] * np.sqrt(np.maximum(disc, 0.0))
            valid &= (disc > 0) & (lo <= slider) & (slider <= hi)
            out.append(slider)
        return valid, np.array(out)

    return prismatic_kappa(actuators, x, y, 25.0)


@dataclasses.dataclass(frozen=True)
class Case:
    """One robot: its preset, its legs' nominal quantities, their reference κ (an
    independent float inverse kinematics), its evaluator and where its tiny boxes lie."""

    text: str
    nominal: Any
    kappas: Any
    evaluator: Any
    area: tuple[float, float, float, float]  # x_lo, x_hi, y_lo, y_hi of the tiny boxes
    region: tuple[float, float, float]  # precision, tolerance, grid step of the region check
    kernel: tuple[Any, str]  # the module and name of its κ kernel (the mutation's target)


CASES = {
    "3-RRR": Case(
        RRR,
        rr_nominal,
        rr_kappas(25.0),  # the Table-3 platform's circumradius
        lambda job, spec: rrr_evaluator(job.robot, spec, job.prepared.circle),
        (30.0, 42.0, 4.0, 16.0),
        (0.25, 0.02, 0.1),
        (dexterity_rr, "rr_dexterity"),
    ),
    "five-bar": Case(
        FIVEBAR,
        rr_nominal,
        rr_kappas(None),
        lambda job, spec: fivebar_evaluator(job.robot, spec),
        (-10.0, 50.0, 40.0, 90.0),
        (1.0, 0.05, 1.0),
        (dexterity_rr, "rr_dexterity"),
    ),
    "3-RPR": Case(
        RPR,
        rpr_nominal,
        rpr_kappas,
        lambda job, spec: rpr_evaluator(job.robot, spec),
        (40.0, 80.0, 20.0, 50.0),
        (1.0, 0.05, 0.5),
        (dexterity_prismatic, "rpr_dexterity"),
    ),
    "3-PRR": Case(
        PRR,
        prr_nominal,
        prr_kappas,
        lambda job, spec: prr_evaluator(
            dataclasses.replace(job.job, spec=spec), working_modes(job.job, job.prepared)
        ),
        (30.0, 50.0, 15.0, 32.0),
        (1.0, 0.05, 0.5),
        (dexterity_prismatic, "prr_dexterity"),
    ),
}


def sampled_robots(job, case, count=ROBOTS, seed=3):
    """Per-leg quantity lists of robots within the job's tolerance: the nominal one, the
    two with every link length at its upper or lower tolerance (the robots the certificates
    exhibit), then random vertices and random inner robots, every leg's quantities drawn
    independently (a quantity the kind does not tolerance stays)."""
    widths = dict.fromkeys(job.spec.tolerance_keys, job.spec.tolerance_cm or 0.0)
    widths.update(dict(job.spec.tolerances_cm or ()))
    nominal = case.nominal(job)
    rng = np.random.default_rng(seed)
    shrink = 1.0 - 1e-6  # as the certificates' vertices: inside the box
    lengths = [k for k in widths if k not in POINTS]
    robots = [nominal]
    for sign in (1.0, -1.0):
        robots.append(
            [{**leg, **{k: leg[k] + sign * shrink * widths[k] for k in lengths}} for leg in nominal]
        )
    while len(robots) < count:
        vertex = len(robots) % 2 == 0
        legs = []
        for leg in nominal:
            moved = dict(leg)
            for key, width in widths.items():
                shape = 2 if key in POINTS else 1
                d = rng.choice([-1.0, 1.0], shape) if vertex else rng.uniform(-1.0, 1.0, shape)
                d = d * shrink * width
                value = leg[key]
                moved[key] = (value[0] + d[0], value[1] + d[1]) if shape == 2 else value + d[0]
            legs.append(moved)
        robots.append(legs)
    return robots


def kappas(case, robots, x, y):
    """κ (robots, points) of each robot at the points, ``inf`` where it does not close."""
    rows = []
    for legs in robots:
        valid, kappa = case.kappas(legs, x, y)
        rows.append(np.where(valid, kappa, np.inf))
    return np.array(rows)


def check_region(job, case, outcome, step_cm):
    """The module docstring's region checks of the job's mode."""
    kmax = outcome.kappa_max
    robots = sampled_robots(job, case)
    dexterous = outcome.boxes[outcome.status == 2]
    x, y = samples(dexterous)
    at_samples = kappas(case, robots, x, y)
    xs, ys = grid(outcome, step_cm)
    gx, gy = (a.ravel() for a in np.meshgrid(xs, ys))
    at_grid = kappas(case, robots, gx, gy)
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


@pytest.mark.parametrize("robot", list(CASES))
@pytest.mark.parametrize("mode", ["all", "some"])
def test_the_region_holds_for_the_sampled_robots(tmp_path, robot, mode):
    case = CASES[robot]
    precision, tolerance, step = case.region
    text = case.text.format(precision=precision, tolerance=tolerance, mode=mode, extra="")
    job, result = run(tmp_path, text)
    outcome = result.dexterity
    good = check_region(job, case, outcome, step)
    assert outcome.area_inside_cm2 > 0.0 and good.any()  # not vacuous


def tiny_boxes(job, case, count=12, seed=5, half_cm=1e-4):
    """Tiny boxes about points where every sampled robot closes with a finite κ."""
    rng = np.random.default_rng(seed)
    robots = sampled_robots(job, case)
    xlo, xhi, ylo, yhi = case.area
    x, y = rng.uniform(xlo, xhi, 400), rng.uniform(ylo, yhi, 400)
    k = kappas(case, robots, x, y)
    keep = np.flatnonzero(np.isfinite(k).all(axis=0))[:count]
    assert len(keep) == count
    boxes = np.column_stack(
        [x[keep] - half_cm, x[keep] + half_cm, y[keep] - half_cm, y[keep] + half_cm]
    )
    return boxes, k[:, keep]


def check_tiny_boxes(job, case):
    """Never dexterous 0.1 % below the sampled worst (``all``) or best (``some``) κ, never
    outside 0.1 % above; most proved dexterous 5 % above."""
    boxes, k = tiny_boxes(job, case)
    ref = k.max(axis=0) if job.spec.tolerance_mode == "all" else k.min(axis=0)
    proved = 0
    for box, value in zip(boxes, ref, strict=True):

        def label(kmax, box=box):
            spec = dataclasses.replace(job.spec, kappa_max=kmax)
            evaluate = case.evaluator(job, spec)
            return int(label_boxes(evaluate, box[None, :], kmax)[0])

        assert label(value / 1.001) != 2, "proved dexterous below its κ"
        assert label(value * 1.001) != 0, "proved outside above its κ"
        proved += label(value * 1.05) == 2
    assert proved >= len(boxes) // 2


def shrink_kernel(monkeypatch, case, factor=0.01):
    """Shrink every κ enclosure of the robot's kernel by ``factor`` (a mutation)."""
    module, name = case.kernel
    original = getattr(module, name)

    def shrunk(*args):
        original(*args)
        kappa = args[-1]
        kappa[:, 0] *= 1.0 + factor
        kappa[:, 1] *= 1.0 - factor

    monkeypatch.setattr(module, name, shrunk)


@pytest.mark.parametrize("robot", list(CASES))
@pytest.mark.parametrize("mode", ["all", "some"])
@pytest.mark.parametrize("shrink", [False, True])
def test_tiny_boxes_are_decided_about_the_sampled_kappa(tmp_path, monkeypatch, robot, mode, shrink):
    case, path = CASES[robot], tmp_path / "d.toml"
    path.write_text(case.text.format(precision=1.0, tolerance=1e-5, mode=mode, extra=""), "utf-8")
    (job,) = prepare_jobs(load_preset(path).jobs)
    if not shrink:
        check_tiny_boxes(job, case)
        return
    shrink_kernel(monkeypatch, case)
    with pytest.raises(AssertionError, match="proved"):
        check_tiny_boxes(job, case)


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
PRR_RANGE = 'slider_modes = [1, 1, 1]\norientation_deg = [-2, 2]\norientation_mode = "total"\n'


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
        (
            "workspace3prr",
            PRR.format(precision=1.0, tolerance=0.05, mode="all", extra=PRR_RANGE),
            "orientation_deg: is",
        ),
        (
            "workspace3rpr",
            RPR.format(precision=1.0, tolerance=0.05, mode="some", extra="").replace(
                "kappa_max = 1.5", "kappa_max = 1"
            ),
            "kappa_max: is 1",
        ),
        (
            "workspace5r",
            FIVEBAR.format(precision=1.0, tolerance=0.05, mode="all", extra="").replace(
                '"+-"', '"any"'
            ),
            "kappa_max: needs a working mode",
        ),
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

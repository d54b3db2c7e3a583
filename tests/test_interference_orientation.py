"""Certified interference-free regions over a range of orientations (``leg_width_cm`` with
``orientation_deg = [lo, hi]``): a point is interference-free when every φ of the range
closes the legs in the working mode and keeps the clearance. Checked against the exact
segment distances of :mod:`tests.test_interference` (its reference turned to each φ) at
every φ of a dense grid over the range: every sample of a box said interference-free keeps
the clearance at every φ; every grid point whose sampled least gap exceeds 0 by a margin
lies in a kept box; tiny boxes about points whose least gap over the range is just above
0 get a gap enclosure holding it, and that check fails with the pose-box gap enclosure
shrunk by 1 % of the width (:func:`shrink_clearance`)."""

from __future__ import annotations

import csv

import numpy as np
import pytest

from planar_tui.workspace.prr import mechanism as prr
from planar_tui.workspace.rpr import mechanism as rpr
from planar_tui.workspace.rrr import mechanism as rrr
from tests.test_interference import (
    COMPACT,
    EXTRA,
    RPR,
    WIDTH_CM,
    covered,
    grid,
    reference,
    run,
    samples,
)

RANGE = 'orientation_deg = [-5, 5]\norientation_mode = "total"\n'
PRR = """
[robot3prr]
[[workspace3prr]]
precision_cm = {precision}
slider_modes = [1, 1, 1]
geometric_reference = false
{extra}output = "a.csv"
"""
TEXTS = {
    "rrr": COMPACT.format(precision="{precision}", extra=EXTRA + RANGE),
    "rpr": RPR.format(precision="{precision}", extra=EXTRA + RANGE)
    + "geometric_reference = false\n",
    "prr": PRR.format(precision="{precision}", extra=EXTRA + RANGE),
}
MECHANISMS = {"rrr": rrr.MECHANISM, "rpr": rpr.MECHANISM, "prr": prr.MECHANISM}


def least_gap(job, x, y, count=41):
    """Whether the legs close at every one of ``count`` φ over the range, and the least
    gap over them, at the points ``(x, y)``."""
    lo, hi = job.spec.orientation_deg
    valid, least = np.ones(np.shape(x), dtype=bool), np.full(np.shape(x), np.inf)
    for phi in np.radians(np.linspace(lo, hi, count)):
        ok, gap = reference(job, x, y, phi)
        valid &= ok
        least = np.minimum(least, np.where(ok, gap, -np.inf))
    return valid, least


def check_inside_boxes(job, outcome):
    """Every sample of a box said interference-free: legs closed, gap >= 0 at every φ."""
    x, y = samples(outcome.boxes[outcome.status == 2])
    valid, least = least_gap(job, x, y)
    ok = valid & (least >= -1e-9)
    assert ok.all(), f"{np.count_nonzero(~ok)} samples of interference-free boxes interfere"


def check_free_points_kept(job, outcome, extent, step_cm, margin_cm=0.1):
    """Every grid point whose least gap over the range exceeds ``margin_cm`` is kept."""
    xs, ys = grid(extent, step_cm)
    x, y = (a.ravel() for a in np.meshgrid(xs, ys))
    valid, least = least_gap(job, x, y)
    free = valid & (least > margin_cm)
    assert free.any()
    lost = free & ~covered(outcome.boxes, xs, ys)
    assert not lost.any(), f"{np.count_nonzero(lost)} interference-free points in no kept box"


@pytest.mark.parametrize("robot", ["rrr", "rpr", "prr"])
def test_the_region_keeps_the_clearance_at_every_orientation(tmp_path, robot):
    job, result = run(tmp_path, TEXTS[robot].format(precision=2.0))
    outcome, extent = result.interference, result.outcome.extent_cm
    assert 0.0 < outcome.area_inside_cm2 <= outcome.area_kept_cm2
    assert outcome.area_kept_cm2 <= result.outcome.area_kept_cm2 + 1e-9  # in the workspace
    check_inside_boxes(job, outcome)
    check_free_points_kept(job, outcome, extent, 1.0)
    _, least = least_gap(job, *samples(result.outcome.boxes[result.outcome.status == 2], 2))
    assert (least < 0).mean() > 0.02  # the legs do collide somewhere in the range


def near_boundary_points(job, outcome, count=8, band_cm=0.04):
    """Up to ``count`` points of the boundary boxes whose least gap over 401 φ of the range
    lies in ``(0.002, band_cm)`` cm (legs closed at every φ), with that gap."""
    rng = np.random.default_rng(7)
    boxes = outcome.boxes[outcome.status == 1]
    pick = boxes[rng.integers(len(boxes), size=12000)]
    x = rng.uniform(pick[:, 0], pick[:, 1])
    y = rng.uniform(pick[:, 2], pick[:, 3])
    valid, least = least_gap(job, x, y, 401)
    near = np.flatnonzero(valid & (least > 0.002) & (least < band_cm))
    assert len(near) >= count // 2
    near = near[:: max(1, len(near) // count)][:count]
    return x[near], y[near], least[near]


def check_tiny_boxes(job, points, slack_cm=0.02):
    """At tiny boxes about ``points`` (x, y, least sampled gap g): the box is not proved
    outside and its gap enclosure holds g (its lower end at most g, its upper end at least
    g less the sampling's ``slack_cm``)."""
    evaluate = job.spec.mechanism.interference(job, job.prepared)
    for x, y, least in zip(*points, strict=True):
        verdict, gap = evaluate(np.array([[x, x + 1e-4, y, y + 1e-4]]))
        held = verdict[0] != 0 and gap[0, 0] <= least + 1e-9 and gap[0, 1] >= least - slack_cm
        assert held, f"({x:.5g}, {y:.5g}): gap {least:.4g} cm, enclosure {gap[0]}, {verdict[0]}"


def shrink_clearance(monkeypatch, mechanism, fraction=0.01):
    """The mutation: ``mechanism``'s pose-box gap enclosure shrunk by ``fraction`` of the
    width at each end."""
    original = type(mechanism).pose_clearance

    def shrunk(self, robot, spec):
        clearance = original(self, robot, spec)

        def shrunk_clearance(boxes):
            verdict, gap = clearance(boxes)
            return verdict, gap + fraction * WIDTH_CM * np.array([1.0, -1.0])

        return shrunk_clearance

    monkeypatch.setattr(type(mechanism), "pose_clearance", shrunk)


@pytest.fixture(scope="module", params=["rrr", "rpr", "prr"])
def near(request, tmp_path_factory):
    robot = request.param
    job, result = run(tmp_path_factory.mktemp(robot), TEXTS[robot].format(precision=2.0))
    return robot, job, near_boundary_points(job, result.interference)


@pytest.mark.parametrize("shrink", [False, True])
def test_tiny_boxes_enclose_the_least_gap_over_the_range(near, monkeypatch, shrink):
    robot, job, points = near
    if not shrink:
        check_tiny_boxes(job, points)
        return
    shrink_clearance(monkeypatch, MECHANISMS[robot])
    with pytest.raises(AssertionError, match=r"gap .* enclosure"):
        check_tiny_boxes(job, points)


def test_the_cli_writes_the_columns_labels_the_boxes_and_draws_the_map(cli, tmp_path):
    path = tmp_path / "i.toml"
    text = TEXTS["prr"].format(precision=4.0).replace("output", 'boxes_output = "b.csv"\noutput')
    path.write_text(text, encoding="utf-8")
    result = cli("workspace3prr", path, "--out-dir", tmp_path)
    assert result.exit_code == 0, result.output
    assert "interference-free (links 6 cm wide): area in [" in result.output
    with open(tmp_path / "a.csv", encoding="utf-8") as f:
        (row,) = list(csv.DictReader(f))
    assert float(row["leg_width_cm"]) == WIDTH_CM
    lo, hi = (float(row[f"interference_free_area_{k}_cm2"]) for k in ("inside", "kept"))
    assert 0 < lo <= hi
    with open(tmp_path / "b.csv", encoding="utf-8") as f:
        labels = {r["status"] for r in csv.DictReader(f)}
    assert {"interference-free", "interference-boundary"} <= labels


@pytest.mark.parametrize(
    ("kind", "text", "drop", "message"),
    [
        ("prr", PRR, "slider_modes = [1, 1, 1]\n", "slider_modes: is not set with leg_width_cm"),
        ("rrr", COMPACT, "elbow = [1, 1, 1]\n", "elbow: is not set with leg_width_cm"),
    ],
)
def test_a_range_without_its_working_mode_exits_2_with_one_line(
    cli, tmp_path, kind, text, drop, message
):
    path = tmp_path / "i.toml"
    path.write_text(
        text.format(precision=4.0, extra=EXTRA + RANGE).replace(drop, ""), encoding="utf-8"
    )
    command = "workspace" if kind == "rrr" else "workspace3prr"
    result = cli(command, path, "--out-dir", tmp_path)
    assert result.exit_code == 2, result.output
    assert result.output.startswith("error: ") and result.output.count("\n") == 1
    assert message in result.output
    assert not any(tmp_path.glob("*.csv"))


def test_a_range_with_a_tolerance_exits_2_with_one_line(cli, tmp_path):
    path = tmp_path / "i.toml"
    extra = EXTRA + RANGE + 'tolerance_cm = 0.1\ntolerance_mode = "all"\n'
    path.write_text(RPR.format(precision=4.0, extra=extra), encoding="utf-8")
    result = cli("workspace3rpr", path, "--out-dir", tmp_path)
    assert result.exit_code == 2, result.output
    assert result.output.startswith("error: ") and result.output.count("\n") == 1
    assert "orientation_deg: is (-5.0, 5.0) with a tolerance (expected one orientation)" in (
        result.output
    )

"""Certified worst-case accuracy over a range of orientations (``accuracy`` with
``orientation_deg = [lo, hi]``): a box's bounds hold the pose error of every robot within
the errors at every pose of the box and every φ of the range. Checked against the
Monte-Carlo robots of :mod:`tests.test_accuracy` (the independent Newton method of
:mod:`tests.accuracy_reference`) at nominal poses sampled over the box and across the range:
every sample inside the enclosure; over a narrow range at a regular point the enclosure
shrunk by 1 % fails (some sample outside it)."""

from __future__ import annotations

import csv

import numpy as np
import pytest

from planar_tui.workspace.paving.accuracy import HEADER
from tests.accuracy_reference import box_points, pose_errors
from tests.test_accuracy import (
    CENTROID,
    PRISMATIC,
    PRISMATIC_ERROR_CM,
    PRISMATIC_POINT,
    TABLE3,
    job_from_text,
    prr_model,
    rpr_model,
    rr_model,
    shrink,
)


def ranged_job(tmp_path, kind, phi_deg, error, precision=8.0, extra=""):
    """A job of ``kind`` (``rrr``, ``rpr``, ``prr``) over ``orientation_deg = phi_deg`` with
    actuator and tolerance errors ``error`` (deg and cm for the 3-RRR, cm otherwise)."""
    lo, hi = phi_deg
    orientation = f'orientation_deg = [{lo}, {hi}]\norientation_mode = "total"\n'
    if kind == "rrr":
        actuator, tolerance = error
        text = TABLE3.format(
            precision=precision, actuator=actuator, tolerance=tolerance, extra=orientation + extra
        )
        return job_from_text(tmp_path / "a.toml", text)
    modes = "slider_modes = [1, 1, 1]\n" if kind == "prr" else ""
    text = (
        PRISMATIC[kind]
        + orientation
        + modes
        + (
            f"precision_cm = {precision}\ngeometric_reference = false\n"
            f"accuracy = {{ actuator_cm = {error}, tolerance_cm = {error} }}\n"
            f'{extra}output = "{kind}.csv"\n'
        )
    )
    return job_from_text(tmp_path / f"{kind}.toml", text)


def model_at(kind, job):
    if kind == "rrr":
        return lambda pose: rr_model(job, pose)
    if kind == "rpr":
        return lambda pose: rpr_model(job, pose)
    return lambda pose: prr_model(job, pose, job.spec.slider_modes)


def enclosure(job, box):
    """The range evaluator's verdict and bounds over ``box``."""
    verdict, bound = job.spec.mechanism.accuracy(job.job, job.prepared)(np.array([box]))
    return verdict[0], bound[0]


def sampled(kind, job, box, count, extra_points, phis=9, seed=1):
    """The largest pose errors over ``count`` robots at the box's corners, centre and
    ``extra_points`` points, each at ``phis`` orientations across the range (its ends
    among them)."""
    rng = np.random.default_rng(seed)
    lo, hi = job.spec.orientation_deg
    points = [
        box_points(box, extra_points, rng, orientation=np.radians(phi))
        for phi in np.linspace(lo, hi, phis)
    ]
    return pose_errors(model_at(kind, job), np.concatenate(points), count, rng).max(axis=0)


CASES = {
    "rrr": (CENTROID, (0.05, 0.005)),
    "rpr": (PRISMATIC_POINT["rpr"], PRISMATIC_ERROR_CM["rpr"]),
    "prr": (PRISMATIC_POINT["prr"], PRISMATIC_ERROR_CM["prr"]),
}


@pytest.mark.parametrize("kind", ["rrr", "rpr", "prr"])
def test_every_robot_at_every_orientation_lies_inside_the_enclosure(tmp_path, kind):
    (x, y), error = CASES[kind]
    job = ranged_job(tmp_path, kind, (-2, 2), error)
    box = (x - 0.05, x + 0.05, y - 0.05, y + 0.05)
    verdict, bound = enclosure(job, box)
    assert verdict == 2 and np.all(np.isfinite(bound)), bound
    worst = sampled(kind, job, box, 300, 2)
    assert np.all(worst <= bound), (worst, bound)
    assert np.all(bound <= 5.0 * worst), (worst, bound)  # not vacuous


SMALL = {"rrr": (0.005, 0.0005), "rpr": 0.0005, "prr": 0.0005}


@pytest.mark.parametrize("kind", ["rrr", "rpr", "prr"])
def test_the_enclosure_over_a_narrow_range_is_sharp_and_fails_shrunk(tmp_path, kind):
    (x, y), _ = CASES[kind]
    job = ranged_job(tmp_path, kind, (0, 0.002), SMALL[kind])
    verdict, bound = enclosure(job, (x, x, y, y))
    assert verdict == 2
    worst = sampled(kind, job, (x, x, y, y), 200, 0, phis=5)
    assert np.all(worst <= bound), (worst, bound)
    assert np.all(bound <= 1.5 * worst), (bound, worst)
    assert np.any(worst > shrink(bound))


def test_the_job_writes_columns_and_labels_boxes_inside_their_enclosures(cli, tmp_path):
    error = PRISMATIC_ERROR_CM["prr"]
    job = ranged_job(tmp_path, "prr", (-2, 2), error, 4.0, 'boxes_output = "b.csv"\n')
    result = cli("workspace3prr", tmp_path / "prr.toml", "--out-dir", tmp_path)
    assert result.exit_code == 0, result.output
    assert "accuracy: |Δx| ≤" in result.output and "error map, x in [" in result.output
    with open(tmp_path / "prr.csv", encoding="utf-8") as f:
        (row,) = list(csv.DictReader(f))
    assert set(HEADER) <= set(row)
    assert float(row["accuracy_actuator_cm"]) == error
    assert float(row["accuracy_certified_area_cm2"]) > 0
    with open(tmp_path / "b.csv", encoding="utf-8") as f:
        rows = [r for r in csv.DictReader(f) if r["status"] == "accuracy-certified"]
    assert rows
    worst = max(rows, key=lambda r: float(r["dx_max_cm"]))
    box = tuple(float(worst[k]) for k in ("x_lo_cm", "x_hi_cm", "y_lo_cm", "y_hi_cm"))
    bound = [float(worst[k]) for k in ("dx_max_cm", "dy_max_cm", "dphi_max_deg")]
    errors = sampled("prr", job, box, 100, 2, phis=5)
    assert np.all(errors <= [bound[0], bound[1], np.radians(bound[2])])


@pytest.mark.parametrize(
    ("kind", "drop", "message"),
    [
        ("prr", "slider_modes = [1, 1, 1]\n", "slider_modes: is not set with accuracy"),
        ("rrr", "elbow = [1, -1, 1]\n", "elbow: is not set with accuracy"),
    ],
)
def test_a_range_without_its_working_mode_exits_2_with_one_line(cli, tmp_path, kind, drop, message):
    error = CASES[kind][1]
    ranged_job(tmp_path, kind, (-2, 2), error)  # the preset, written and valid
    path = next(tmp_path.glob("*.toml"))
    path.write_text(path.read_text(encoding="utf-8").replace(drop, ""), encoding="utf-8")
    command = "workspace" if kind == "rrr" else "workspace3prr"
    result = cli(command, path, "--out-dir", tmp_path)
    assert result.exit_code == 2, result.output
    assert result.output.startswith("error: ") and result.output.count("\n") == 1
    assert message in result.output
    assert not any(tmp_path.glob("*.csv"))


def test_a_range_with_a_tolerance_exits_2_with_one_line(cli, tmp_path):
    extra = 'tolerance_cm = 0.1\ntolerance_mode = "all"\n'
    ranged_job(tmp_path, "rpr", (-2, 2), 0.01)
    path = tmp_path / "rpr.toml"
    path.write_text(path.read_text(encoding="utf-8") + extra, encoding="utf-8")
    result = cli("workspace3rpr", path, "--out-dir", tmp_path)
    assert result.exit_code == 2, result.output
    assert result.output.startswith("error: ") and result.output.count("\n") == 1
    assert "orientation_deg: is (-2.0, 2.0) with a tolerance" in result.output

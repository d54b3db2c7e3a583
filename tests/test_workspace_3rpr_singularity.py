"""The 3-RPR's type II singularities and singularity-free circle (``singularities = true``):
the kept boxes hold every root of an independent float trace of det A = 0, the circle's
bracket holds the closed-form radius of the symmetric design, bad input."""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest

from planar_tui.batch import run_job
from planar_tui.presets import load_preset
from planar_tui.progress import Progress
from tests.test_workspace_3rpr import preset_text, refused

BASE = np.array([[0.0, 0.0], [120.0, 0.0], [60.0, 60.0 * math.sqrt(3.0)]])
PLATFORM = np.array([[0.0, 0.0], [40.0, 0.0], [20.0, 40.0]])


def det(x, y, phi_deg):
    """det A of the default design, independently: rows [v, v × r], v = C - A, r = R q."""
    c, s = math.cos(math.radians(phi_deg)), math.sin(math.radians(phi_deg))
    r = PLATFORM @ np.array([[c, s], [-s, c]])
    v = np.array([x, y]) + r - BASE
    return float(np.linalg.det(np.column_stack([v, v[:, 0] * r[:, 1] - v[:, 1] * r[:, 0]])))


def inside(x, y, phi_deg, lo=20.0, hi=80.0, margin=1e-6):
    c, s = math.cos(math.radians(phi_deg)), math.sin(math.radians(phi_deg))
    r = PLATFORM @ np.array([[c, s], [-s, c]])
    d = np.hypot(*(np.array([x, y]) + r - BASE).T)
    return bool(np.all(d >= lo + margin) and np.all(d <= hi - margin))


def run(tmp_path, phi):
    """The default design at ``phi`` with singularities about (30, 10), ε = 0.5 cm."""
    path = tmp_path / "s.toml"
    keys = f"orientation_deg = {phi}\nprecision_cm = 0.5\nsingularities = true\n"
    path.write_text(preset_text(job=keys + "circle_centre_cm = [30, 10]"), encoding="utf-8")
    (job,) = load_preset(path).jobs
    return run_job(job, Progress())


def test_the_symmetric_design_has_the_closed_form_circle(tmp_path):
    """At φ = 0 the default design is symmetric about x = 40 (legs 1 and 2 mirror each
    other, leg 3 on the axis: concurrent) and on y = 0 legs 1 and 2 are collinear: both
    lines are singular, so about (30, 10) r* = 10 cm (the workspace margin there is
    larger)."""
    result = run(tmp_path, 0.0)
    assert det(40.0, 17.0, 0.0) == pytest.approx(0.0, abs=1e-6)
    assert det(25.0, 0.0, 0.0) == pytest.approx(0.0, abs=1e-6)
    singular = result.singularity
    assert singular.radius_lo_cm <= 10.0 <= singular.radius_hi_cm
    assert singular.radius_hi_cm - singular.radius_lo_cm <= 2 * 0.5 * math.sqrt(2.0)
    row = dict(zip(result.table.header, result.table.rows[0], strict=True))
    assert row["circle_radius_lo_cm"] == singular.radius_lo_cm and row["elbow"] == ""


@pytest.mark.parametrize("phi", [0.0, 10.0, -25.0])
def test_every_root_of_a_float_trace_of_det_lies_in_a_kept_box(tmp_path, phi):
    result = run(tmp_path, phi)
    boxes = result.singularity.boxes
    roots = trace_roots(
        lambda x, y: det(x, y, phi), np.linspace(-25.0, 55.0, 17), np.linspace(-10.03, 90.01, 801)
    )  # off the axis x = 40
    roots = [(x, y) for x, y in roots if inside(x, y, phi)]
    if phi == 0.0:
        assert len(roots) >= 4  # the symmetry axis crosses the workspace
    assert_in_boxes(roots, boxes)


def trace_roots(det_of, ys, xs):
    """Roots of ``det_of(x, y)`` along each line ``y``: sign changes between neighbouring
    ``xs``, bisected in floats (``None``, a point off the workspace, stops a bracket)."""
    roots = []
    for y in ys:
        values = [det_of(x, y) for x in xs]
        for k in range(len(xs) - 1):
            a, b = values[k], values[k + 1]
            if a is None or b is None or a * b >= 0.0:
                continue
            lo, hi = xs[k], xs[k + 1]
            for _ in range(60):
                mid = 0.5 * (lo + hi)
                value = det_of(mid, y)
                if value is None:
                    break
                lo, hi = (mid, hi) if value * a > 0.0 else (lo, mid)
            else:
                roots.append((lo, y))
    return roots


def assert_in_boxes(points, boxes, tol=1e-6):
    """Every point lies in one of the rows ``x_lo, x_hi, y_lo, y_hi`` (within ``tol``)."""
    for x, y in points:
        hit = (
            (boxes[:, 0] - tol <= x)
            & (x <= boxes[:, 1] + tol)
            & (boxes[:, 2] - tol <= y)
            & (y <= boxes[:, 3] + tol)
        )
        assert hit.any(), (x, y)


def test_the_circle_holds_no_singular_or_unreachable_sample(tmp_path):
    result = run(tmp_path, 10.0)
    s = result.singularity
    cx, cy = s.centre_cm
    sign = np.sign(det(cx, cy, 10.0))
    rng = np.random.default_rng(3)
    for _ in range(2000):
        radius = s.radius_lo_cm * math.sqrt(rng.uniform())
        angle = rng.uniform(0, 2 * math.pi)
        x, y = cx + radius * math.cos(angle), cy + radius * math.sin(angle)
        assert inside(x, y, 10.0, margin=-1e-9) and np.sign(det(x, y, 10.0)) == sign


@pytest.mark.parametrize(
    ("job", "fragment"),
    [
        ("circle_centre_cm = [30, 10]", "circle_centre_cm: is set without singularities = true"),
        ("singularity_precision_cm = 1", "singularity_precision_cm: is set without"),
    ],
)
def test_circle_keys_need_singularities(cli, tmp_path, job, fragment):
    refused(cli, tmp_path, "workspace3rpr", preset_text(job=job), fragment)


@pytest.mark.parametrize(
    ("centre", "fragment"),
    [("[500, 500]", "is not inside the workspace"), ("[40, 20]", "on a type II singularity")],
)
def test_a_bad_centre_is_refused_before_anything_runs(cli, tmp_path, centre, fragment):
    text = preset_text(job=f"singularities = true\ncircle_centre_cm = {centre}")
    refused(cli, tmp_path, "workspace3rpr", text, fragment)


def test_the_command_writes_the_circle_columns(cli, tmp_path):
    preset = tmp_path / "s.toml"
    preset.write_text(
        preset_text(job="orientation_deg = 30\nsingularities = true"), encoding="utf-8"
    )
    result = cli("workspace3rpr", preset, "--out-dir", tmp_path)
    assert result.exit_code == 0, result.output
    with open(tmp_path / "o.csv", encoding="utf-8") as f:
        (row,) = list(csv.DictReader(f))
    assert float(row["circle_radius_lo_cm"]) <= float(row["circle_radius_hi_cm"])
    assert "singularity-free" in result.stdout

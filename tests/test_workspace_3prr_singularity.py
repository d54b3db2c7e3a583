"""The 3-PRR's type II singularities and singularity-free circle (``singularities = true``):
the kept boxes hold every root of an independent float trace of det A = 0 in the circle's
working modes, the circle holds no bad sample, bad input."""

from __future__ import annotations

import math

import numpy as np
import pytest

from planar_tui.batch import run_job
from planar_tui.presets import load_preset
from planar_tui.progress import Progress
from tests.test_workspace_3prr import preset_text
from tests.test_workspace_3rpr import refused
from tests.test_workspace_3rpr_singularity import assert_in_boxes, trace_roots

B = np.array([[0.0, 0.0], [120.0, 0.0], [60.0, 60.0 * math.sqrt(3.0)]])
U = np.array([[math.cos(math.radians(a)), math.sin(math.radians(a))] for a in (0, 120, 240)])
Q = np.array([[0.0, 0.0], [40.0, 0.0], [20.0, 40.0]])
STROKE, LENGTH = (10.0, 110.0), 40.0


def legs(x, y, modes):
    """The default design's distal links at (x, y) in ``modes`` (φ = 0), solving
    |C - B - s u|² = l² for s independently: ``None`` where a leg cannot close."""
    links = []
    for b, u, q, sigma in zip(B, U, Q, modes, strict=True):
        w = np.array([x, y]) + q - b
        a = w @ u
        disc = a * a - (w @ w - LENGTH**2)
        if disc < 0.0:
            return None
        s = a + sigma * math.sqrt(disc)
        if not STROKE[0] + 1e-6 <= s <= STROKE[1] - 1e-6:
            return None
        links.append(w - s * u)
    return links


def det(x, y, modes):
    links = legs(x, y, modes)
    if links is None:
        return None
    rows = [[d[0], d[1], d[0] * q[1] - d[1] * q[0]] for d, q in zip(links, Q, strict=True)]
    return float(np.linalg.det(np.array(rows)))


def run(tmp_path, job=""):
    path = tmp_path / "s.toml"
    path.write_text(
        preset_text(job="precision_cm = 0.5\nsingularities = true\n" + job).replace(
            "precision_cm = 1\n", ""
        ),
        encoding="utf-8",
    )
    (loaded,) = load_preset(path).jobs
    return run_job(loaded, Progress())


def test_every_root_of_a_float_trace_of_det_lies_in_a_kept_box(tmp_path):
    result = run(tmp_path)
    s = result.singularity
    modes = tuple(int(m) for m in s.elbow.split())
    roots = trace_roots(
        lambda x, y: det(x, y, modes), np.linspace(-15.0, 45.0, 25), np.linspace(-5.03, 90.01, 1201)
    )
    assert roots, "the trace found no singular pose: the test would prove nothing"
    assert_in_boxes(roots, s.boxes)


def test_the_circle_holds_no_bad_sample_and_its_bracket_is_narrow(tmp_path):
    result = run(tmp_path)
    s = result.singularity
    modes = tuple(int(m) for m in s.elbow.split())
    cx, cy = s.centre_cm
    sign = np.sign(det(cx, cy, modes))
    rng = np.random.default_rng(5)
    for _ in range(2000):
        radius = s.radius_lo_cm * math.sqrt(rng.uniform())
        angle = rng.uniform(0, 2 * math.pi)
        value = det(cx + radius * math.cos(angle), cy + radius * math.sin(angle), modes)
        assert value is not None and np.sign(value) == sign
    assert 0.0 < s.radius_hi_cm - s.radius_lo_cm <= 2 * 0.5 * math.sqrt(2.0)
    # r_out is an upper bound: a bad point (unreachable or opposite sign) lies within it
    angles = np.linspace(0.0, 2.0 * math.pi, 720, endpoint=False)
    r = s.radius_hi_cm + 1e-6
    bad = [det(cx + r * math.cos(t), cy + r * math.sin(t), modes) for t in angles]
    assert any(v is None or np.sign(v) != sign for v in bad) or s.radius_hi_cm > 1e3


@pytest.mark.parametrize(
    ("job", "fragment"),
    [
        ("slider_modes = [1, 1, 1]", "slider_modes: is set without singularities = true"),
        ("circle_centre_cm = [40, 20]", "circle_centre_cm: is set without singularities"),
        ("slider_modes = [1, 2, 1]", "workspace3prr[1].slider_modes"),
        ('singularities = true\nform = "geometric"', "singularities: is true with form"),
        ("singularities = true\ncircle_centre_cm = [500, 0]", "is not reachable"),
    ],
)
def test_bad_circle_keys_are_refused(cli, tmp_path, job, fragment):
    refused(cli, tmp_path, "workspace3prr", preset_text(job=job), fragment)

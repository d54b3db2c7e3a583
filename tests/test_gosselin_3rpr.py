"""The bundled 3-RPR of Gosselin, Sefrioui and Richard (1992), ``gosselin-3rpr``.

Its geometry is checked against the paper's own published result, independently of any of
planar-tui's kinematics: at leg lengths rho = (14.98, 15.38, 12) the robot has six real
assembly modes, at phi = -56.55, -2.71, 14.06, 33.56, 57.41 and 122.21 deg. Each is found
here by plain numpy (the platform position from legs 1 and 2 as a circle intersection, the
orientation as a root of leg 3's residual). Its workspace jobs are then run through the CLI
and their certified bracket compared with an independent grid bracket of the three annuli.
"""

from __future__ import annotations

import csv
import functools
import math

import numpy as np
import pytest

from planar_tui.presets import load_preset
from tests.conftest import PRESETS

PRESET = PRESETS / "gosselin-3rpr.toml"
#: The six real assembly modes at rho = (14.98, 15.38, 12) as published (deg).
PUBLISHED_MODES_DEG = (-56.55, -2.71, 14.06, 33.56, 57.41, 122.21)
LEG_LENGTHS = (14.98, 15.38, 12.0)


@functools.cache
def robot():
    return load_preset(PRESET).jobs[0].robot


def leg3_residuals(phi_rad: float) -> list[float]:
    """``|p - c3| - rho3`` for both positions ``p`` that close legs 1 and 2 at ``phi``
    (NaN where the two circles do not meet)."""
    r = robot()
    c, s = math.cos(phi_rad), math.sin(phi_rad)
    centres = [
        np.array([ax - (c * qx - s * qy), ay - (s * qx + c * qy)])
        for (ax, ay), (qx, qy) in zip(r.base_joints_cm, r.platform_points_cm, strict=True)
    ]
    d = float(np.linalg.norm(centres[1] - centres[0]))
    along = (LEG_LENGTHS[0] ** 2 - LEG_LENGTHS[1] ** 2 + d * d) / (2.0 * d)
    h2 = LEG_LENGTHS[0] ** 2 - along * along
    if h2 < 0.0:
        return [math.nan, math.nan]
    e = (centres[1] - centres[0]) / d
    foot, normal = centres[0] + along * e, np.array([-e[1], e[0]])
    return [
        float(np.linalg.norm(foot + side * math.sqrt(h2) * normal - centres[2]) - LEG_LENGTHS[2])
        for side in (1.0, -1.0)
    ]


def test_the_geometry_is_the_published_one():
    r = robot()
    (b1, b2, b3) = (np.array(p) for p in r.platform_points_cm)
    assert r.base_joints_cm == ((0.0, 0.0), (15.91, 0.0), (0.0, 10.0))
    assert np.linalg.norm(b2 - b1) == pytest.approx(17.04, abs=1e-9)
    assert np.linalg.norm(b3 - b1) == pytest.approx(20.84, abs=1e-5)
    assert np.linalg.norm(b3 - b2) == pytest.approx(16.54, abs=5e-3)
    angle = math.atan2(b3[1] - b1[1], b3[0] - b1[0]) - math.atan2(b2[1] - b1[1], b2[0] - b1[0])
    assert angle == pytest.approx(0.882603, abs=1e-6)


def test_six_real_assembly_modes_at_the_published_orientations():
    """Leg 3's residual, on either branch of legs 1 and 2, changes sign exactly six times
    over a turn, each within 0.02 deg of a published mode (the paper prints two decimals)."""
    phis = np.radians(np.arange(-180.0, 180.0, 0.01))
    residuals = np.array([leg3_residuals(phi) for phi in phis])
    roots = []
    for branch in (0, 1):
        f = residuals[:, branch]
        crossing = np.nonzero(np.isfinite(f[:-1]) & np.isfinite(f[1:]) & (f[:-1] * f[1:] < 0))
        for k in crossing[0]:
            t = f[k] / (f[k] - f[k + 1])
            roots.append(math.degrees(phis[k] + t * (phis[k + 1] - phis[k])))
    assert len(roots) == 6
    for found, published in zip(sorted(roots), PUBLISHED_MODES_DEG, strict=True):
        assert found == pytest.approx(published, abs=0.02)


def grid_bracket(phi_deg: float, limits_cm: tuple[float, float], cell_cm: float = 0.05):
    """Cells certainly inside and not certainly outside the three annuli: each leg's margin
    ``min(|p - c| - lo, hi - |p - c|)`` is 1-Lipschitz, so at a cell's centre it decides
    the cell when its size exceeds the half-diagonal."""
    r = robot()
    phi = math.radians(phi_deg)
    c, s = math.cos(phi), math.sin(phi)
    centres = [
        (ax - (c * qx - s * qy), ay - (s * qx + c * qy))
        for (ax, ay), (qx, qy) in zip(r.base_joints_cm, r.platform_points_cm, strict=True)
    ]
    lo, hi = limits_cm
    xs = np.arange(-40.0, 40.0, cell_cm) + 0.5 * cell_cm
    x, y = np.meshgrid(xs, xs, indexing="ij")
    margin = np.full(x.shape, np.inf)
    for cx, cy in centres:
        distance = np.hypot(x - cx, y - cy)
        margin = np.minimum(margin, np.minimum(distance - lo, hi - distance))
    half_diagonal = cell_cm * math.sqrt(0.5)
    area = cell_cm * cell_cm
    return area * np.count_nonzero(margin > half_diagonal), area * np.count_nonzero(
        margin >= -half_diagonal
    )


@pytest.mark.parametrize(("output", "phi_deg"), [("gosselin-3rpr.csv", 0.0)])
def test_the_workspace_bracket_agrees_with_an_independent_grid(cli, tmp_path, output, phi_deg):
    result = cli("workspace3rpr", PRESET, "--job", output, "--out-dir", tmp_path, "--no-map")
    assert result.exit_code == 0, result.output
    with open(tmp_path / output, newline="", encoding="utf-8") as handle:
        (row,) = list(csv.DictReader(handle))
    inside, kept = float(row["area_inside_cm2"]), float(row["area_kept_cm2"])
    exact = float(row["area_geometric_cm2"])
    grid_inside, grid_kept = grid_bracket(phi_deg, (5.0, 25.0))
    assert inside <= exact <= kept
    assert grid_inside <= exact <= grid_kept
    # The two certified brackets enclose the same area, so they overlap.
    assert max(inside, grid_inside) <= min(kept, grid_kept)
    assert kept - inside < 0.01 * exact

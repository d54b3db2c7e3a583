"""Direct kinematics of the four parallel robots (``Mechanism.direct_kinematics``).

Checked against the published assembly modes of the bundled Gosselin 3-RPR, against an
independent dense sign-change scan of leg 3's residual (the modes it finds are all found,
so the polynomial misses none), and by round trips: a random pose's inverse kinematics
(written here in plain numpy, one elbow or slider branch chosen at random) gives actuator
values whose direct kinematics holds that pose, and every mode returned closes every leg.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from planar_tui.kernels.direct_kinematics import circle_intersections, three_distance_poses

from planar_tui.presets import load_preset
from planar_tui.workspace.fivebar.mechanism import MECHANISM as FIVEBAR
from planar_tui.workspace.fivebar.robot import Robot5R
from planar_tui.workspace.prr.mechanism import MECHANISM as PRR
from planar_tui.workspace.prr.robot import Robot3PRR
from planar_tui.workspace.rpr.mechanism import MECHANISM as RPR
from planar_tui.workspace.rpr.robot import Robot3RPR
from planar_tui.workspace.rrr.mechanism import MECHANISM as RRR
from planar_tui.workspace.rrr.robot import Robot3RRR
from tests.conftest import PRESETS

PUBLISHED_MODES_DEG = (-56.55, -2.71, 14.06, 33.56, 57.41, 122.21)


def rotate(phi: float, q) -> np.ndarray:
    c, s = math.cos(phi), math.sin(phi)
    q = np.asarray(q, dtype=float)
    return np.array([c * q[0] - s * q[1], s * q[0] + c * q[1]])


def platform_points(pose, points) -> list[np.ndarray]:
    """:math:`C_i = p + R(\\varphi) q_i`."""
    x, y, phi = pose
    return [np.array([x, y]) + rotate(phi, q) for q in points]


def holds(poses: np.ndarray, pose, tol: float = 1e-7) -> bool:
    """Whether ``pose`` is one of ``poses`` (angles compared around the circle)."""
    return any(
        np.max(np.abs(p[:2] - pose[:2])) < tol
        and abs(math.remainder(p[2] - pose[2], 2 * math.pi)) < tol
        for p in poses
    )


def test_gosselin_six_modes_at_the_published_orientations():
    robot = load_preset(PRESETS / "gosselin-3rpr.toml").jobs[0].robot
    poses = RPR.direct_kinematics(robot, (14.98, 15.38, 12.0))
    assert poses.shape == (6, 3)
    for found, published in zip(np.degrees(poses[:, 2]), PUBLISHED_MODES_DEG, strict=True):
        assert found == pytest.approx(published, abs=0.01)
    for pose in poses:
        lengths = [
            np.linalg.norm(c - np.asarray(a))
            for c, a in zip(
                platform_points(pose, robot.platform_points_cm), robot.base_joints_cm, strict=True
            )
        ]
        np.testing.assert_allclose(lengths, (14.98, 15.38, 12.0), rtol=0, atol=1e-10)


def scan_roots(bases, points, distances) -> list[float]:
    """Orientations where leg 3's residual changes sign, legs 1 and 2 closed by a circle
    intersection (either branch), on a 0.005 deg grid: an independent, possibly
    incomplete, list of the modes."""
    bases, points = np.asarray(bases, float), np.asarray(points, float)
    phis = np.radians(np.arange(-180.0, 180.0, 0.005))
    rows = []
    for phi in phis:
        c1 = bases[0] - rotate(phi, points[0])
        c2 = bases[1] - rotate(phi, points[1])
        d = np.linalg.norm(c2 - c1)
        along = (distances[0] ** 2 - distances[1] ** 2 + d * d) / (2 * d)
        h2 = distances[0] ** 2 - along**2
        if h2 < 0:
            rows.append((math.nan, math.nan))
            continue
        e = (c2 - c1) / d
        n = np.array([-e[1], e[0]])
        c3 = bases[2] - rotate(phi, points[2])
        rows.append(
            tuple(
                np.linalg.norm(c1 + along * e + side * math.sqrt(h2) * n - c3) - distances[2]
                for side in (1.0, -1.0)
            )
        )
    f = np.array(rows)
    roots = []
    for branch in (0, 1):
        g = f[:, branch]
        for k in np.nonzero(np.isfinite(g[:-1]) & np.isfinite(g[1:]) & (g[:-1] * g[1:] < 0))[0]:
            roots.append(phis[k] - g[k] * (phis[k + 1] - phis[k]) / (g[k + 1] - g[k]))
    return roots


@pytest.mark.parametrize("seed", range(4))
def test_every_scanned_mode_is_found(seed):
    rng = np.random.default_rng(seed)
    bases = rng.uniform(-10, 10, (3, 2))
    points = rng.uniform(-6, 6, (3, 2))
    pose = (rng.uniform(-3, 3), rng.uniform(-3, 3), rng.uniform(-math.pi, math.pi))
    distances = [
        np.linalg.norm(c - b) for c, b in zip(platform_points(pose, points), bases, strict=True)
    ]
    poses = three_distance_poses(bases, points, distances)
    assert holds(poses, pose)
    scanned = scan_roots(bases, points, distances)
    assert len(poses) >= len(scanned) >= 1
    for phi in scanned:
        assert min(abs(math.remainder(phi - p, 2 * math.pi)) for p in poses[:, 2]) < 1e-4


def test_no_mode_when_the_legs_cannot_close():
    bases = [[0.0, 0.0], [10.0, 0.0], [0.0, 10.0]]
    assert three_distance_poses(bases, [[0, 0], [1, 0], [0, 1]], [1.0, 1.0, 1.0]).shape == (0, 3)


@pytest.mark.parametrize("seed", range(5))
def test_3rpr_round_trip(seed):
    rng = np.random.default_rng(100 + seed)
    robot = Robot3RPR()
    pose = (rng.uniform(40, 80), rng.uniform(20, 50), rng.uniform(-0.6, 0.6))
    rho = [
        np.linalg.norm(c - np.asarray(a))
        for c, a in zip(
            platform_points(pose, robot.platform_points_cm), robot.base_joints_cm, strict=True
        )
    ]
    poses = RPR.direct_kinematics(robot, rho)
    assert holds(poses, pose)
    for other in poses:
        again = [
            np.linalg.norm(c - np.asarray(a))
            for c, a in zip(
                platform_points(other, robot.platform_points_cm), robot.base_joints_cm, strict=True
            )
        ]
        np.testing.assert_allclose(again, rho, rtol=1e-11)


@pytest.mark.parametrize("seed", range(5))
def test_3rrr_round_trip(seed):
    rng = np.random.default_rng(200 + seed)
    robot = Robot3RRR()
    l1, l2 = robot.proximal_cm, robot.distal_cm
    # about the centred pose (40, 21, 0): the platform's centroid over the base's
    pose = (rng.uniform(35, 45), rng.uniform(16, 26), rng.uniform(-0.3, 0.3))
    thetas = []
    for c, a in zip(
        platform_points(pose, robot.platform_points_cm()), robot.base_joints_cm(), strict=True
    ):
        v = c - np.asarray(a)
        r, alpha = np.linalg.norm(v), math.atan2(v[1], v[0])
        beta = math.acos((r * r + l1 * l1 - l2 * l2) / (2 * l1 * r))
        thetas.append(alpha + rng.choice((-1.0, 1.0)) * beta)
    poses = RRR.direct_kinematics(robot, thetas)
    assert holds(poses, pose)
    for other in poses:
        for c, a, theta in zip(
            platform_points(other, robot.platform_points_cm()),
            robot.base_joints_cm(),
            thetas,
            strict=True,
        ):
            elbow = np.asarray(a) + l1 * np.array([math.cos(theta), math.sin(theta)])
            assert np.linalg.norm(c - elbow) == pytest.approx(l2, rel=1e-11)


@pytest.mark.parametrize("seed", range(5))
def test_3prr_round_trip(seed):
    rng = np.random.default_rng(300 + seed)
    robot = Robot3PRR()
    pose = (rng.uniform(45, 55), rng.uniform(25, 35), rng.uniform(-0.3, 0.3))
    strokes = []
    for c, b, angle, length in zip(
        platform_points(pose, robot.platform_points_cm),
        robot.slider_points_cm,
        robot.slider_angles_deg,
        robot.distal_cm,
        strict=True,
    ):
        u = np.array([math.cos(math.radians(angle)), math.sin(math.radians(angle))])
        w = c - np.asarray(b)
        along, across = w @ u, w[0] * u[1] - w[1] * u[0]
        strokes.append(
            along + rng.choice((-1.0, 1.0)) * math.sqrt(length * length - across * across)
        )
    poses = PRR.direct_kinematics(robot, strokes)
    assert holds(poses, pose)
    for other in poses:
        for c, b, angle, s, length in zip(
            platform_points(other, robot.platform_points_cm),
            robot.slider_points_cm,
            robot.slider_angles_deg,
            strokes,
            robot.distal_cm,
            strict=True,
        ):
            joint = np.asarray(b) + s * np.array(
                [math.cos(math.radians(angle)), math.sin(math.radians(angle))]
            )
            assert np.linalg.norm(c - joint) == pytest.approx(length, rel=1e-11)


@pytest.mark.parametrize("seed", range(5))
def test_fivebar_round_trip_two_modes(seed):
    rng = np.random.default_rng(400 + seed)
    robot = Robot5R()
    point = np.array([rng.uniform(-20, 20), rng.uniform(50, 80)])
    thetas = []
    for a, l1, l2 in zip(robot.base_joints_cm(), robot.proximal_cm, robot.distal_cm, strict=True):
        v = point - np.asarray(a)
        r, alpha = np.linalg.norm(v), math.atan2(v[1], v[0])
        thetas.append(
            alpha + rng.choice((-1.0, 1.0)) * math.acos((r * r + l1 * l1 - l2 * l2) / (2 * l1 * r))
        )
    points = FIVEBAR.direct_kinematics(robot, thetas)
    assert points.shape == (2, 2)
    assert min(np.linalg.norm(p - point) for p in points) < 1e-9
    elbows = [
        np.asarray(a) + l1 * np.array([math.cos(t), math.sin(t)])
        for a, l1, t in zip(robot.base_joints_cm(), robot.proximal_cm, thetas, strict=True)
    ]
    for p in points:
        np.testing.assert_allclose(
            [np.linalg.norm(p - e) for e in elbows], robot.distal_cm, rtol=1e-12
        )


def test_circle_intersections_tangent_and_apart():
    np.testing.assert_allclose(circle_intersections((0, 0), 1.0, (2, 0), 1.0), [[1.0, 0.0]])
    assert circle_intersections((0, 0), 1.0, (3, 0), 1.0).shape == (0, 2)
    np.testing.assert_allclose(
        circle_intersections((0, 0), 5.0, (6, 0), 5.0), [[3.0, 4.0], [3.0, -4.0]]
    )


def test_the_eliminant_has_degree_three_so_at_most_six_modes():
    """F(phi) sampled at 64 angles has no harmonic above 3: the degree-4 terms cancel
    (the spurious roots z = 0, infinity), leaving Gosselin's sextic."""
    from planar_tui.kernels.direct_kinematics import _eliminant

    rng = np.random.default_rng(11)
    for _ in range(5):
        bases, points = rng.uniform(-1, 1, (3, 2)), rng.uniform(-1, 1, (3, 2))
        values = _eliminant(2 * np.pi * np.arange(64) / 64, bases, points, rng.uniform(0.5, 1.5, 3))
        harmonics = np.abs(np.fft.rfft(values)) / 64
        assert harmonics[3] > 1e-6 * harmonics.max()
        assert harmonics[4:].max() < 1e-12 * harmonics.max()

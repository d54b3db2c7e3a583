"""``Mechanism.linkage``, the robots' bodies the app's path tabs draw, and their scene:
at actuator values and every assembly mode the direct kinematics (an independent solver)
finds for them, each leg of the drawing has its link lengths (the 3-RRR's and five-bar's
distal links, the 3-RPR's leg length ρ_i, the 3-PRR's link from its slider on its rail),
its actuated joint where the actuator puts it, and the scene draws every joint."""

from __future__ import annotations

import math

import numpy as np
import pytest

from planar_tui.app.widgets.path_pane import linkage_scene
from planar_tui.app.widgets.robot_drawing import render_scene
from planar_tui.workspace.fivebar.mechanism import MECHANISM as FIVEBAR
from planar_tui.workspace.fivebar.robot import Robot5R
from planar_tui.workspace.prr.mechanism import MECHANISM as PRR
from planar_tui.workspace.prr.robot import Robot3PRR
from planar_tui.workspace.rpr.mechanism import MECHANISM as RPR
from planar_tui.workspace.rpr.robot import Robot3RPR
from planar_tui.workspace.rrr.mechanism import MECHANISM as RRR
from planar_tui.workspace.rrr.robot import Robot3RRR


def distance(p, q) -> float:
    return math.hypot(p[0] - q[0], p[1] - q[1])


def on_platform(pose, platform, points_cm) -> None:
    """The platform joints are the platform points at ``pose``: their distances to the
    platform's origin and to each other are the platform frame's."""
    origin = pose[:2]
    for c, q in zip(platform, points_cm, strict=True):
        assert distance(c, origin) == pytest.approx(math.hypot(*q), abs=1e-9)
    for i in range(3):
        j = (i + 1) % 3
        assert distance(platform[i], platform[j]) == pytest.approx(
            distance(points_cm[i], points_cm[j]), abs=1e-9
        )


def test_3rrr_legs_close_with_their_link_lengths_in_every_assembly_mode():
    robot = Robot3RRR()
    thetas = (math.radians(40), math.radians(140), math.radians(265))
    poses = RRR.direct_kinematics(robot, thetas)
    assert len(poses)
    for pose in poses:
        linkage = RRR.linkage(robot, pose, thetas)
        assert linkage.frame == ((*robot.base_joints_cm(), robot.base_joints_cm()[0]),)
        on_platform(pose, linkage.platform, robot.platform_points_cm())
        for (a, b, c), theta, base in zip(
            linkage.legs, thetas, robot.base_joints_cm(), strict=True
        ):
            assert a == base
            assert distance(a, b) == pytest.approx(robot.proximal_cm, rel=1e-12)
            assert math.atan2(b[1] - a[1], b[0] - a[0]) == pytest.approx(
                math.remainder(theta, 2 * math.pi), abs=1e-12
            )
            assert distance(b, c) == pytest.approx(robot.distal_cm, rel=1e-9)


def test_fivebar_legs_meet_at_the_end_point():
    robot = Robot5R()
    thetas = (math.radians(80), math.radians(100))
    for point in FIVEBAR.direct_kinematics(robot, thetas):
        linkage = FIVEBAR.linkage(robot, point, thetas)
        assert linkage.platform == ()
        for (a, b, p), l1, l2 in zip(linkage.legs, robot.proximal_cm, robot.distal_cm, strict=True):
            assert p == pytest.approx(tuple(point), abs=1e-12)
            assert distance(a, b) == pytest.approx(l1, rel=1e-12)
            assert distance(b, p) == pytest.approx(l2, rel=1e-9)


def test_3rpr_legs_have_the_actuated_lengths():
    robot = Robot3RPR()
    rho = (45.0, 50.0, 42.0)
    poses = RPR.direct_kinematics(robot, rho)
    assert len(poses)
    for pose in poses:
        linkage = RPR.linkage(robot, pose, rho)
        on_platform(pose, linkage.platform, robot.platform_points_cm)
        for (a, c), length in zip(linkage.legs, rho, strict=True):
            assert distance(a, c) == pytest.approx(length, rel=1e-9)


def test_3prr_sliders_sit_on_their_rails_and_links_have_their_lengths():
    robot = Robot3PRR()
    strokes = (50.0, 55.0, 60.0)
    poses = PRR.direct_kinematics(robot, strokes)
    assert len(poses)
    for pose in poses:
        linkage = PRR.linkage(robot, pose, strokes)
        on_platform(pose, linkage.platform, robot.platform_points_cm)
        for (s, c), rail, b, (lo, hi), stroke, length in zip(
            linkage.legs,
            linkage.frame,
            robot.slider_points_cm,
            robot.strokes_cm,
            strokes,
            robot.distal_cm,
            strict=True,
        ):
            assert distance(rail[0], b) == pytest.approx(lo, rel=1e-12)
            assert distance(rail[1], b) == pytest.approx(hi, rel=1e-12)
            assert distance(s, b) == pytest.approx(stroke, rel=1e-12)
            assert distance(rail[0], s) + distance(s, rail[1]) == pytest.approx(hi - lo)
            assert distance(s, c) == pytest.approx(length, rel=1e-9)


def test_the_scene_draws_every_joint_and_moves_with_the_pose():
    robot = Robot3RRR()
    thetas = (math.radians(40), math.radians(140), math.radians(265))
    pose = RRR.direct_kinematics(robot, thetas)[0]
    extent = (-0.2, 1.4, -0.4, 1.2)
    text = "\n".join(
        render_scene(linkage_scene(RRR.linkage(robot, pose, thetas), extent, ""), 60, 24).lines()
    )
    assert text.count("#") == 3 and text.count("o") == 3 and text.count("*") == 3
    point = FIVEBAR.direct_kinematics(Robot5R(), (math.radians(80), math.radians(100)))[0]
    five = linkage_scene(FIVEBAR.linkage(Robot5R(), point, (1.4, 1.75)), extent, "")
    assert [glyph for _, glyph, _ in five.joints] == ["#", "o", "#", "o", "+"]
    moved = RRR.linkage(robot, np.add(pose, [2.0, 0.0, 0.0]), thetas)
    assert moved.platform[0][0] == pytest.approx(
        RRR.linkage(robot, pose, thetas).platform[0][0] + 2.0
    )

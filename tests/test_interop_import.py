"""Import of URDF and MJCF as a ``[robot]``: exact round trips of exports, two hand-written
menagerie-style MJCF models checked against MuJoCo itself, and every refusal in one line."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest
from planar_tui.kernels.dynamics import inverse_dynamics

from planar_tui.dynamics.robot import SerialRobot
from planar_tui.errors import PresetError
from planar_tui.interop.mjcf import robot_mjcf
from planar_tui.interop.robot_import import read_robot
from planar_tui.interop.urdf import robot_urdf
from tests.conftest import REPO
from tests.test_dynamics_kernels import random_state

DATA = REPO / "tests" / "data" / "interop"
EXPORTERS = {"xml": robot_mjcf, "urdf": robot_urdf}


def written(tmp_path, text: str, suffix: str):
    path = tmp_path / f"robot.{suffix}"
    path.write_text(text, encoding="utf-8")
    return path


@pytest.mark.parametrize("suffix", ["xml", "urdf"])
def test_export_then_import_gives_back_the_robot_exactly(tmp_path, suffix):
    rng = np.random.default_rng(7)
    robots = [
        SerialRobot(lengths_m=(0.3, 0.7), masses_kg=(1.0, 2.5)),  # rod inertias, no name
        SerialRobot(
            lengths_m=(0.1,),
            masses_kg=(3.0,),
            inertias_kgm2=(0.2,),
            gravity_m_s2=0.0,
            name='arm "A" & <b>',
        ),
        SerialRobot(
            lengths_m=(1e-3, 1e3, 0.1 + 0.2),
            masses_kg=(1e-4, 5e2, 1 / 3),
            inertias_kgm2=(1e-9, 1e5, math.pi),
            gravity_m_s2=3.71,
            name="3R",
        ),
    ]
    for n in (4, 17, 50, 1200):  # 1200: deeper than Python's recursion limit
        robots.append(
            SerialRobot(
                lengths_m=tuple(rng.uniform(0.01, 5.0, n)),
                masses_kg=tuple(rng.uniform(0.01, 9, n)),
                inertias_kgm2=tuple(rng.uniform(1e-4, 3.0, n)),
                gravity_m_s2=float(rng.uniform(0, 20)),
            )
        )
    for robot in robots:
        imported = read_robot(written(tmp_path, EXPORTERS[suffix](robot), suffix))
        expected = robot if robot.name != "3R" else SerialRobot(**{**robot.__dict__, "name": ""})
        assert imported.robot == expected
        assert imported.offsets_deg == (0.0,) * robot.n_links
        assert imported.notes == ()


def mujoco_matches_preset(path, imported, states=8):
    """MuJoCo's inverse dynamics of the file at q equals planar-tui's of the preset at
    θ = q + Δ, damping and joint limits (not kept by the preset) switched off."""
    model = mujoco.MjModel.from_xml_path(str(path))
    model.dof_damping[:] = 0.0
    model.opt.disableflags |= mujoco.mjtDisableBit.mjDSBL_LIMIT
    data = mujoco.MjData(model)
    robot = imported.robot
    offsets = np.radians(imported.offsets_deg)
    rng = np.random.default_rng(11)
    for _ in range(states):
        q, omega, alpha = random_state(rng, robot.n_links)
        data.qpos[:], data.qvel[:], data.qacc[:] = q, omega, alpha
        mujoco.mj_inverse(model, data)
        tau = inverse_dynamics(*robot.arrays(), robot.gravity_m_s2, q + offsets, omega, alpha)
        assert np.abs(data.qfrc_inverse - tau).max() <= 1e-10 * np.abs(tau).max()


def test_a_reacher_style_model_imports_as_a_horizontal_two_link_arm():
    path = DATA / "reacher.xml"
    imported = read_robot(path)
    assert imported.robot == SerialRobot(
        lengths_m=(0.12, 0.1),
        masses_kg=(0.2, 0.15),
        inertias_kgm2=(2.5e-4, 1.25e-4),
        gravity_m_s2=0.0,
        name="reacher",
    )
    assert imported.offsets_deg == (0.0, 0.0)
    notes = " | ".join(imported.notes)
    assert "horizontal plane" in notes and "range -160 160 is not kept" in notes
    mujoco_matches_preset(path, imported)


def test_an_acrobot_style_model_imports_with_its_angle_offsets():
    path = DATA / "acrobot.xml"
    imported = read_robot(path)
    robot = imported.robot
    assert (robot.lengths_m, robot.masses_kg, robot.gravity_m_s2) == ((1.0, 1.2), (1.3, 0.8), 9.81)
    np.testing.assert_allclose(robot.inertias_kgm2, (0.11, 0.1), rtol=1e-14)
    # links up at zero, the mount turned 30° towards +x: 90° + 30° from the plane's x axis
    # the elbow drawn at its reference angle 0.5 rad: θ2 = q2 - 0.5 rad
    np.testing.assert_allclose(imported.offsets_deg, (120.0, -np.degrees(0.5)), atol=1e-12)
    assert "theta_i = q_i + [120, -28.6479] deg" in " ".join(imported.notes)
    mujoco_matches_preset(path, imported)


MJCF_2R = robot_mjcf(SerialRobot(lengths_m=(0.5, 0.4), masses_kg=(1.0, 1.0)))
URDF_2R = robot_urdf(SerialRobot(lengths_m=(0.5, 0.4), masses_kg=(1.0, 1.0)))


def edited(text: str, old: str, new: str, count: int = 1) -> str:
    assert old in text, old
    return text.replace(old, new, count)


REFUSALS = {
    "mjcf slide joint": (
        "xml",
        edited(MJCF_2R, '"joint2" type="hinge"', '"joint2" type="slide"'),
        '<joint name="joint2">: is a slide joint',
    ),
    "mjcf free joint": (
        "xml",
        edited(
            MJCF_2R, '<joint name="joint1" type="hinge" axis="0 0 1" pos="0 0 0"/>', "<freejoint/>"
        ),
        "<freejoint>: is a free joint",
    ),
    "mjcf axes not parallel": (
        "xml",
        edited(MJCF_2R, '"joint2" type="hinge" axis="0 0 1"', '"joint2" type="hinge" axis="0 1 1"'),
        "is not parallel to the first joint's (0, 0, 1)",
    ),
    "mjcf opposite axes": (
        "xml",
        edited(
            MJCF_2R, '"joint2" type="hinge" axis="0 0 1"', '"joint2" type="hinge" axis="0 0 -1"'
        ),
        "is not parallel to the first joint's",
    ),
    "mjcf centre of mass off the line": (
        "xml",
        edited(MJCF_2R, '<inertial pos="0.25 0.0 0.0"', '<inertial pos="0.25 0.01 0.0"'),
        'line 17: <body name="link1">: centre of mass 0.01 m off the link line',
    ),
    "mjcf centre of mass not at mid-link": (
        "xml",
        edited(MJCF_2R, '<inertial pos="0.25 0.0 0.0"', '<inertial pos="0.2 0.0 0.0"'),
        "centre of mass at 40 % of the link from its joint",
    ),
    "mjcf branched tree": (
        "xml",
        edited(
            MJCF_2R,
            '<body name="link2"',
            '<body name="twig"><joint type="hinge"/><inertial pos="0.1 0 0" mass="1" '
            'diaginertia="1 1 1"/></body><body name="link2"',
        ),
        '<body name="link2">: is a second moving chain below <body name="link1">: a branched tree',
    ),
    "mjcf two joints in a body": (
        "xml",
        edited(MJCF_2R, '<joint name="joint2"', '<joint name="extra"/><joint name="joint2"'),
        '<body name="link2">: has 2 joints',
    ),
    "mjcf no inertial": (
        "xml",
        edited(MJCF_2R, '<inertial pos="0.2 0.0 0.0"', '<site pos="0.2 0.0 0.0"'),
        '<body name="link2">: has no <inertial> (inertia from geoms is not computed)',
    ),
    "mjcf welded mass": (
        "xml",
        edited(
            MJCF_2R,
            '<site name="tip"',
            '<body name="gripper"><inertial pos="0 0 0" mass="0.3" diaginertia="1 1 1"/>'
            '</body><site name="tip"',
        ),
        '<body name="gripper">: has a mass welded to',
    ),
    "mjcf closed loop": (
        "xml",
        edited(
            MJCF_2R,
            "</mujoco>",
            '<equality><connect body1="link1" body2="link2" anchor="0 0 0"/></equality></mujoco>',
        ),
        "<equality>: closed loops or couplings are not a serial chain",
    ),
    "mjcf masses from geoms": (
        "xml",
        edited(MJCF_2R, 'inertiafromgeom="false"', 'inertiafromgeom="true"'),
        '<compiler>: inertiafromgeom is "true": the masses are the geoms\', which are not read',
    ),
    "mjcf total mass": (
        "xml",
        edited(MJCF_2R, 'inertiafromgeom="false"', 'inertiafromgeom="false" settotalmass="3"'),
        "settotalmass changes the masses MuJoCo uses",
    ),
    "mjcf include": (
        "xml",
        edited(MJCF_2R, "<worldbody>", '<include file="other.xml"/><worldbody>'),
        "<include>: other files are not read",
    ),
    "urdf prismatic joint": (
        "urdf",
        edited(URDF_2R, '"joint2" type="continuous"', '"joint2" type="prismatic"'),
        '<joint name="joint2">: is a prismatic joint',
    ),
    "urdf floating joint": (
        "urdf",
        edited(URDF_2R, '"joint1" type="continuous"', '"joint1" type="floating"'),
        "is a floating joint",
    ),
    "urdf axes not parallel": (
        "urdf",
        edited(URDF_2R, '<axis xyz="0 0 1"/>', '<axis xyz="1 0 0"/>', 2).replace(
            '<axis xyz="1 0 0"/>', '<axis xyz="0 0 1"/>', 1
        ),
        "is not parallel to the first joint's (0, 0, 1)",
    ),
    "urdf centre of mass off the line": (
        "urdf",
        edited(
            URDF_2R,
            '<origin xyz="0.2 0.0 0.0" rpy="0 0 0"/>',
            '<origin xyz="0.2 0.0 0.0" rpy="0 0 0.3"/>',
        ).replace('<origin xyz="0.25 0.0 0.0"', '<origin xyz="0.25 -0.02 0.0"'),
        '<link name="link1">: centre of mass 0.02 m off the link line',
    ),
    "urdf branched tree": (
        "urdf",
        edited(
            URDF_2R,
            "</robot>",
            '<link name="twig"><inertial><mass value="1"/><inertia ixx="1" iyy="1" '
            'izz="1"/></inertial></link><joint name="twig" type="revolute"><parent '
            'link="link1"/><child link="twig"/><axis xyz="0 0 1"/></joint></robot>',
        ),
        "a branched tree",
    ),
    "doctype": (
        "urdf",
        edited(URDF_2R, "<robot", '<!DOCTYPE robot [<!ENTITY len "0.5">]>\n<robot'),
        "line 13: has a DOCTYPE declaration: refused, entities are never expanded",
    ),
    "entity without doctype": (
        "xml",
        edited(MJCF_2R, "<mujoco", '<!ENTITY x SYSTEM "file:///etc/passwd">\n<mujoco'),
        "has a ENTITY declaration: refused",
    ),
    "not xml": ("xml", "<mujoco><worldbody></mujoco>", "line 1: is not well-formed XML"),
    "not a model": ("xml", "<svg/>", "<svg>: is not an MJCF <mujoco> model"),
}


@pytest.mark.parametrize("case", sorted(REFUSALS))
def test_each_refusal_is_one_line_naming_the_element(tmp_path, case):
    suffix, text, expected = REFUSALS[case]
    path = written(tmp_path, text, suffix)
    with pytest.raises(PresetError) as caught:
        read_robot(path)
    message = str(caught.value)
    assert "\n" not in message
    assert message.startswith(f"error: {path}: ")
    assert expected in message, message


@pytest.mark.parametrize(
    ("orientation", "sequence"),
    [
        ('euler="20 -35 50"', "xyz"),
        ('euler="20 -35 50"', "XYZ"),
        ('euler="-70 15 110"', "zyx"),
        ('axisangle="1 2 3 40"', "xyz"),
        ('xyaxes="0.3 1 0.2 -1 0.1 0.4"', "xyz"),
        ('zaxis="0.2 -0.5 1"', "xyz"),
        ('quat="0.3 -0.4 0.5 0.6"', "xyz"),
    ],
)
def test_an_arm_on_a_turned_mount_imports_with_gravitys_in_plane_part(
    tmp_path, orientation, sequence
):
    """The exported arm under a mount body turned every way MJCF can say it (MuJoCo's
    gravity along -z): the plane tilts, the preset keeps gravity's in-plane part and the
    angle offsets; MuJoCo's inverse dynamics of the file agree with the preset's."""
    robot = SerialRobot(
        lengths_m=(0.5, 0.3, 0.4), masses_kg=(1.0, 0.7, 0.4), inertias_kgm2=(0.03, 0.01, 0.02)
    )
    text = robot_mjcf(robot)
    text = edited(text, 'angle="radian"', f'angle="degree" eulerseq="{sequence}"')
    text = edited(text, '<option gravity="0.0 -9.81 0.0"/>', "")
    text = edited(
        text, "<worldbody>", f'<worldbody><body name="mount" pos="0.1 0.2 0.3" {orientation}>'
    )
    text = edited(text, "</worldbody>", "</body></worldbody>")
    path = written(tmp_path, text, "xml")
    imported = read_robot(path)
    assert imported.robot.lengths_m == pytest.approx(robot.lengths_m, rel=1e-14)
    assert imported.robot.masses_kg == robot.masses_kg
    assert 0.0 < imported.robot.gravity_m_s2 < 9.81
    mujoco_matches_preset(path, imported)


def test_a_urdf_arm_on_a_turned_base_joint_matches_pinocchio(tmp_path):
    """The exported URDF without planar-tui's gravity element (so ROS's -z is assumed, as
    Pinocchio assumes) and its first joint turned by rpy: Pinocchio's rnea of the file at q
    equals the preset's inverse dynamics at θ = q + Δ."""
    import pinocchio

    robot = SerialRobot(lengths_m=(0.5, 0.3), masses_kg=(1.0, 0.7), inertias_kgm2=(0.03, 0.01))
    text = robot_urdf(robot)
    text = edited(text, '  <planar_tui gravity_m_s2="9.81" direction="0 -1 0"/>\n', "")
    text = edited(
        text,
        '<origin xyz="0.0 0.0 0.0" rpy="0 0 0"/>',
        '<origin xyz="0.1 0.0 0.2" rpy="0.4 -0.9 1.3"/>',
    )
    imported = read_robot(written(tmp_path, text, "urdf"))
    assert "assumed: URDF has no gravity (ROS: z up)" in " ".join(imported.notes)
    model = pinocchio.buildModelFromXML(text)
    data = model.createData()
    preset = imported.robot
    rng = np.random.default_rng(5)
    for _ in range(5):
        q, omega, alpha = random_state(rng, 2)
        cs = np.column_stack([np.cos(q), np.sin(q)]).ravel()
        tau = np.array(pinocchio.rnea(model, data, cs, omega, alpha))
        theta = q + np.radians(imported.offsets_deg)
        ours = inverse_dynamics(*preset.arrays(), preset.gravity_m_s2, theta, omega, alpha)
        assert np.abs(ours - tau).max() <= 1e-10 * np.abs(tau).max()

"""The serial robot as URDF, the ``export --format urdf`` file.

Conventions (:mod:`.conventions`, also stated in the file's own comment): a fixed
``base_link`` at the world origin, ``link1`` … ``linkn``, joint i a ``continuous`` joint
(URDF's revolute joint without limits: planar-tui's joints have none) about +z, placed
``l_{i-1}`` along the parent's x axis, so the joint coordinates are planar-tui's relative
angles; each link's ``<inertial>`` has its origin at mid-link and the tensor
``diag(a_i, I_i, I_i)`` about the centre of mass (``a_i`` the tiny axial moment, as in the
MJCF export). A massless ``tip`` link on a fixed joint marks the end of the last link.

URDF has no gravity: a tool that reads it uses its own (Pinocchio and ROS: −9.81 along
z, which is perpendicular to this robot's plane). The file says planar-tui's gravity in
its comment and in a ``<planar_tui gravity_m_s2="…" direction="0 -1 0"/>`` element that
URDF readers ignore (urdfdom, Pinocchio, MuJoCo) and ``planar-tui import`` reads.
"""

from __future__ import annotations

from xml.sax.saxutils import quoteattr

from planar_tui import __version__
from planar_tui.dynamics.robot import SerialRobot
from planar_tui.interop.conventions import (
    axial_inertia_kgm2,
    number,
    robot_label,
    vector,
    xml_comment,
)

#: The element planar-tui writes its gravity in (URDF readers ignore unknown elements).
GRAVITY_ELEMENT = "planar_tui"


def header_comment(robot: SerialRobot) -> str:
    """The URDF file's comment: where it comes from and every convention it follows."""
    return xml_comment(
        f"{robot.label} exported by planar-tui {__version__} (URDF).\n"
        "Plane of motion: x-y; every joint turns about +z ('continuous': a revolute\n"
        "joint without limits); joint positions = planar-tui's relative joint angles (rad),\n"
        "all links along +x at zero. Each link: mass at mid-link, inertia diag(a, I, I)\n"
        "about the centre of mass: only I_zz = I enters planar motion; a = max(1e-6 I,\n"
        "1e-15) kg m2 is a tiny axial moment (a slender rod; MuJoCo needs it positive).\n"
        "URDF has no gravity: planar-tui's is g = "
        f"{number(robot.gravity_m_s2)} m/s2 along -y (in the plane),\n"
        "written in the <planar_tui> element below for planar-tui; set it in your tool\n"
        "(Pinocchio: model.gravity.linear = (0, -g, 0)). No damping, friction or limits."
    )


def robot_urdf(robot: SerialRobot) -> str:
    """URDF text of ``robot`` (see the module's conventions)."""
    lengths = robot.lengths_m
    lines = [
        '<?xml version="1.0"?>',
        header_comment(robot),
        f"<robot name={quoteattr(robot_label(robot))}>",
        f'  <{GRAVITY_ELEMENT} gravity_m_s2="{number(robot.gravity_m_s2)}" direction="0 -1 0"/>',
        '  <link name="base_link"/>',
    ]
    for i, (length, mass, inertia) in enumerate(
        zip(lengths, robot.masses_kg, robot.inertias_kgm2, strict=True), start=1
    ):
        parent = "base_link" if i == 1 else f"link{i - 1}"
        offset = 0.0 if i == 1 else lengths[i - 2]
        lines += [
            f'  <link name="link{i}">',
            "    <inertial>",
            f'      <origin xyz="{vector(0.5 * length, 0.0, 0.0)}" rpy="0 0 0"/>',
            f'      <mass value="{number(mass)}"/>',
            f'      <inertia ixx="{number(axial_inertia_kgm2(inertia))}" ixy="0" ixz="0"'
            f' iyy="{number(inertia)}" iyz="0" izz="{number(inertia)}"/>',
            "    </inertial>",
            "  </link>",
            f'  <joint name="joint{i}" type="continuous">',
            f'    <parent link="{parent}"/>',
            f'    <child link="link{i}"/>',
            f'    <origin xyz="{vector(offset, 0.0, 0.0)}" rpy="0 0 0"/>',
            '    <axis xyz="0 0 1"/>',
            "  </joint>",
        ]
    lines += [
        '  <link name="tip"/>',
        '  <joint name="tip" type="fixed">',
        f'    <parent link="link{robot.n_links}"/>',
        '    <child link="tip"/>',
        f'    <origin xyz="{vector(lengths[-1], 0.0, 0.0)}" rpy="0 0 0"/>',
        "  </joint>",
        "</robot>",
    ]
    return "\n".join(lines) + "\n"

"""The serial robot as an MJCF model (MuJoCo's XML), the ``export --format mjcf`` file.

Conventions (:mod:`.conventions`, also stated in the file's own comment): the x-y plane,
hinge joints about z, ``qpos`` = planar-tui's relative joint angles, gravity
``(0, −g, 0)``, link i's inertial frame at mid-link with ``diaginertia = (a_i, I_i, I_i)``
about the centre of mass (``a_i`` the tiny axial moment). ``inertiafromgeom="false"``: the
capsule geoms are for the viewer only (no contact: ``contype = conaffinity = 0``, and no
mass); no damping, armature, friction or joint limits, as in planar-tui. Each joint has a
``motor`` actuator (gear 1, unlimited control), so ``data.ctrl`` is the joint torque in N m.
A site ``tip`` marks the end of the last link. ``mj_inverse`` on this model gives
planar-tui's inverse dynamics (checked in ``tests/test_interop_engines.py``).
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

#: Radius of a link's capsule geom (viewer only), as a fraction of the shortest link.
GEOM_RADIUS_FRACTION = 0.04
#: Nesting levels that are indented: deeper bodies keep this indentation, so that the file
#: of a chain of thousands of links grows linearly with n.
INDENT_LEVELS = 16


def _indent(level: int) -> str:
    return "  " * (2 + min(level, INDENT_LEVELS))


def header_comment(robot: SerialRobot) -> str:
    """The MJCF file's comment: where it comes from and every convention it follows."""
    return xml_comment(
        f"{robot.label} exported by planar-tui {__version__} (MJCF).\n"
        "Plane of motion: x-y; every joint is a hinge about +z at the start of its link;\n"
        "qpos = planar-tui's relative joint angles (rad), all links along +x at qpos = 0.\n"
        f"Gravity: (0, -g, 0), g = {number(robot.gravity_m_s2)} m/s2.\n"
        "Each link: mass at mid-link, diaginertia = (a, I, I) about the centre of mass:\n"
        "only I_zz = I enters planar motion; a = max(1e-6 I, 1e-15) kg m2 is the tiny\n"
        "axial moment MuJoCo's triangle inequality (A + B >= C) and mjMINVAL need.\n"
        "Geoms are for the viewer only (inertiafromgeom=false, no contact).\n"
        "No damping, armature, friction or joint limits. Actuators: one motor per joint\n"
        "(gear 1): ctrl = joint torque (N m). Site 'tip': the end of the last link."
    )


def robot_mjcf(robot: SerialRobot) -> str:
    """MJCF text of ``robot`` (see the module's conventions)."""
    lengths = robot.lengths_m
    radius = GEOM_RADIUS_FRACTION * min(lengths)
    lines = [
        header_comment(robot),
        f"<mujoco model={quoteattr(robot_label(robot))}>",
        '  <compiler angle="radian" inertiafromgeom="false" autolimits="true"/>',
        f'  <option gravity="{vector(0.0, -robot.gravity_m_s2, 0.0)}"/>',
        "  <worldbody>",
    ]
    for i, (length, mass, inertia) in enumerate(
        zip(lengths, robot.masses_kg, robot.inertias_kgm2, strict=True), start=1
    ):
        offset = 0.0 if i == 1 else lengths[i - 2]
        indent = _indent(i - 1)
        lines += [
            f'{indent}<body name="link{i}" pos="{vector(offset, 0.0, 0.0)}">',
            f'{indent}  <joint name="joint{i}" type="hinge" axis="0 0 1" pos="0 0 0"/>',
            f'{indent}  <inertial pos="{vector(0.5 * length, 0.0, 0.0)}" mass="{number(mass)}"'
            f' diaginertia="{vector(axial_inertia_kgm2(inertia), inertia, inertia)}"/>',
            f'{indent}  <geom name="link{i}" type="capsule" fromto="0 0 0 {number(length)} 0 0"'
            f' size="{number(radius)}" contype="0" conaffinity="0"/>',
        ]
    lines.append(f'{_indent(len(lengths))}<site name="tip" pos="{vector(lengths[-1], 0.0, 0.0)}"/>')
    lines += [f"{_indent(level)}</body>" for level in reversed(range(len(lengths)))]
    lines += ["  </worldbody>", "  <actuator>"]
    lines += [
        f'    <motor name="motor{i}" joint="joint{i}" gear="1"/>'
        for i in range(1, robot.n_links + 1)
    ]
    lines += ["  </actuator>", "</mujoco>"]
    return "\n".join(lines) + "\n"

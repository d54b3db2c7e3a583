"""A URDF file read as a chain of revolute joints (:func:`read_urdf`).

Fixed joints from the root link to the first revolute joint are the base (their masses
ignored); massless fixed links between revolute joints (tips, tools) are composed through;
gravity is planar-tui's ``<planar_tui>`` element, else ROS's. The rules are in
:mod:`.robot_import`.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from planar_tui.interop.planar_chain import (
    Chain,
    Frame,
    ImportedRobot,
    Link,
    basis_rotation,
    planar_robot,
    unit,
)
from planar_tui.interop.robot_xml import XmlReader, read_xml
from planar_tui.interop.urdf import GRAVITY_ELEMENT

#: The gravity assumed for a URDF without planar-tui's element (ROS: z up), m/s².
ROS_GRAVITY = (0.0, 0.0, -9.81)
#: URDF joint types that are revolute; MJCF's is ``hinge``.
URDF_REVOLUTE = ("revolute", "continuous")


def rpy_rotation(rpy: np.ndarray) -> np.ndarray:
    """URDF's roll-pitch-yaw (fixed axes x, y, z): ``Rz(yaw) Ry(pitch) Rx(roll)``."""
    roll, pitch, yaw = rpy
    return basis_rotation(2, yaw) @ basis_rotation(1, pitch) @ basis_rotation(0, roll)


def _urdf_origin(reader: XmlReader, element: ET.Element) -> Frame:
    origin = element.find("origin")
    if origin is None:
        return Frame()
    xyz = reader.numbers(origin, "xyz", 3, (0.0, 0.0, 0.0))
    rpy = reader.numbers(origin, "rpy", 3, (0.0, 0.0, 0.0))
    return Frame(rpy_rotation(rpy), xyz)


def _urdf_inertial(reader: XmlReader, link: ET.Element) -> tuple[float, np.ndarray, np.ndarray]:
    """``(mass, centre of mass, inertia about it)`` in the link's frame; mass 0 without."""
    inertial = link.find("inertial")
    if inertial is None:
        return 0.0, np.zeros(3), np.zeros((3, 3))
    frame = _urdf_origin(reader, inertial)
    mass_element = inertial.find("mass")
    mass = 0.0 if mass_element is None else reader.number(mass_element, "value", None)
    tensor = np.zeros((3, 3))
    element = inertial.find("inertia")
    if element is not None:
        value = {
            k: reader.number(element, k, 0.0) for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
        }
        tensor = np.array(
            [
                [value["ixx"], value["ixy"], value["ixz"]],
                [value["ixy"], value["iyy"], value["iyz"]],
                [value["ixz"], value["iyz"], value["izz"]],
            ]
        )
    return mass, frame.p, frame.R @ tensor @ frame.R.T


@dataclass(frozen=True)
class _UrdfJoint:
    """A URDF ``<joint>``: its element, type and the names of its parent and child links."""

    element: ET.Element
    type: str
    parent: str
    child: str

    @property
    def revolute(self) -> bool:
        return self.type in URDF_REVOLUTE


def _urdf_joints(
    reader: XmlReader, root: ET.Element, links: dict[str, ET.Element]
) -> list[_UrdfJoint]:
    """Every joint, checked: a known type, two links of the file, one parent per link."""
    joints: list[_UrdfJoint] = []
    children: set[str] = set()
    for element in root.findall("joint"):
        ends = [element.find(tag) for tag in ("parent", "child")]
        names = [None if end is None else end.get("link") for end in ends]
        kind = element.get("type", "")
        if kind not in (*URDF_REVOLUTE, "fixed"):
            raise reader.error(
                element,
                f"is a {kind or 'typeless'} joint",
                "revolute, continuous (or fixed) joints only",
            )
        for name in names:
            if name is None or name not in links:
                raise reader.error(
                    element,
                    f"names link {name!r}, which is not in the file",
                    "<parent link> and <child link> of the file's links",
                )
        parent, child = str(names[0]), str(names[1])
        if child in children:
            raise reader.error(element, f"link {child!r} has two parents", "a tree")
        children.add(child)
        joints.append(_UrdfJoint(element, kind, parent, child))
    return joints


def read_urdf(path: Path | str) -> ImportedRobot:
    """A URDF file as a ``[robot]`` (see :mod:`.robot_import`'s rules)."""
    root, reader = read_xml(path)
    if root.tag != "robot":
        raise reader.error(root, "is not a URDF <robot>", "a URDF file (root <robot>)")
    links = {str(link.get("name")): link for link in root.findall("link")}
    joints = _urdf_joints(reader, root, links)
    below: dict[str, list[_UrdfJoint]] = {}
    for entry in joints:
        below.setdefault(entry.parent, []).append(entry)
    parent_of = {entry.child: entry.parent for entry in joints}
    roots = [name for name in links if name not in parent_of]
    if len(roots) != 1:
        raise reader.error(root, f"has {len(roots)} root links", "one base link")
    gravity, source = _urdf_gravity(reader, root)
    notes: list[str] = []
    above_revolute: set[str] = set()  # links with a revolute joint somewhere below
    for entry in joints:
        link: str | None = entry.parent if entry.revolute else None
        while link is not None and link not in above_revolute:  # no recursion: any length
            above_revolute.add(link)
            link = parent_of.get(link)

    def leads(joint: _UrdfJoint) -> bool:
        return joint.revolute or joint.child in above_revolute

    def chain_joint(link_name: str) -> _UrdfJoint | None:
        """The one joint below ``link_name`` leading to more revolute joints; the others
        (massless frames: tips, tools) are checked by :func:`welded`."""
        leading = [joint for joint in below.get(link_name, []) if leads(joint)]
        if len(leading) > 1:
            raise reader.error(
                leading[1].element,
                f"is a second chain below link {link_name!r}: a branched tree",
                "a serial chain",
            )
        return leading[0] if leading else None

    def welded(link_name: str, moving_link: str) -> None:
        """Refuse a mass fixed to a moving link (planar-tui does not merge bodies)."""
        for joint in below.get(link_name, []):
            if not leads(joint):
                if _urdf_inertial(reader, links[joint.child])[0] > 0:
                    raise reader.error(
                        links[joint.child],
                        f"has a mass welded to link {moving_link!r}",
                        "massless fixed links only (merge the mass into the link)",
                    )
                welded(joint.child, moving_link)

    # the base: fixed joints from the root to the first revolute joint (masses ignored)
    world = Frame()
    joint = chain_joint(roots[0])
    while joint is not None and not joint.revolute:
        world = world.then(_urdf_origin(reader, joint.element))
        joint = chain_joint(joint.child)
    chain: list[Link] = []
    while joint is not None:
        frame = world.then(_urdf_origin(reader, joint.element))
        name = joint.child
        axis_element = joint.element.find("axis")
        axis = np.array([1.0, 0.0, 0.0])  # URDF's default
        if axis_element is not None:
            try:
                axis = unit(reader.numbers(axis_element, "xyz", 3, None))
            except ValueError:
                raise reader.error(axis_element, "axis is zero", "a direction") from None
        label = joint.element.get("name")
        if joint.type == "revolute" and joint.element.find("limit") is not None:
            notes.append(f"joint {label!r}: its limits are not kept")
        notes += [
            f"joint {label!r}: <{tag}> is not kept"
            for tag in ("dynamics", "mimic")
            if joint.element.find(tag) is not None
        ]
        link_element = links[name]
        if link_element.find("inertial") is None:
            raise reader.error(link_element, "has no <inertial>", "the link's mass and inertia")
        mass, com, inertia = _urdf_inertial(reader, link_element)
        welded(name, name)
        # the next revolute joint, through massless fixed links
        relative = Frame()
        following = chain_joint(name)
        while following is not None and not following.revolute:
            relative = relative.then(_urdf_origin(reader, following.element))
            if _urdf_inertial(reader, links[following.child])[0] > 0:
                raise reader.error(
                    links[following.child],
                    f"has a mass welded to link {name!r}",
                    "massless fixed links only",
                )
            welded(following.child, name)
            following = chain_joint(following.child)
        next_point = None
        if following is not None:
            next_point = relative.then(_urdf_origin(reader, following.element)).p
        chain.append(
            Link(
                joint=reader.where(joint.element),
                element=reader.where(link_element),
                joint_point=np.zeros(3),
                axis=axis,
                mass_kg=mass,
                com=com,
                inertia=inertia,
                world=frame.R,
                next_point=next_point,
            )
        )
        world = frame.then(relative)
        joint = following
    return planar_robot(Chain(root.get("name", ""), chain, gravity, source, notes), reader, "URDF")


def _urdf_gravity(reader: XmlReader, root: ET.Element) -> tuple[np.ndarray, str]:
    """Gravity from planar-tui's ``<planar_tui>`` element, else ROS's (assumed)."""
    element = root.find(GRAVITY_ELEMENT)
    if element is None:
        return np.array(ROS_GRAVITY), "assumed: URDF has no gravity (ROS: z up)"
    g = reader.number(element, "gravity_m_s2", None)
    try:
        direction = unit(reader.numbers(element, "direction", 3, (0.0, -1.0, 0.0)))
    except ValueError:
        raise reader.error(element, "direction is zero", "a direction") from None
    return g * direction, f"the file's <{GRAVITY_ELEMENT}>"

"""An MJCF file read as a chain of hinge joints (:func:`read_mjcf`), with MJCF's
orientation forms (``quat``, ``axisangle``, ``euler``, ``xyaxes``, ``zaxis``), its
``<compiler>`` settings and its joint defaults. The rules are in :mod:`.robot_import`.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from planar_tui.interop.planar_chain import (
    Chain,
    Frame,
    ImportedRobot,
    Link,
    axis_rotation,
    basis_rotation,
    planar_robot,
    unit,
    vector_length,
)
from planar_tui.interop.robot_xml import XmlReader, read_xml


def quaternion_rotation(quat: np.ndarray) -> np.ndarray:
    """Rotation of a quaternion ``(w, x, y, z)`` (normalised first, as MuJoCo does)."""
    norm = float(np.linalg.norm(quat))
    if norm == 0.0:
        raise ValueError("a zero quaternion")
    w, x, y, z = quat / norm
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )


@dataclass
class _Compiler:
    degrees: bool = True
    eulerseq: str = "xyz"


def _mjcf_rotation(reader: XmlReader, element: ET.Element, compiler: _Compiler) -> np.ndarray:
    """An MJCF element's orientation (``quat``, ``axisangle``, ``euler``, ``xyaxes``,
    ``zaxis``; identity without), ``compiler angle`` applied to angles."""
    given = [a for a in ("quat", "axisangle", "euler", "xyaxes", "zaxis") if a in element.attrib]
    if len(given) > 1:
        raise reader.error(element, f"has {' and '.join(given)}", "one orientation attribute")
    scale = math.pi / 180.0 if compiler.degrees else 1.0
    try:
        if not given:
            return np.eye(3)
        if given[0] == "quat":
            quat = reader.numbers(element, "quat", 4, None)
            if quat[0] != 0.0 and not quat[1:].any():
                return np.eye(3)  # exactly
            return quaternion_rotation(quat)
        if given[0] == "axisangle":
            values = reader.numbers(element, "axisangle", 4, None)
            return axis_rotation(unit(values[:3]), values[3] * scale)
        if given[0] == "euler":
            angles = reader.numbers(element, "euler", 3, None) * scale
            rotation = np.eye(3)
            for letter, angle in zip(compiler.eulerseq, angles, strict=True):
                turn = basis_rotation("xyz".index(letter.lower()), float(angle))
                rotation = rotation @ turn if letter.islower() else turn @ rotation
            return rotation
        if given[0] == "xyaxes":
            values = reader.numbers(element, "xyaxes", 6, None)
            x = unit(values[:3])
            y = unit(values[3:] - np.dot(values[3:], x) * x)
            return np.column_stack([x, y, np.cross(x, y)])
        z = unit(reader.numbers(element, "zaxis", 3, None))
        reference = np.array([0.0, 0.0, 1.0])
        turn = np.cross(reference, z)
        if vector_length(turn) < 1e-15:
            return np.eye(3) if z[2] > 0 else basis_rotation(0, math.pi)
        return axis_rotation(unit(turn), math.acos(max(-1.0, min(1.0, float(z[2])))))
    except ValueError as error:
        raise reader.error(element, f"{given[0]} is {error}", "a valid orientation") from None


def _mjcf_defaults(reader: XmlReader, root: ET.Element) -> dict[str, dict[str, str]]:
    """Joint attributes per default class (``main`` the top level), inherited down."""
    classes: dict[str, dict[str, str]] = {}

    def visit(element: ET.Element, inherited: dict[str, str]) -> None:
        name = element.get("class", "main")
        own = dict(inherited)
        for joint in element.findall("joint"):
            own.update(joint.attrib)
        classes[name] = own
        for child in element.findall("default"):
            visit(child, own)

    for top in root.findall("default"):
        visit(top, {})
    return classes


def read_mjcf(path: Path | str) -> ImportedRobot:
    """An MJCF file as a ``[robot]`` (see :mod:`.robot_import`'s rules)."""
    root, reader = read_xml(path)
    if root.tag != "mujoco":
        raise reader.error(root, "is not an MJCF <mujoco> model", "an MJCF file (root <mujoco>)")
    for tag in ("include", "equality", "frame", "replicate"):
        found = next(root.iter(tag), None)
        if found is not None:
            why = {
                "include": "other files are not read",
                "equality": "closed loops or couplings are not a serial chain",
            }.get(tag, "not read")
            raise reader.error(found, why, f"one file without <{tag}>")
    compiler = _Compiler()
    for element in root.iter("compiler"):
        angle = element.get("angle")
        if angle is not None:
            if angle not in ("degree", "radian"):
                raise reader.error(element, f"angle is {angle!r}", '"degree" or "radian"')
            compiler.degrees = angle == "degree"
        if element.get("inertiafromgeom") == "true":
            raise reader.error(
                element,
                'inertiafromgeom is "true": the masses are the geoms\', which are not read',
                '"auto" or "false" with <inertial>',
            )
        for attribute in ("settotalmass", "boundmass", "boundinertia", "balanceinertia"):
            if element.get(attribute) not in (None, "-1", "0", "false"):
                raise reader.error(
                    element,
                    f"{attribute} changes the masses MuJoCo uses: not read",
                    f"a <compiler> without {attribute}",
                )
        sequence = element.get("eulerseq")
        if sequence is not None:
            if len(sequence) != 3 or any(c not in "xyzXYZ" for c in sequence):
                raise reader.error(
                    element, f"eulerseq is {sequence!r}", "three of x, y, z, X, Y, Z"
                )
            compiler.eulerseq = sequence
    gravity = np.array([0.0, 0.0, -9.81])
    for option in root.iter("option"):
        gravity = reader.numbers(option, "gravity", 3, tuple(gravity))
    defaults = _mjcf_defaults(reader, root)
    worldbodies = root.findall("worldbody")
    notes: list[str] = []

    def joints_of(body: ET.Element) -> list[ET.Element]:
        return [c for c in body if c.tag in ("joint", "freejoint")]

    moving_bodies: set[ET.Element] = set()  # bodies with a joint in their subtree
    for element in reversed(list(root.iter("body"))):  # children before their parents
        if joints_of(element) or any(c in moving_bodies for c in element.findall("body")):
            moving_bodies.add(element)

    def moving(body: ET.Element) -> bool:
        return body in moving_bodies

    def next_body(body: ET.Element) -> ET.Element | None:
        leading = [c for c in body.findall("body") if moving(c)]
        if len(leading) > 1:
            raise reader.error(
                leading[1],
                f"is a second moving chain below {reader.named(body)}: a branched tree",
                "a serial chain",
            )
        return leading[0] if leading else None

    def frame_of(body: ET.Element) -> Frame:
        return Frame(
            _mjcf_rotation(reader, body, compiler), reader.numbers(body, "pos", 3, (0.0, 0.0, 0.0))
        )

    def check_welded(body: ET.Element, moving_body: ET.Element) -> None:
        for child in body.findall("body"):
            if not moving(child):
                inertial = child.find("inertial")
                if inertial is not None and reader.number(inertial, "mass", None) > 0:
                    raise reader.error(
                        child,
                        f"has a mass welded to {reader.named(moving_body)}",
                        "massless fixed bodies only (merge the mass)",
                    )
                check_welded(child, moving_body)

    tops = [body for world in worldbodies for body in world.findall("body") if moving(body)]
    if len(tops) > 1:
        raise reader.error(
            tops[1], "is a second moving chain in the world: a branched tree", "one serial chain"
        )

    def classed(body: ET.Element, active: str) -> str:
        name = body.get("childclass", active)
        if name not in defaults and name != "main":
            raise reader.error(body, f"childclass {name!r} is not defined", "a <default> class")
        return name

    world = Frame()
    body = tops[0] if tops else None
    active = "main"
    while body is not None and not joints_of(body):  # the base, fixed to the world
        active = classed(body, active)
        world = world.then(frame_of(body))
        body = next_body(body)
    chain: list[Link] = []
    while body is not None:
        active = classed(body, active)
        joints = joints_of(body)
        if len(joints) != 1:
            raise reader.error(body, f"has {len(joints)} joints", "one hinge joint per body")
        joint = joints[0]
        joint_class = joint.get("class", active)
        if joint_class not in defaults and joint_class != "main":
            raise reader.error(joint, f"class {joint_class!r} is not defined", "a <default> class")
        resolved = ET.Element("joint", {**defaults.get(joint_class, {}), **joint.attrib})
        reader.lines[resolved] = reader.lines.get(joint, 0)
        kind = "free" if joint.tag == "freejoint" else resolved.get("type", "hinge")
        if kind != "hinge":
            raise reader.error(joint, f"is a {kind} joint", "hinge joints only")
        try:
            axis = unit(reader.numbers(resolved, "axis", 3, (0.0, 0.0, 1.0)))
        except ValueError:
            raise reader.error(joint, "axis is zero", "a direction") from None
        for attribute in ("range", "damping", "armature", "frictionloss", "stiffness"):
            value = resolved.get(attribute)
            if value is not None and (attribute == "range" or value.strip() not in ("0", "0.0")):
                notes.append(f"{reader.where(joint)}: {attribute} {value} is not kept")
        reference = reader.number(resolved, "ref", 0.0) * (
            math.pi / 180.0 if compiler.degrees else 1.0
        )
        inertial = body.find("inertial")
        if inertial is None:
            has_geoms = body.find("geom") is not None
            raise reader.error(
                body,
                "has no <inertial>"
                + (" (inertia from geoms is not computed)" if has_geoms else ""),
                "an <inertial> element with mass and inertia",
            )
        mass = reader.number(inertial, "mass", None)
        rotation = _mjcf_rotation(reader, inertial, compiler)
        if "fullinertia" in inertial.attrib:
            xx, yy, zz, xy, xz, yz = reader.numbers(inertial, "fullinertia", 6, None)
            tensor = np.array([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])
        else:
            tensor = np.diag(reader.numbers(inertial, "diaginertia", 3, None))
        frame = world.then(frame_of(body))
        joint_point = reader.numbers(resolved, "pos", 3, (0.0, 0.0, 0.0))
        check_welded(body, body)
        following = next_body(body)
        relative = Frame()
        while following is not None and not joints_of(following):
            inertial_w = following.find("inertial")
            if inertial_w is not None and reader.number(inertial_w, "mass", None) > 0:
                raise reader.error(
                    following,
                    f"has a mass welded to {reader.named(body)}",
                    "massless fixed bodies only",
                )
            relative = relative.then(frame_of(following))
            check_welded(following, body)
            following = next_body(following)
        next_point = None
        if following is not None:
            child_frame = relative.then(frame_of(following))
            child_joints = joints_of(following)
            child_point = (
                reader.numbers(child_joints[0], "pos", 3, (0.0, 0.0, 0.0))
                if len(child_joints) == 1
                else np.zeros(3)
            )
            next_point = child_frame.point(child_point)
        chain.append(
            Link(
                joint=reader.where(joint),
                element=reader.where(body),
                joint_point=joint_point,
                axis=axis,
                mass_kg=mass,
                com=reader.numbers(inertial, "pos", 3, None),
                inertia=rotation @ tensor @ rotation.T,
                world=frame.R,
                next_point=next_point,
                reference_rad=reference,
            )
        )
        world = frame.then(relative)
        body = following
    source = (
        "the file's <option gravity>" if root.find("option") is not None else "MuJoCo's default"
    )
    return planar_robot(Chain(root.get("model", ""), chain, gravity, source, notes), reader, "MJCF")

r"""URDF and MJCF files as a ``[robot]`` preset (``planar-tui import``).

Reading: the standard library's XML parser (``xml.parsers.expat`` building
``xml.etree.ElementTree`` elements, with each element's line kept for messages), from one
local file, never the network. A file holding a ``<!DOCTYPE`` or ``<!ENTITY`` is refused
before it is parsed (checked in the raw text, and again by the parser's handlers), so no
entity is ever expanded (no "billion laughs", no external entity); so is one over
:data:`MAX_BYTES` or not UTF-8. MJCF ``<include>`` (other files) is refused too.

What becomes a preset: a serial chain of revolute joints (URDF ``revolute`` or
``continuous``, MJCF ``hinge``) whose axes are all parallel and point the same way. In
the frame of link i (its joint's frame at zero joint angles):

* the link runs from joint i's axis to joint i+1's, projected on the plane normal to the
  axis; its length :math:`l_i` is that distance (offsets along the axis are allowed: they
  do not change planar motion). The last link has no next joint: its length is twice its
  centre of mass's distance from its joint's axis;
* the centre of mass must lie on the link line at mid-link (planar-tui's links have it
  there), else the file is refused;
* the mass is the inertial's; the inertia is the moment about the axis through the centre
  of mass, :math:`k^T J k` (k the unit axis, J the inertia tensor about the centre of
  mass): the only moment planar motion feels;
* the plane's y axis points against gravity's in-plane part, its x axis is
  :math:`y \times k` (so angles turn the joints' way). Gravity is the MJCF
  ``<option gravity>`` (default :math:`(0, 0, -9.81)`); URDF has none, so it is
  planar-tui's ``<planar_tui gravity_m_s2 direction>`` element when the file has one (the
  exporter writes it), else ROS's :math:`(0, 0, -9.81)`, with a note. Gravity along the
  axis (a horizontal plane) gives ``gravity_m_s2 = 0`` and x along link 1; a tilted plane
  keeps gravity's in-plane part, with a note;
* links that are not straight along x at zero joint angles get a note giving the angle
  offsets (planar-tui's :math:`\theta_i = q_i + \Delta_i`): the preset is the same arm,
  its angles counted from the straight posture (an MJCF joint's ``ref``, the coordinate
  of the drawn posture, is taken off :math:`\Delta_i`).

Refused, each with one line naming the file, the element (and its line) and why: a joint
that is not revolute (prismatic, ball, free, planar, floating ...), axes not parallel, a
centre of mass off the link line or not at mid-link, a branched tree (two moving chains),
a body with two joints, a mass welded to a moving link, a moving link without an
inertial, closed loops (MJCF ``<equality>``), and anything planar-tui's ``[robot]`` cannot
hold. What a preset has no key for is left out with a note: joint limits, damping,
armature, friction, actuators, geoms, and all masses fixed to the world (the base).

Exactness: every position and rotation is composed as read, so a file
``planar-tui export`` wrote (identity rotations, links along x) gives back the preset's
values exactly (``tests/test_interop_import.py``).
"""

from __future__ import annotations

import itertools
import math
import xml.etree.ElementTree as ET
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from xml.parsers import expat

import numpy as np

from planar_tui.dynamics.robot import SerialRobot
from planar_tui.errors import PresetError

#: Largest file read (bytes): robot descriptions are kilobytes; meshes are not read.
MAX_BYTES = 16 * 1024 * 1024
#: Relative tolerance of "parallel", "on the link line" and "at mid-link".
TOLERANCE = 1e-9
#: What the CLI accepts: URDF by suffix, MJCF (``.xml``, ``.mjcf``) otherwise.
URDF_SUFFIXES = (".urdf",)
MJCF_SUFFIXES = (".xml", ".mjcf")
#: The gravity assumed for a URDF without planar-tui's element (ROS: z up), m/s².
ROS_GRAVITY = (0.0, 0.0, -9.81)
#: URDF joint types that are revolute; MJCF's is ``hinge``.
URDF_REVOLUTE = ("revolute", "continuous")

_FORBIDDEN = ("<!DOCTYPE", "<!ENTITY")


@dataclass
class Frame:
    """A rigid transform: rotation ``R`` (3×3, child axes in the parent's) and origin ``p``."""

    R: np.ndarray = field(default_factory=lambda: np.eye(3))
    p: np.ndarray = field(default_factory=lambda: np.zeros(3))

    def then(self, child: Frame) -> Frame:
        """The child's frame seen from this frame's parent: ``(R Rc, p + R pc)``."""
        return Frame(self.R @ child.R, self.p + self.R @ child.p)

    def point(self, local: np.ndarray) -> np.ndarray:
        return self.p + self.R @ local


@dataclass
class Link:
    """One moving link in its own frame (its joint's frame at zero joint angles).

    ``joint_point`` and ``axis`` are the joint's, ``com`` and ``inertia`` (about the
    centre of mass, in the frame's axes) the link's; ``world`` its rotation in the
    world; ``next_point`` joint i+1's point in this frame (``None`` for the last link);
    ``joint`` and ``element`` name the joint and the link for messages;
    ``reference_rad`` the joint coordinate at which the link is where the file draws it
    (MJCF ``ref``; 0 in URDF)."""

    joint: str
    element: str
    joint_point: np.ndarray
    axis: np.ndarray
    mass_kg: float
    com: np.ndarray
    inertia: np.ndarray
    world: np.ndarray
    next_point: np.ndarray | None = None
    reference_rad: float = 0.0


@dataclass
class Chain:
    """A file read as a chain: its links from the base out, gravity, name and notes."""

    name: str
    links: list[Link]
    gravity: np.ndarray
    gravity_source: str
    notes: list[str]


@dataclass(frozen=True)
class ImportedRobot:
    """The robot read from a file and what the preset could not hold (``notes``), and
    ``offsets_deg`` (Δ_i: planar-tui's θ_i = q_i + Δ_i; zeros for a straight arm)."""

    robot: SerialRobot
    notes: tuple[str, ...]
    offsets_deg: tuple[float, ...]
    source_format: str


# ---------------------------------------------------------------------------------------
# Reading the XML safely
# ---------------------------------------------------------------------------------------


class _Reader:
    """Errors about one file: ``error(element, problem, expected)``, the element named by
    its tag, its ``name`` and its line."""

    def __init__(self, path: Path | str, lines: dict):
        self.path = path
        self.lines = lines

    @staticmethod
    def named(element: ET.Element) -> str:
        """``<tag name="...">`` (``<tag>`` without a name)."""
        name = element.get("name")
        return f'<{element.tag} name="{name}">' if name is not None else f"<{element.tag}>"

    def where(self, element: ET.Element) -> str:
        """:meth:`named` after the element's line: ``line 12: <joint name="elbow">``."""
        line = self.lines.get(element)
        return f"line {line}: {self.named(element)}" if line else self.named(element)

    def error(self, element: ET.Element | None, problem: str, expected: str | None = None):
        where = "(file)" if element is None else self.where(element)
        return PresetError(self.path, where, problem, expected)

    def numbers(
        self, element: ET.Element, attribute: str, count: int, default: Sequence[float] | None
    ) -> np.ndarray:
        """``count`` finite numbers of an attribute (space-separated), or the default."""
        text = element.get(attribute)
        if text is None:
            if default is None:
                raise self.error(element, f"no {attribute} attribute", f"{count} number(s)")
            return np.array(default, dtype=np.float64)
        try:
            values = [float(item) for item in text.split()]
        except ValueError:
            values = []
        if len(values) != count or not all(math.isfinite(v) for v in values):
            raise self.error(element, f"{attribute} is {text!r}", f"{count} finite number(s)")
        return np.array(values, dtype=np.float64)

    def number(self, element: ET.Element, attribute: str, default: float | None) -> float:
        return float(self.numbers(element, attribute, 1, None if default is None else [default])[0])


def read_xml(path: Path | str) -> tuple[ET.Element, _Reader]:
    """The file's root element and a :class:`_Reader` for its messages.

    Refused (:class:`PresetError`): a missing or unreadable file, one over
    :data:`MAX_BYTES`, one not UTF-8, and any ``<!DOCTYPE``/``<!ENTITY`` (checked in the
    raw text before parsing: no entity is ever expanded)."""
    path = Path(path)
    try:
        with open(path, "rb") as stream:
            raw = stream.read(MAX_BYTES + 1)
    except FileNotFoundError:
        raise PresetError(path, "(file)", "no such file", "a URDF or MJCF file") from None
    except OSError as error:
        raise PresetError(path, "(file)", f"cannot be read: {error.strerror or error}") from None
    if len(raw) > MAX_BYTES:
        raise PresetError(path, "(file)", f"is larger than {MAX_BYTES >> 20} MiB",
                          "a robot description (meshes are not read)")  # fmt: skip
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as error:
        raise PresetError(path, "(file)", f"is not UTF-8 text ({error.reason} at byte "
                          f"{error.start})", "a UTF-8 XML file") from None  # fmt: skip
    upper = text.upper()
    for marker in _FORBIDDEN:
        at = upper.find(marker)
        if at >= 0:
            line = text.count("\n", 0, at) + 1
            raise PresetError(
                path, f"line {line}", f"has a {marker[2:]} declaration: refused, entities "
                "are never expanded", "plain URDF or MJCF without a DTD",
            )  # fmt: skip
    return _parse(path, text)


def _parse(path: Path, text: str) -> tuple[ET.Element, _Reader]:
    """Parse with expat into ElementTree elements, keeping each element's line."""
    parser = expat.ParserCreate()
    lines: dict[ET.Element, int] = {}
    stack: list[ET.Element] = []
    roots: list[ET.Element] = []

    def start(tag, attributes):
        element = ET.Element(tag, attributes)
        lines[element] = parser.CurrentLineNumber
        (stack[-1].append(element) if stack else roots.append(element))
        stack.append(element)

    def end(tag):
        stack.pop()

    def refuse(*args):  # a DTD slipped past the text check: never expand it
        raise ValueError("a DTD or entity declaration")

    parser.StartElementHandler = start
    parser.EndElementHandler = end
    parser.StartDoctypeDeclHandler = refuse
    parser.EntityDeclHandler = refuse
    parser.ExternalEntityRefHandler = refuse
    try:
        parser.Parse(text.encode("utf-8"), True)
    except expat.ExpatError as error:
        raise PresetError(path, f"line {error.lineno}", f"is not well-formed XML: "
                          f"{expat.ErrorString(error.code)}", "a URDF or MJCF file") from None  # fmt: skip
    except ValueError as error:
        raise PresetError(path, "(file)", f"has {error}: refused",
                          "plain URDF or MJCF without a DTD") from None  # fmt: skip
    return roots[0], _Reader(path, lines)


# ---------------------------------------------------------------------------------------
# Rotations
# ---------------------------------------------------------------------------------------


def _axis_rotation(axis: np.ndarray, angle: float) -> np.ndarray:
    """Rotation by ``angle`` (rad) about the unit ``axis`` (Rodrigues)."""
    x, y, z = axis
    c, s = math.cos(angle), math.sin(angle)
    t = 1.0 - c
    return np.array(
        [
            [c + x * x * t, x * y * t - z * s, x * z * t + y * s],
            [y * x * t + z * s, c + y * y * t, y * z * t - x * s],
            [z * x * t - y * s, z * y * t + x * s, c + z * z * t],
        ]
    )


def _basis_rotation(index: int, angle: float) -> np.ndarray:
    """Rotation about the x (0), y (1) or z (2) axis; the identity, exactly, at angle 0."""
    if angle == 0.0:
        return np.eye(3)
    axis = np.zeros(3)
    axis[index] = 1.0
    return _axis_rotation(axis, angle)


def rpy_rotation(rpy: np.ndarray) -> np.ndarray:
    """URDF's roll-pitch-yaw (fixed axes x, y, z): ``Rz(yaw) Ry(pitch) Rx(roll)``."""
    roll, pitch, yaw = rpy
    return _basis_rotation(2, yaw) @ _basis_rotation(1, pitch) @ _basis_rotation(0, roll)


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


def _unit(vector: np.ndarray) -> np.ndarray:
    norm = float(np.linalg.norm(vector))
    if norm == 0.0 or not math.isfinite(norm):
        raise ValueError("a zero vector")
    return vector / norm


# ---------------------------------------------------------------------------------------
# The chain: planar checks, then the robot
# ---------------------------------------------------------------------------------------


def _signed_angle(a: np.ndarray, b: np.ndarray, axis: np.ndarray) -> float:
    """The angle (rad) turning ``a`` to ``b`` about ``axis`` (both in its plane)."""
    return math.atan2(float(np.dot(np.cross(a, b), axis)), float(np.dot(a, b)))


def _in_plane(vector: np.ndarray, axis: np.ndarray) -> np.ndarray:
    """``vector`` less its part along the unit ``axis``."""
    return vector - np.dot(vector, axis) * axis


def _length(vector: np.ndarray) -> float:
    return math.hypot(*(float(v) for v in vector))


def planar_robot(chain: Chain, reader: _Reader, source_format: str) -> ImportedRobot:
    """Check a chain is a planar serial revolute arm and make its ``[robot]``."""
    notes = list(chain.notes)
    if not chain.links:
        raise reader.error(None, "has no revolute joint", "a serial chain of revolute joints")
    first = chain.links[0]
    normal = first.world @ first.axis
    lengths, masses, inertias, directions = [], [], [], []
    for link in chain.links:
        world_axis = link.world @ link.axis
        if _length(np.cross(world_axis, normal)) > TOLERANCE or np.dot(world_axis, normal) <= 0:
            raise PresetError(
                reader.path, link.joint,
                f"axis {_shown(world_axis)} (world) is not parallel to the first joint's "
                f"{_shown(normal)}", "every joint turning about the same direction",
            )  # fmt: skip
        offset = _in_plane(link.com - link.joint_point, link.axis)
        if link.next_point is not None:
            along = _in_plane(link.next_point - link.joint_point, link.axis)
            length = _length(along)
            if length <= TOLERANCE * max(_length(link.next_point), 1e-300):
                raise PresetError(reader.path, link.element,
                                  "the next joint is on this joint's axis: the link has no "
                                  "length", "a link of positive length")  # fmt: skip
            direction = along / length
            off_line = _length(np.cross(offset, direction))
            if off_line > TOLERANCE * length:
                raise PresetError(
                    reader.path, link.element,
                    f"centre of mass {off_line:.6g} m off the link line (the line from "
                    "its joint to the next)", "the centre of mass on the link line, at mid-link",
                )  # fmt: skip
            fraction = float(np.dot(offset, direction)) / length
            if abs(fraction - 0.5) > TOLERANCE:
                raise PresetError(
                    reader.path, link.element,
                    f"centre of mass at {100 * fraction:.6g} % of the link from its joint",
                    "the centre of mass at mid-link (50 %), as planar-tui's links have it",
                )  # fmt: skip
        else:
            half = _length(offset)
            if half == 0.0:
                raise PresetError(reader.path, link.element,
                                  "centre of mass on the joint's axis: the last link's "
                                  "length (twice its distance) would be 0",
                                  "the centre of mass at mid-link")  # fmt: skip
            length = 2.0 * half
            direction = offset / half
        if not link.mass_kg > 0:
            raise PresetError(reader.path, link.element, f"mass is {link.mass_kg:g}",
                              "a positive mass (kg)")  # fmt: skip
        unit_axis = link.axis / _length(link.axis)
        inertia = float(unit_axis @ link.inertia @ unit_axis)
        if not inertia > 0:
            raise PresetError(reader.path, link.element,
                              f"moment of inertia about the joint axis is {inertia:g}",
                              "a positive moment of inertia (kg m²)")  # fmt: skip
        lengths.append(length)
        masses.append(link.mass_kg)
        inertias.append(inertia)
        directions.append(link.world @ direction)
    gravity_m_s2, x_axis = _plane_gravity(chain, normal, directions[0], notes)
    offsets = [_signed_angle(x_axis, directions[0], normal)]
    offsets += [_signed_angle(a, b, normal) for a, b in itertools.pairwise(directions)]
    offsets = [
        offset - link.reference_rad for offset, link in zip(offsets, chain.links, strict=True)
    ]
    offsets_deg = tuple(math.degrees(o) if abs(o) > 1e-12 else 0.0 for o in offsets)
    if any(offsets_deg):
        shown = ", ".join(f"{o:.6g}" for o in offsets_deg)
        notes.append(
            "the links are not straight along x at zero joint angles: planar-tui's angles "
            f"are theta_i = q_i + [{shown}] deg (q: the file's joint angles)"
        )
    name = preset_name(chain.name, len(lengths))
    robot = SerialRobot(
        lengths_m=tuple(lengths), masses_kg=tuple(masses), inertias_kgm2=tuple(inertias),
        gravity_m_s2=gravity_m_s2, name=name,
    )  # fmt: skip
    return ImportedRobot(robot, tuple(notes), offsets_deg, source_format)


def _plane_gravity(chain: Chain, normal, first_direction, notes) -> tuple[float, np.ndarray]:
    """``(g, x axis)``: gravity's in-plane magnitude and the plane's x axis (world)."""
    gravity = chain.gravity
    total = _length(gravity)
    in_plane = _in_plane(gravity, normal)
    g = _length(in_plane)
    if total == 0.0 or g <= TOLERANCE * total:
        if total > 0.0:
            notes.append(
                f"gravity {_shown(gravity)} m/s² ({chain.gravity_source}) is along the joint "
                "axes: the arm moves in a horizontal plane, gravity_m_s2 = 0"
            )
        return 0.0, first_direction
    if abs(float(np.dot(gravity, normal))) > TOLERANCE * total:
        notes.append(
            f"gravity {_shown(gravity)} m/s² ({chain.gravity_source}) is tilted from the "
            f"plane: its in-plane part, {g:.6g} m/s², is kept"
        )
    elif chain.gravity_source.startswith("assumed"):
        notes.append(f"gravity {_shown(gravity)} m/s² {chain.gravity_source}")
    up = -in_plane / g
    return g, np.cross(up, normal)


def _shown(vector: np.ndarray) -> str:
    return "(" + ", ".join(f"{float(v):.6g}" for v in vector) + ")"


def preset_name(model_name: str, n_links: int) -> str:
    """The preset's ``name``: the model's, except ``nR``, the label planar-tui gives an
    unnamed robot (and writes as the model's name on export), which reads back as none."""
    return "" if model_name == f"{n_links}R" else model_name


# ---------------------------------------------------------------------------------------
# URDF
# ---------------------------------------------------------------------------------------


def _urdf_origin(reader: _Reader, element: ET.Element) -> Frame:
    origin = element.find("origin")
    if origin is None:
        return Frame()
    xyz = reader.numbers(origin, "xyz", 3, (0.0, 0.0, 0.0))
    rpy = reader.numbers(origin, "rpy", 3, (0.0, 0.0, 0.0))
    return Frame(rpy_rotation(rpy), xyz)


def _urdf_inertial(reader: _Reader, link: ET.Element) -> tuple[float, np.ndarray, np.ndarray]:
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
    reader: _Reader, root: ET.Element, links: dict[str, ET.Element]
) -> list[_UrdfJoint]:
    """Every joint, checked: a known type, two links of the file, one parent per link."""
    joints: list[_UrdfJoint] = []
    children: set[str] = set()
    for element in root.findall("joint"):
        ends = [element.find(tag) for tag in ("parent", "child")]
        names = [None if end is None else end.get("link") for end in ends]
        kind = element.get("type", "")
        if kind not in (*URDF_REVOLUTE, "fixed"):
            raise reader.error(element, f"is a {kind or 'typeless'} joint",
                               "revolute, continuous (or fixed) joints only")  # fmt: skip
        for name in names:
            if name is None or name not in links:
                raise reader.error(element, f"names link {name!r}, which is not in the file",
                                   "<parent link> and <child link> of the file's links")  # fmt: skip
        parent, child = str(names[0]), str(names[1])
        if child in children:
            raise reader.error(element, f"link {child!r} has two parents", "a tree")
        children.add(child)
        joints.append(_UrdfJoint(element, kind, parent, child))
    return joints


def read_urdf(path: Path | str) -> ImportedRobot:
    """A URDF file as a ``[robot]`` (see the module's rules)."""
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
            raise reader.error(leading[1].element, f"is a second chain below link "
                               f"{link_name!r}: a branched tree", "a serial chain")  # fmt: skip
        return leading[0] if leading else None

    def welded(link_name: str, moving_link: str) -> None:
        """Refuse a mass fixed to a moving link (planar-tui does not merge bodies)."""
        for joint in below.get(link_name, []):
            if not leads(joint):
                if _urdf_inertial(reader, links[joint.child])[0] > 0:
                    raise reader.error(links[joint.child], f"has a mass welded to link "
                                       f"{moving_link!r}", "massless fixed links only "
                                       "(merge the mass into the link)")  # fmt: skip
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
                axis = _unit(reader.numbers(axis_element, "xyz", 3, None))
            except ValueError:
                raise reader.error(axis_element, "axis is zero", "a direction") from None
        label = joint.element.get("name")
        if joint.type == "revolute" and joint.element.find("limit") is not None:
            notes.append(f"joint {label!r}: its limits are not kept")
        notes += [f"joint {label!r}: <{tag}> is not kept" for tag in ("dynamics", "mimic")
                  if joint.element.find(tag) is not None]  # fmt: skip
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
                raise reader.error(links[following.child], f"has a mass welded to link "
                                   f"{name!r}", "massless fixed links only")  # fmt: skip
            welded(following.child, name)
            following = chain_joint(following.child)
        next_point = None
        if following is not None:
            next_point = relative.then(_urdf_origin(reader, following.element)).p
        chain.append(Link(
            joint=reader.where(joint.element), element=reader.where(link_element),
            joint_point=np.zeros(3), axis=axis, mass_kg=mass, com=com, inertia=inertia,
            world=frame.R, next_point=next_point,
        ))  # fmt: skip
        world = frame.then(relative)
        joint = following
    return planar_robot(Chain(root.get("name", ""), chain, gravity, source, notes), reader, "URDF")


def _urdf_gravity(reader: _Reader, root: ET.Element) -> tuple[np.ndarray, str]:
    """Gravity from planar-tui's ``<planar_tui>`` element, else ROS's (assumed)."""
    from planar_tui.interop.urdf import GRAVITY_ELEMENT

    element = root.find(GRAVITY_ELEMENT)
    if element is None:
        return np.array(ROS_GRAVITY), "assumed: URDF has no gravity (ROS: z up)"
    g = reader.number(element, "gravity_m_s2", None)
    try:
        direction = _unit(reader.numbers(element, "direction", 3, (0.0, -1.0, 0.0)))
    except ValueError:
        raise reader.error(element, "direction is zero", "a direction") from None
    return g * direction, f"the file's <{GRAVITY_ELEMENT}>"


# ---------------------------------------------------------------------------------------
# MJCF
# ---------------------------------------------------------------------------------------


@dataclass
class _Compiler:
    degrees: bool = True
    eulerseq: str = "xyz"


def _mjcf_rotation(reader: _Reader, element: ET.Element, compiler: _Compiler) -> np.ndarray:
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
            return _axis_rotation(_unit(values[:3]), values[3] * scale)
        if given[0] == "euler":
            angles = reader.numbers(element, "euler", 3, None) * scale
            rotation = np.eye(3)
            for letter, angle in zip(compiler.eulerseq, angles, strict=True):
                turn = _basis_rotation("xyz".index(letter.lower()), float(angle))
                rotation = rotation @ turn if letter.islower() else turn @ rotation
            return rotation
        if given[0] == "xyaxes":
            values = reader.numbers(element, "xyaxes", 6, None)
            x = _unit(values[:3])
            y = _unit(values[3:] - np.dot(values[3:], x) * x)
            return np.column_stack([x, y, np.cross(x, y)])
        z = _unit(reader.numbers(element, "zaxis", 3, None))
        reference = np.array([0.0, 0.0, 1.0])
        turn = np.cross(reference, z)
        if _length(turn) < 1e-15:
            return np.eye(3) if z[2] > 0 else _basis_rotation(0, math.pi)
        return _axis_rotation(_unit(turn), math.acos(max(-1.0, min(1.0, float(z[2])))))
    except ValueError as error:
        raise reader.error(element, f"{given[0]} is {error}", "a valid orientation") from None


def _mjcf_defaults(reader: _Reader, root: ET.Element) -> dict[str, dict[str, str]]:
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
    """An MJCF file as a ``[robot]`` (see the module's rules)."""
    root, reader = read_xml(path)
    if root.tag != "mujoco":
        raise reader.error(root, "is not an MJCF <mujoco> model", "an MJCF file (root <mujoco>)")
    for tag in ("include", "equality", "frame", "replicate"):
        found = next(root.iter(tag), None)
        if found is not None:
            why = {"include": "other files are not read", "equality": "closed loops or "
                   "couplings are not a serial chain"}.get(tag, "not read")  # fmt: skip
            raise reader.error(found, why, f"one file without <{tag}>")
    compiler = _Compiler()
    for element in root.iter("compiler"):
        angle = element.get("angle")
        if angle is not None:
            if angle not in ("degree", "radian"):
                raise reader.error(element, f"angle is {angle!r}", '"degree" or "radian"')
            compiler.degrees = angle == "degree"
        if element.get("inertiafromgeom") == "true":
            raise reader.error(element, "inertiafromgeom is \"true\": the masses are the "
                               "geoms', which are not read", '"auto" or "false" with <inertial>')  # fmt: skip
        for attribute in ("settotalmass", "boundmass", "boundinertia", "balanceinertia"):
            if element.get(attribute) not in (None, "-1", "0", "false"):
                raise reader.error(element, f"{attribute} changes the masses MuJoCo uses: "
                                   "not read", f"a <compiler> without {attribute}")  # fmt: skip
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
            raise reader.error(leading[1], f"is a second moving chain below {reader.named(body)}:"
                               " a branched tree", "a serial chain")  # fmt: skip
        return leading[0] if leading else None

    def frame_of(body: ET.Element) -> Frame:
        return Frame(_mjcf_rotation(reader, body, compiler),
                     reader.numbers(body, "pos", 3, (0.0, 0.0, 0.0)))  # fmt: skip

    def check_welded(body: ET.Element, moving_body: ET.Element) -> None:
        for child in body.findall("body"):
            if not moving(child):
                inertial = child.find("inertial")
                if inertial is not None and reader.number(inertial, "mass", None) > 0:
                    raise reader.error(child, f"has a mass welded to {reader.named(moving_body)}",
                                       "massless fixed bodies only (merge the mass)")  # fmt: skip
                check_welded(child, moving_body)

    tops = [body for world in worldbodies for body in world.findall("body") if moving(body)]
    if len(tops) > 1:
        raise reader.error(tops[1], "is a second moving chain in the world: a branched tree",
                           "one serial chain")  # fmt: skip

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
            axis = _unit(reader.numbers(resolved, "axis", 3, (0.0, 0.0, 1.0)))
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
            raise reader.error(body, "has no <inertial>" + (" (inertia from geoms is not "
                               "computed)" if has_geoms else ""),
                               "an <inertial> element with mass and inertia")  # fmt: skip
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
                raise reader.error(following, f"has a mass welded to {reader.named(body)}",
                                   "massless fixed bodies only")  # fmt: skip
            relative = relative.then(frame_of(following))
            check_welded(following, body)
            following = next_body(following)
        next_point = None
        if following is not None:
            child_frame = relative.then(frame_of(following))
            child_joints = joints_of(following)
            child_point = (reader.numbers(child_joints[0], "pos", 3, (0.0, 0.0, 0.0))
                           if len(child_joints) == 1 else np.zeros(3))  # fmt: skip
            next_point = child_frame.point(child_point)
        chain.append(Link(
            joint=reader.where(joint), element=reader.where(body), joint_point=joint_point,
            axis=axis, mass_kg=mass, com=reader.numbers(inertial, "pos", 3, None),
            inertia=rotation @ tensor @ rotation.T, world=frame.R, next_point=next_point,
            reference_rad=reference,
        ))  # fmt: skip
        world = frame.then(relative)
        body = following
    source = (
        "the file's <option gravity>" if root.find("option") is not None else "MuJoCo's default"
    )
    return planar_robot(Chain(root.get("model", ""), chain, gravity, source, notes), reader, "MJCF")


def read_robot(path: Path | str) -> ImportedRobot:
    """A URDF (``.urdf``) or MJCF (``.xml``, ``.mjcf``) file as a ``[robot]``."""
    suffix = Path(path).suffix.lower()
    if suffix in URDF_SUFFIXES:
        return read_urdf(path)
    if suffix in MJCF_SUFFIXES:
        return read_mjcf(path)
    raise PresetError(path, "(file)", f"has the suffix {suffix or '(none)'!r}",
                      "a .urdf (URDF) or .xml/.mjcf (MJCF) file")  # fmt: skip


def preset_text(imported: ImportedRobot, source: Path | str) -> str:
    """The ``[robot]`` preset of an imported robot, its notes as comments."""
    from planar_tui import __version__
    from planar_tui.dynamics.robot import ROBOT_KIND
    from planar_tui.preset_writer import dump_document

    lines = [f"{imported.robot.label} imported from {Path(source).name} "
             f"({imported.source_format}) by planar-tui {__version__}."]  # fmt: skip
    lines += [f"Note: {note}." for note in imported.notes]
    return dump_document({"robot": ROBOT_KIND.dump(imported.robot)}, "\n".join(lines))

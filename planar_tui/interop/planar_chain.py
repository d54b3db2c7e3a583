r"""A chain read from a URDF or MJCF file, checked planar, as a ``[robot]`` preset.

The readers (:mod:`.urdf_import`, :mod:`.mjcf_import`) turn a file into a :class:`Chain`
of :class:`Link` s, each in its own frame (:class:`Frame`: positions and rotations composed
as read); :func:`planar_robot` checks it is a planar serial revolute arm and makes its
:class:`~planar_tui.dynamics.robot.SerialRobot` (lengths :math:`l_i`, masses, moments
:math:`k^T J k` about the axis, in-plane gravity, angle offsets :math:`\Delta_i`, with the
notes), and :func:`preset_text` writes it as a preset. The rules are in
:mod:`.robot_import`.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from planar_tui import __version__
from planar_tui.dynamics.robot import ROBOT_KIND, SerialRobot
from planar_tui.errors import PresetError
from planar_tui.interop.robot_xml import XmlReader
from planar_tui.preset_writer import dump_document

#: Relative tolerance of "parallel", "on the link line" and "at mid-link".
TOLERANCE = 1e-9


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
# Rotations and vectors
# ---------------------------------------------------------------------------------------


def axis_rotation(axis: np.ndarray, angle: float) -> np.ndarray:
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


def basis_rotation(index: int, angle: float) -> np.ndarray:
    """Rotation about the x (0), y (1) or z (2) axis; the identity, exactly, at angle 0."""
    if angle == 0.0:
        return np.eye(3)
    axis = np.zeros(3)
    axis[index] = 1.0
    return axis_rotation(axis, angle)


def unit(vector: np.ndarray) -> np.ndarray:
    """``vector`` over its length; ``ValueError`` for a zero or non-finite one."""
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


def vector_length(vector: np.ndarray) -> float:
    """The Euclidean length of ``vector`` (``math.hypot`` of its components)."""
    return math.hypot(*(float(v) for v in vector))


def planar_robot(chain: Chain, reader: XmlReader, source_format: str) -> ImportedRobot:
    """Check a chain is a planar serial revolute arm and make its ``[robot]``."""
    notes = list(chain.notes)
    if not chain.links:
        raise reader.error(None, "has no revolute joint", "a serial chain of revolute joints")
    first = chain.links[0]
    normal = first.world @ first.axis
    lengths, masses, inertias, directions = [], [], [], []
    for link in chain.links:
        world_axis = link.world @ link.axis
        if (
            vector_length(np.cross(world_axis, normal)) > TOLERANCE
            or np.dot(world_axis, normal) <= 0
        ):
            raise PresetError(
                reader.path,
                link.joint,
                f"axis {_shown(world_axis)} (world) is not parallel to the first joint's "
                f"{_shown(normal)}",
                "every joint turning about the same direction",
            )
        offset = _in_plane(link.com - link.joint_point, link.axis)
        if link.next_point is not None:
            along = _in_plane(link.next_point - link.joint_point, link.axis)
            length = vector_length(along)
            if length <= TOLERANCE * max(vector_length(link.next_point), 1e-300):
                raise PresetError(
                    reader.path,
                    link.element,
                    "the next joint is on this joint's axis: the link has no length",
                    "a link of positive length",
                )
            direction = along / length
            off_line = vector_length(np.cross(offset, direction))
            if off_line > TOLERANCE * length:
                raise PresetError(
                    reader.path,
                    link.element,
                    f"centre of mass {off_line:.6g} m off the link line (the line from "
                    "its joint to the next)",
                    "the centre of mass on the link line, at mid-link",
                )
            fraction = float(np.dot(offset, direction)) / length
            if abs(fraction - 0.5) > TOLERANCE:
                raise PresetError(
                    reader.path,
                    link.element,
                    f"centre of mass at {100 * fraction:.6g} % of the link from its joint",
                    "the centre of mass at mid-link (50 %), as planar-tui's links have it",
                )
        else:
            half = vector_length(offset)
            if half == 0.0:
                raise PresetError(
                    reader.path,
                    link.element,
                    "centre of mass on the joint's axis: the last link's "
                    "length (twice its distance) would be 0",
                    "the centre of mass at mid-link",
                )
            length = 2.0 * half
            direction = offset / half
        if not link.mass_kg > 0:
            raise PresetError(
                reader.path, link.element, f"mass is {link.mass_kg:g}", "a positive mass (kg)"
            )
        unit_axis = link.axis / vector_length(link.axis)
        inertia = float(unit_axis @ link.inertia @ unit_axis)
        if not inertia > 0:
            raise PresetError(
                reader.path,
                link.element,
                f"moment of inertia about the joint axis is {inertia:g}",
                "a positive moment of inertia (kg m²)",
            )
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
        lengths_m=tuple(lengths),
        masses_kg=tuple(masses),
        inertias_kgm2=tuple(inertias),
        gravity_m_s2=gravity_m_s2,
        name=name,
    )
    return ImportedRobot(robot, tuple(notes), offsets_deg, source_format)


def _plane_gravity(chain: Chain, normal, first_direction, notes) -> tuple[float, np.ndarray]:
    """``(g, x axis)``: gravity's in-plane magnitude and the plane's x axis (world)."""
    gravity = chain.gravity
    total = vector_length(gravity)
    in_plane = _in_plane(gravity, normal)
    g = vector_length(in_plane)
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


def preset_text(imported: ImportedRobot, source: Path | str) -> str:
    """The ``[robot]`` preset of an imported robot, its notes as comments."""
    lines = [
        f"{imported.robot.label} imported from {Path(source).name} "
        f"({imported.source_format}) by planar-tui {__version__}."
    ]
    lines += [f"Note: {note}." for note in imported.notes]
    return dump_document({"robot": ROBOT_KIND.dump(imported.robot)}, "\n".join(lines))

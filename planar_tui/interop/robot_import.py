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

Where: the safe XML reading and the refusals' line format in :mod:`.robot_xml`, URDF in
:mod:`.urdf_import`, MJCF and its orientation forms in :mod:`.mjcf_import`, the chain's
planar checks and its ``[robot]`` preset in :mod:`.planar_chain`; this module picks the
reader by suffix and keeps the names the others import.
"""

from __future__ import annotations

from pathlib import Path

from planar_tui.errors import PresetError
from planar_tui.interop.mjcf_import import quaternion_rotation, read_mjcf
from planar_tui.interop.planar_chain import (
    TOLERANCE,
    Chain,
    Frame,
    ImportedRobot,
    Link,
    planar_robot,
    preset_name,
    preset_text,
)
from planar_tui.interop.robot_xml import MAX_BYTES, read_xml
from planar_tui.interop.urdf_import import ROS_GRAVITY, URDF_REVOLUTE, read_urdf, rpy_rotation

__all__ = [
    "MAX_BYTES",
    "MJCF_SUFFIXES",
    "ROS_GRAVITY",
    "TOLERANCE",
    "URDF_REVOLUTE",
    "URDF_SUFFIXES",
    "Chain",
    "Frame",
    "ImportedRobot",
    "Link",
    "planar_robot",
    "preset_name",
    "preset_text",
    "quaternion_rotation",
    "read_mjcf",
    "read_robot",
    "read_urdf",
    "read_xml",
    "rpy_rotation",
]

#: What the CLI accepts: URDF by suffix, MJCF (``.xml``, ``.mjcf``) otherwise.
URDF_SUFFIXES = (".urdf",)
MJCF_SUFFIXES = (".xml", ".mjcf")


def read_robot(path: Path | str) -> ImportedRobot:
    """A URDF (``.urdf``) or MJCF (``.xml``, ``.mjcf``) file as a ``[robot]``."""
    suffix = Path(path).suffix.lower()
    if suffix in URDF_SUFFIXES:
        return read_urdf(path)
    if suffix in MJCF_SUFFIXES:
        return read_mjcf(path)
    raise PresetError(
        path,
        "(file)",
        f"has the suffix {suffix or '(none)'!r}",
        "a .urdf (URDF) or .xml/.mjcf (MJCF) file",
    )

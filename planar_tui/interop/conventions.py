r"""The planar serial robot as MuJoCo and URDF see it: conventions shared by the exporters.

planar-tui's ``[robot]`` (:class:`~planar_tui.dynamics.robot.SerialRobot`, paper A) is an
n-link arm in a vertical plane: relative joint angles :math:`\theta_i` (all links along
+x at :math:`\theta = 0`), gravity :math:`g` along −y, link i of length :math:`l_i` with
its mass :math:`m_i` at mid-link and its moment of inertia :math:`I_i` about its centre of
mass, perpendicular to the plane. The exported models keep all of that:

* the plane of motion is the x-y plane of the model's world frame, every joint turns
  about +z (so a positive angle is counter-clockwise seen from +z, as in planar-tui);
* link i's frame sits on joint i, ``l_{i-1}`` along the parent's x axis (link 1's on the
  world origin), so the models' joint coordinates *are* planar-tui's relative angles;
* link i's centre of mass is at ``(l_i / 2, 0, 0)`` in its frame, its inertia tensor about
  the centre of mass is ``diag(a_i, I_i, I_i)``: only :math:`I_{zz} = I_i` enters planar
  motion; :math:`I_{yy} = I_i` and a tiny axial moment ``a_i`` (:func:`axial_inertia_kgm2`)
  make it a slender rod along x, which satisfies MuJoCo's triangle inequality
  (A + B ≥ C for the principal moments) and its smallest accepted moment;
* gravity is ``(0, −g, 0)`` (MJCF ``<option gravity>``; URDF has no gravity: see
  :mod:`.urdf`).

Numbers are written with Python's ``repr`` of a float (the shortest text that reads back
as the same double), so an export read back gives the preset's values exactly.
"""

from __future__ import annotations

import re

#: The axial moment of a link is this fraction of its I_zz (a slender rod's is ~0) ...
AXIAL_INERTIA_FRACTION = 1e-6
#: ... but at least MuJoCo's smallest accepted principal moment (``mjMINVAL``, kg m²).
MUJOCO_MIN_VALUE = 1e-15


def axial_inertia_kgm2(inertia_kgm2: float) -> float:
    """The moment about the link's own axis (x): ``max(1e-6 I, 1e-15)`` kg m².

    It never enters planar motion (every link turns about z only, so the z torques depend
    on I_zz alone); MuJoCo needs it positive and the principal moments ``(a, I, I)`` to
    satisfy the triangle inequality ``a ≤ 2 I``, which holds whenever I itself is at least
    MuJoCo's ``mjMINVAL`` (below that MuJoCo refuses the model anyway)."""
    return max(AXIAL_INERTIA_FRACTION * inertia_kgm2, MUJOCO_MIN_VALUE)


def number(value: float) -> str:
    """A float as XML text: its shortest exact form (``repr``), ``0.3``, ``1e-50``."""
    return repr(float(value))


def vector(*values: float) -> str:
    """Space-separated numbers (:func:`number`), as MJCF and URDF write vectors."""
    return " ".join(number(value) for value in values)


#: What XML 1.0 cannot hold, even escaped: characters outside its ``Char`` production
#: (``#x9 | #xA | #xD | [#x20-#xD7FF] | [#xE000-#xFFFD] | [#x10000-#x10FFFF]``): the C0
#: controls but tab and newlines, lone surrogates, U+FFFE and U+FFFF.
_NOT_XML_CHAR = re.compile("[^\t\n\r\x20-\ud7ff\ue000-\ufffd\U00010000-\U0010ffff]")


def xml_chars(text: str) -> str:
    """``text`` with every character XML cannot hold (:data:`_NOT_XML_CHAR`: NUL, ESC,
    BEL …) replaced by U+FFFD, so that any XML parser (and planar-tui's own ``import``)
    reads the file written."""
    return _NOT_XML_CHAR.sub("\ufffd", text)


def xml_comment(text: str) -> str:
    """An XML comment of ``text`` (``--`` cannot appear inside one: it becomes ``- -``;
    characters XML cannot hold become U+FFFD, :func:`xml_chars`)."""
    text = xml_chars(text)
    while "--" in text:
        text = text.replace("--", "- -")
    return f"<!--\n{text.rstrip()}\n-->"


def robot_label(robot) -> str:
    """The model's name: the robot's ``name``, else its label ``nR`` (an importer reads
    ``nR`` back as no name: :func:`planar_tui.interop.planar_chain.preset_name`), in
    characters XML can hold (:func:`xml_chars`)."""
    return xml_chars(robot.name or robot.label)

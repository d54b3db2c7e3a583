"""A parallel robot (:class:`~.closed_chain.ClosedChain`) as MJCF, the ``export --robot
robot3rrr|robot5r --format mjcf`` file.

The spanning tree, under one fixed body ``base`` (Pinocchio's MJCF reader follows only
the first body of ``<worldbody>``): per leg a body ``proximal{i}`` at the base joint with the
actuated hinge ``theta{i}`` (absolute angle from x), its child ``distal{i}`` at the
proximal link's end with the hinge ``psi{i}`` (relative angle), a site ``tip{i}`` at the
distal link's end; the end body ``platform`` (3-RRR) or ``end`` (five-bar) on the base
with the slides ``x``, ``y`` and (platform) the hinge ``phi``, a site ``point{i}`` at each
point :math:`q_i` where leg i is pinned. The loops close by ``<connect site1="tip{i}"
site2="point{i}">`` equality constraints (a 3-D point constraint: its z row is satisfied
by every planar motion). A keyframe ``home`` holds the assembled home pose (its loop
residual is zero to rounding); ``qpos0`` (all zero) is not assembled. One ``motor`` per
actuated hinge (gear 1): ``ctrl`` = the actuator's torque in N m, counter-clockwise
positive. Masses as :mod:`.mjcf` (centres of mass at mid-link, inertia ``diag(a, I, I)``
of a slender rod; the platform's ``diag(I/2, I/2, I)`` of a flat plate; the end point's a
point mass). Equality constraints keep MuJoCo's default ``solref``/``solimp``: MuJoCo's
constraints are soft, see docs/closed-chain-export.md for the figures.
"""

from __future__ import annotations

from xml.sax.saxutils import quoteattr

from planar_tui import __version__
from planar_tui.interop.closed_chain import ClosedChain
from planar_tui.interop.conventions import (
    MUJOCO_MIN_VALUE,
    axial_inertia_kgm2,
    number,
    vector,
    xml_chars,
    xml_comment,
)

#: Radius of a link's capsule geom (viewer only), as a fraction of the shortest link.
GEOM_RADIUS_FRACTION = 0.04


def header_comment(chain: ClosedChain) -> str:
    """The file's comment: where it comes from and the conventions it follows."""
    end = "platform" if chain.rotates else "end"
    coordinates = "x, y, phi" if chain.rotates else "x, y"
    return xml_comment(
        f"{chain.label} exported by planar-tui {__version__} (MJCF, closed chain).\n"
        "Plane of motion: x-y, lengths in m. Per leg i: hinge theta{i} (actuated, absolute\n"
        "angle of the proximal link from +x) at the base joint, hinge psi{i} (the distal\n"
        f"link's angle relative to the proximal link) at the elbow; the {end} body slides\n"
        f"({coordinates}). Loops: connect constraints tip{{i}} = point{{i}} (MuJoCo's\n"
        "default solref/solimp: soft). Keyframe 'home': the assembled home pose (from\n"
        f"{chain.home_source}); qpos0 is not assembled. Motors motor{{i}} on theta{{i}}\n"
        "(gear 1): ctrl = torque (N m), counter-clockwise positive.\n"
        f"Gravity: (0, -g, 0), g = {number(chain.gravity_m_s2)} m/s2. Centres of mass at\n"
        "mid-link, inertia diag(a, I, I) about them (a: a tiny axial moment); no contact,\n"
        "damping, friction or joint limits."
    )


def _inertial(indent: str, com: tuple[float, float], mass: float, moments) -> str:
    """An ``<inertial>`` element; MuJoCo refuses moving bodies lighter than its
    ``mjMINVAL`` (1e-15), so a massless body gets that mass and moments (whose effect on
    the dynamics is below double rounding of any other mass)."""
    mass = max(mass, MUJOCO_MIN_VALUE)
    moments = tuple(max(value, MUJOCO_MIN_VALUE) for value in moments)
    return (
        f'{indent}<inertial pos="{vector(*com, 0.0)}" mass="{number(mass)}"'
        f' diaginertia="{vector(*moments)}"/>'
    )


def _rod(indent: str, name: str, length: float, mass: float, inertia: float, radius: float):
    return [
        _inertial(
            indent, (0.5 * length, 0.0), mass, (axial_inertia_kgm2(inertia),) + (inertia,) * 2
        ),
        f'{indent}<geom name="{name}" type="capsule" fromto="0 0 0 {number(length)} 0 0"'
        f' size="{number(radius)}" contype="0" conaffinity="0"/>',
    ]


def chain_mjcf(chain: ClosedChain) -> str:
    """MJCF text of ``chain`` (see the module's conventions)."""
    radius = GEOM_RADIUS_FRACTION * min(min(leg.proximal_m, leg.distal_m) for leg in chain.legs)
    lines = [
        header_comment(chain),
        f"<mujoco model={quoteattr(xml_chars(chain.label))}>",
        '  <compiler angle="radian" inertiafromgeom="false" autolimits="true"/>',
        f'  <option gravity="{vector(0.0, -chain.gravity_m_s2, 0.0)}"/>',
        "  <worldbody>",
        '    <body name="base">',
        '      <inertial pos="0 0 0" mass="0" diaginertia="0 0 0"/>',
    ]
    bodies: list[str] = []  # the base's children, indented below
    for i, leg in enumerate(chain.legs, start=1):
        bodies += [
            f'    <body name="proximal{i}" pos="{vector(*leg.base_m, 0.0)}">',
            f'      <joint name="theta{i}" type="hinge" axis="0 0 1"/>',
            *_rod(
                "      ",
                f"proximal{i}",
                leg.proximal_m,
                leg.proximal_mass_kg,
                leg.proximal_inertia_kgm2,
                radius,
            ),
            f'      <body name="distal{i}" pos="{vector(leg.proximal_m, 0.0, 0.0)}">',
            f'        <joint name="psi{i}" type="hinge" axis="0 0 1"/>',
            *_rod(
                "        ",
                f"distal{i}",
                leg.distal_m,
                leg.distal_mass_kg,
                leg.distal_inertia_kgm2,
                radius,
            ),
            f'        <site name="tip{i}" pos="{vector(leg.distal_m, 0.0, 0.0)}"/>',
            "      </body>",
            "    </body>",
        ]
    end = "platform" if chain.rotates else "end"
    inertia = chain.end_inertia_kgm2
    bodies += [
        f'    <body name="{end}">',
        '      <joint name="x" type="slide" axis="1 0 0"/>',
        '      <joint name="y" type="slide" axis="0 1 0"/>',
    ]
    if chain.rotates:
        bodies.append('      <joint name="phi" type="hinge" axis="0 0 1"/>')
    bodies.append(
        _inertial("      ", (0.0, 0.0), chain.end_mass_kg, (0.5 * inertia, 0.5 * inertia, inertia))
    )
    bodies += [
        f'      <site name="point{i}" pos="{vector(*point, 0.0)}"/>'
        for i, point in enumerate(chain.end_points_m, start=1)
    ]
    bodies.append("    </body>")
    lines += ["  " + line for line in bodies]
    lines += ["    </body>", "  </worldbody>", "  <equality>"]
    lines += [
        f'    <connect name="loop{i}" site1="tip{i}" site2="point{i}"/>'
        for i in range(1, len(chain.legs) + 1)
    ]
    lines += ["  </equality>", "  <actuator>"]
    lines += [
        f'    <motor name="motor{i}" joint="theta{i}" gear="1"/>'
        for i in range(1, len(chain.legs) + 1)
    ]
    lines += [
        "  </actuator>",
        "  <keyframe>",
        f'    <key name="home" qpos="{vector(*chain.home_qpos)}"/>',
        "  </keyframe>",
        "</mujoco>",
    ]
    return "\n".join(lines) + "\n"

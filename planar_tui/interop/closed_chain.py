r"""The planar parallel robots (3-RRR, five-bar) as closed chains of rigid bodies in SI
units, assembled at their home pose: what the MJCF writer (:mod:`.closed_mjcf`) writes.

Each leg ``i`` is a spanning-tree branch from the ground: a proximal link of length
:math:`l_1` turning about its base joint :math:`A_i` (the actuated hinge, its coordinate
the absolute angle :math:`\theta_i` from the x axis) and a distal link of length
:math:`l_2` on the elbow hinge :math:`B_i = A_i + l_1(\cos\theta_i, \sin\theta_i)` (its
coordinate the relative angle :math:`\psi_i`, the distal link at :math:`\theta_i + \psi_i`).
The end body (the 3-RRR's platform, the five-bar's end point :math:`P`) is a second
branch with its own planar coordinates: two slides :math:`x, y` and, for the platform, a
hinge :math:`\varphi`. A loop closes where leg ``i``'s distal tip meets the end body's point
:math:`C_i = (x, y) + R(\varphi) q_i`: one point constraint per leg (the tree has
``2n + 3`` coordinates for the 3-RRR, ``2n + 2`` for the five-bar, and the ``2n`` planar
closure equations leave its 3 or 2 degrees of freedom).

Masses follow the robot tables: each link's centre of mass at mid-link with its moment
about the centre of mass, the platform's centre of mass at the platform frame's origin,
the five-bar's end mass a point at :math:`P`; gravity along −y.

The home pose: the start of the preset's first path job on that robot (``from_pose`` in
its working mode ``elbow``, as the job resolves it), so that the job's efforts replay from
the keyframe; without one, the 3-RRR's platform with its points' centroid over the base
joints' centroid at :math:`\varphi = 0`, the five-bar's :math:`P` on the base's perpendicular
bisector (at :math:`x` midway between the base joints) at the height where the first leg
is at its middle reach :math:`\sqrt{l_1^2 + l_2^2}`. The working modes (the elbow signs
:math:`\sigma_i`, :math:`\theta_i = \alpha_i + \sigma_i\beta_i` as in
:func:`planar_tui.workspace.paving.legs.branch_angles`): the 3-RRR's ``(1, -1, 1)`` (the
bundled presets' mode), the five-bar's ``working_mode`` (``+-``, both elbows outwards,
where it is ``any``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from planar_tui.errors import PresetError
from planar_tui.workspace.paving.legs import branch_angles

#: cm per metre: presets give lengths in cm, the exported model is in SI.
CM_PER_M = 100.0
#: The home pose's working modes (module docstring).
HOME_ELBOWS_3RRR = (1, -1, 1)
HOME_ELBOWS_5R = (1, -1)


@dataclass(frozen=True)
class Leg:
    """One RR leg in SI units, with its home coordinates."""

    base_m: tuple[float, float]
    proximal_m: float
    distal_m: float
    proximal_mass_kg: float
    proximal_inertia_kgm2: float
    distal_mass_kg: float
    distal_inertia_kgm2: float
    theta_rad: float
    psi_rad: float


@dataclass(frozen=True)
class ClosedChain:
    """A parallel robot as legs and an end body (``rotates``: the 3-RRR's platform has a
    hinge ``phi``, the five-bar's end point only slides), at its home pose."""

    label: str
    legs: tuple[Leg, ...]
    end_points_m: tuple[tuple[float, float], ...]
    end_mass_kg: float
    end_inertia_kgm2: float
    rotates: bool
    pose: tuple[float, float, float]
    gravity_m_s2: float
    #: Where the home pose comes from: a path job's ``from_pose``, or the robot's table.
    home_source: str

    @property
    def home_qpos(self) -> tuple[float, ...]:
        """The tree's coordinates at home, in the model's joint order: per leg
        :math:`\\theta_i, \\psi_i`, then :math:`x, y` (and :math:`\\varphi`)."""
        legs = tuple(value for leg in self.legs for value in (leg.theta_rad, leg.psi_rad))
        return legs + (self.pose if self.rotates else self.pose[:2])


@dataclass(frozen=True)
class Home:
    """A home pose: ``pose`` ``(x_cm, y_cm[, phi_deg])``, the working mode ``elbow``, and
    ``where`` it comes from (the table, or the path job's ``from_pose``) for a refusal."""

    pose: tuple[float, ...]
    elbow: tuple[int, ...]
    where: str


#: The leg masses' keys (one value for every leg), in :class:`Leg`'s order.
LEG_MASS_KEYS = (
    "proximal_mass_kg",
    "proximal_inertia_kgm2",
    "distal_mass_kg",
    "distal_inertia_kgm2",
)


def _legs(robot, source, home: Home, lengths_cm, targets_cm) -> tuple[Leg, ...]:
    """The legs ``(l1, l2)`` from the robot's base joints to their points ``targets_cm``
    at the home pose, in its working modes; a leg that cannot reach is refused."""
    m1, i1, m2, i2 = (float(getattr(robot, key)) for key in LEG_MASS_KEYS)
    legs = []
    for index, (base, (l1, l2), target, elbow) in enumerate(
        zip(robot.base_joints_cm(), lengths_cm, targets_cm, home.elbow, strict=True), start=1
    ):
        angles = branch_angles(target[0] - base[0], target[1] - base[1], l1, l2)
        if angles is None:
            pose = ", ".join(f"{value:g}" for value in home.pose)
            raise PresetError(
                source,
                home.where,
                f"leg {index} cannot reach the home pose ({pose})",
                "a pose all legs reach (docs/closed-chain-export.md)",
            )
        theta = angles[elbow]
        elbow_x, elbow_y = base[0] + l1 * math.cos(theta), base[1] + l1 * math.sin(theta)
        distal = math.atan2(target[1] - elbow_y, target[0] - elbow_x)
        base_m = (base[0] / CM_PER_M, base[1] / CM_PER_M)
        psi = math.remainder(distal - theta, 2.0 * math.pi)
        legs.append(Leg(base_m, l1 / CM_PER_M, l2 / CM_PER_M, m1, i1, m2, i2, theta, psi))
    return tuple(legs)


def rrr_chain(robot, source, home: Home | None = None) -> ClosedChain:
    """The 3-RRR (``[robot3rrr]``) at ``home`` (default: the module docstring's)."""
    bases = robot.base_joints_cm()
    points = robot.platform_points_cm()
    if home is None:
        x = sum(a[0] for a in bases) / 3.0 - sum(q[0] for q in points) / 3.0
        y = sum(a[1] for a in bases) / 3.0 - sum(q[1] for q in points) / 3.0
        home = Home((x, y, 0.0), HOME_ELBOWS_3RRR, "[robot3rrr]")
    x, y, phi_deg = home.pose
    c, s = math.cos(math.radians(phi_deg)), math.sin(math.radians(phi_deg))
    targets = [(x + c * qx - s * qy, y + s * qx + c * qy) for qx, qy in points]
    lengths = [(robot.proximal_cm, robot.distal_cm)] * 3
    return ClosedChain(
        robot.name or "3-RRR",
        _legs(robot, source, home, lengths, targets),
        tuple((qx / CM_PER_M, qy / CM_PER_M) for qx, qy in points),
        float(robot.platform_mass_kg),
        float(robot.platform_inertia_kgm2),
        True,
        (x / CM_PER_M, y / CM_PER_M, math.radians(phi_deg)),
        float(robot.gravity_m_s2),
        home.where,
    )


def fivebar_chain(robot, source, home: Home | None = None) -> ClosedChain:
    """The five-bar (``[robot5r]``) at ``home`` (default: the module docstring's)."""
    if home is None:
        bases = robot.base_joints_cm()
        x = 0.5 * (bases[0][0] + bases[1][0])
        reach = math.hypot(robot.proximal_cm[0], robot.distal_cm[0])
        half = x - bases[0][0]
        y = math.sqrt(max(reach * reach - half * half, 0.0))
        elbow = HOME_ELBOWS_5R if robot.working_mode == "any" else robot.elbows
        home = Home((x, y), elbow, "[robot5r]")
    x, y = home.pose
    lengths = list(zip(robot.proximal_cm, robot.distal_cm, strict=True))
    return ClosedChain(
        robot.name or "five-bar",
        _legs(robot, source, home, lengths, [(x, y)] * 2),
        ((0.0, 0.0), (0.0, 0.0)),
        float(robot.end_mass_kg),
        0.0,
        False,
        (x / CM_PER_M, y / CM_PER_M, 0.0),
        float(robot.gravity_m_s2),
        home.where,
    )

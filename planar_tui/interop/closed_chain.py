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

    @property
    def home_qpos(self) -> tuple[float, ...]:
        """The tree's coordinates at home, in the model's joint order: per leg
        :math:`\\theta_i, \\psi_i`, then :math:`x, y` (and :math:`\\varphi`)."""
        legs = tuple(value for leg in self.legs for value in (leg.theta_rad, leg.psi_rad))
        return legs + (self.pose if self.rotates else self.pose[:2])


def _per_leg(value, count: int) -> tuple[float, ...]:
    """A table value given once for all legs or once per leg, as one float per leg."""
    values = tuple(value) if isinstance(value, (tuple, list)) else (value,) * count
    return tuple(float(item) for item in values)


def _leg(robot, base_cm, l1_cm, l2_cm, point_cm, elbow: int, index: int, masses) -> Leg:
    """Leg ``index`` (0-based) reaching ``point_cm`` in the working mode ``elbow``."""
    vx, vy = point_cm[0] - base_cm[0], point_cm[1] - base_cm[1]
    angles = branch_angles(vx, vy, l1_cm, l2_cm)
    if angles is None:
        raise PresetError(
            robot.source,
            robot.table,
            f"leg {index + 1} cannot reach the home pose {robot.home_text}",
            "a robot whose legs reach the home pose (module planar_tui.interop.closed_chain)",
        )
    theta = angles[elbow]
    elbow_x = base_cm[0] + l1_cm * math.cos(theta)
    elbow_y = base_cm[1] + l1_cm * math.sin(theta)
    distal = math.atan2(point_cm[1] - elbow_y, point_cm[0] - elbow_x)
    psi = math.remainder(distal - theta, 2.0 * math.pi)
    m1, i1, m2, i2 = (values[index] for values in masses)
    return Leg(
        (base_cm[0] / CM_PER_M, base_cm[1] / CM_PER_M),
        l1_cm / CM_PER_M,
        l2_cm / CM_PER_M,
        m1,
        i1,
        m2,
        i2,
        theta,
        psi,
    )


@dataclass(frozen=True)
class Home:
    """A home pose given by a path job: ``pose`` ``(x_cm, y_cm[, phi_deg])``, the working
    mode ``elbow`` and ``where`` (the job's key) for a refusal."""

    pose: tuple[float, ...]
    elbow: tuple[int, ...]
    where: str


@dataclass(frozen=True)
class _Named:
    """Where a refusal points: the preset and the robot's table (or path job)."""

    source: object
    table: str
    home_text: str


def _leg_masses(robot, count: int):
    return tuple(
        _per_leg(getattr(robot, key), count)
        for key in (
            "proximal_mass_kg",
            "proximal_inertia_kgm2",
            "distal_mass_kg",
            "distal_inertia_kgm2",
        )
    )


def rrr_chain(robot, source, home: Home | None = None) -> ClosedChain:
    """The 3-RRR (``[robot3rrr]``) at its home pose (module docstring)."""
    bases = robot.base_joints_cm()
    points = robot.platform_points_cm()
    if home is None:
        x = sum(a[0] for a in bases) / 3.0 - sum(q[0] for q in points) / 3.0
        y = sum(a[1] for a in bases) / 3.0 - sum(q[1] for q in points) / 3.0
        home = Home((x, y, 0.0), HOME_ELBOWS_3RRR, "[robot3rrr]")
    x, y, phi_deg = home.pose
    named = _Named(source, home.where, f"(x, y, phi) = ({x:g} cm, {y:g} cm, {phi_deg:g} deg)")
    masses = _leg_masses(robot, 3)
    c, s = math.cos(math.radians(phi_deg)), math.sin(math.radians(phi_deg))
    legs = tuple(
        _leg(
            named,
            a,
            robot.proximal_cm,
            robot.distal_cm,
            (x + c * qx - s * qy, y + s * qx + c * qy),
            elbow,
            i,
            masses,
        )
        for i, (a, (qx, qy), elbow) in enumerate(zip(bases, points, home.elbow, strict=True))
    )
    return ClosedChain(
        robot.name or "3-RRR",
        legs,
        tuple((qx / CM_PER_M, qy / CM_PER_M) for qx, qy in points),
        float(robot.platform_mass_kg),
        float(robot.platform_inertia_kgm2),
        True,
        (x / CM_PER_M, y / CM_PER_M, math.radians(phi_deg)),
        float(robot.gravity_m_s2),
    )


def fivebar_chain(robot, source, home: Home | None = None) -> ClosedChain:
    """The five-bar (``[robot5r]``) at its home pose (module docstring)."""
    bases = robot.base_joints_cm()
    if home is None:
        x = 0.5 * (bases[0][0] + bases[1][0])
        reach = math.hypot(robot.proximal_cm[0], robot.distal_cm[0])
        half = x - bases[0][0]
        y = math.sqrt(max(reach * reach - half * half, 0.0))
        elbow = HOME_ELBOWS_5R if robot.working_mode == "any" else robot.elbows
        home = Home((x, y), elbow, "[robot5r]")
    x, y = home.pose
    named = _Named(source, home.where, f"(x, y) = ({x:g} cm, {y:g} cm)")
    elbows = home.elbow
    masses = _leg_masses(robot, 2)
    legs = tuple(
        _leg(named, a, l1, l2, (x, y), elbow, i, masses)
        for i, (a, l1, l2, elbow) in enumerate(
            zip(bases, robot.proximal_cm, robot.distal_cm, elbows, strict=True)
        )
    )
    return ClosedChain(
        robot.name or "five-bar",
        legs,
        ((0.0, 0.0), (0.0, 0.0)),
        float(robot.end_mass_kg),
        0.0,
        False,
        (x / CM_PER_M, y / CM_PER_M, 0.0),
        float(robot.gravity_m_s2),
    )

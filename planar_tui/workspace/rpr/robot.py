"""The 3-RPR planar parallel robot: model, leg constraint and exact workspace reference.

Three legs join base joints :math:`A_i` (revolute) to platform points :math:`q_i` (revolute,
given in the platform frame) through an actuated prismatic joint of length
:math:`\\rho_i \\in [\\underline\\rho_i, \\overline\\rho_i]` (``leg_limits_cm`` of the job).
At the platform position :math:`p = (x, y)` and orientation :math:`\\varphi` the platform
point is :math:`C_i = p + R(\\varphi) q_i`, and leg ``i`` closes iff

.. math:: \\underline\\rho_i \\le |p + R(\\varphi) q_i - A_i| \\le \\overline\\rho_i,

i.e. :math:`p` lies in the annulus of radii :math:`\\underline\\rho_i, \\overline\\rho_i`
about :math:`c_i = A_i - R(\\varphi) q_i`. The constant-orientation workspace is the
intersection of the three annuli; its exact area is bracketed by polygons
(:func:`workspace_polygon`: each outer circle inscribed and each hole circumscribed for the
inner polygon, the reverse for the outer one; intersections and differences are monotone,
so :math:`|W_{in}| \\le |W| \\le |W_{out}|`), doubled until narrow
(:func:`~planar_tui.workspace.paving.geometry.polygon_bracket`).

The bundled design (the defaults) is illustrative, at the scale of paper B's 3-RRR: its base
triangle of side 120 cm and its platform triangle of base and height 40 cm (no published
3-RPR's dimensions could be sourced for this project).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from planar_tui.jobkind import RobotKind
from planar_tui.schema import mass_setting, number, setting, string
from planar_tui.workspace.paving.layout import PAPER_B_BASE_CM, paper_b_points, platform_points
from planar_tui.workspace.paving.orientation import range_reach_box
from planar_tui.workspace.paving.runner import single_orientation_rad
from planar_tui.workspace.rpr.tolerance import spec_thresholds


@dataclass(frozen=True, kw_only=True)
class Robot3RPR:
    """Geometry of a 3-RPR, the ``[robot3rpr]`` table (lengths in cm; defaults: an
    illustrative design at paper B's scale, see the module docstring)."""

    name: str = setting(string(), default="", type_doc="string", doc="a label")
    base_joints_cm: tuple[tuple[float, float], ...] = paper_b_points(
        PAPER_B_BASE_CM, "paper B's base triangle (side 120)", "base joints `A1, A2, A3`"
    )
    platform_points_cm: tuple[tuple[float, float], ...] = platform_points()
    cylinder_mass_kg: float = mass_setting("mass of each leg's cylinder (turns about `A_i`)")
    cylinder_inertia_kgm2: float = mass_setting("inertia of each cylinder about its centre of mass")
    cylinder_com_cm: float = setting(
        number(minimum=0.0),
        default=0.0,
        type_doc="number >= 0",
        doc="distance of each cylinder's centre of mass from `A_i` along the leg",
    )
    piston_mass_kg: float = mass_setting(
        "mass of each leg's piston (turns with its cylinder and slides in it)"
    )
    piston_inertia_kgm2: float = mass_setting("inertia of each piston about its centre of mass")
    piston_com_cm: float = setting(
        number(minimum=0.0),
        default=0.0,
        type_doc="number >= 0",
        doc="distance of each piston's centre of mass from `B_i` back along the leg",
    )
    platform_mass_kg: float = mass_setting(
        "mass of the platform (centre of mass at the platform frame's origin)"
    )
    platform_inertia_kgm2: float = mass_setting("inertia of the platform about its centre of mass")
    gravity_m_s2: float = mass_setting("gravity along -y in the plane (0: a horizontal machine)")

    def centres_cm(self, orientation_rad: float) -> tuple[tuple[float, float], ...]:
        """The annuli's centres :math:`c_i = A_i - R(\\varphi) q_i`."""
        c, s = math.cos(orientation_rad), math.sin(orientation_rad)
        return tuple(
            (ax - (c * qx - s * qy), ay - (s * qx + c * qy))
            for (ax, ay), (qx, qy) in zip(self.base_joints_cm, self.platform_points_cm, strict=True)
        )


def leg_parameters(robot: Robot3RPR, spec) -> object:
    """The kernel's (3, 8) array: per leg ``c_x, c_y, rho_lo, rho_hi`` (cm) and the labels'
    thresholds (:func:`~planar_tui.workspace.rpr.tolerance.spec_thresholds`: ``rho_lo,
    rho_hi`` twice for the nominal robot)."""
    import numpy as np

    centres = robot.centres_cm(spec.orientation_rad)
    limits, thresholds = spec.leg_limits_cm, spec_thresholds(spec)
    rows = [
        (cx, cy, lo, hi, *t)
        for (cx, cy), (lo, hi), t in zip(centres, limits, thresholds, strict=True)
    ]
    return np.ascontiguousarray(rows, dtype=np.float64)


def reach_box(robot: Robot3RPR, spec) -> tuple[float, float, float, float]:
    """Bounding box of the intersection of the discs :math:`|p - c_i| \\le \\overline\\rho_i`
    (empty when ``lo > hi``), or of its union over a range of orientations
    (:func:`~planar_tui.workspace.paving.orientation.range_reach_box`)."""
    his = [hi for _, hi in spec.leg_limits_cm]
    phi = single_orientation_rad(spec)
    if phi is None:
        bases, points = robot.base_joints_cm, robot.platform_points_cm
        return range_reach_box(bases, points, his, spec.orientation_deg)
    centres = robot.centres_cm(phi)
    return (
        max(cx - r for (cx, _), r in zip(centres, his, strict=True)),
        min(cx + r for (cx, _), r in zip(centres, his, strict=True)),
        max(cy - r for (_, cy), r in zip(centres, his, strict=True)),
        min(cy + r for (_, cy), r in zip(centres, his, strict=True)),
    )


def annulus(centre, lo, hi, segments_per_turn, outward):
    """Polygon of :math:`lo \\le |p - c| \\le hi`: inner (``outward=False``: outer circle
    inscribed, hole circumscribed) or outer (the reverse)."""
    from planar_tui.workspace.paving.geometry import disc

    outer = disc(centre, hi, segments_per_turn, outward)
    if lo <= 0.0:
        return outer
    return outer.difference(disc(centre, lo, segments_per_turn, not outward))


def workspace_polygon(robot: Robot3RPR, spec, segments_per_turn: int, outward: bool):
    """Inner (``outward=False``) or outer polygon of the workspace: three annuli intersected
    (over a range of orientations, at its middle one: a size for the job's estimate)."""
    from shapely import intersection_all

    phi = spec.orientation_deg
    centres = robot.centres_cm(
        math.radians(0.5 * (phi[0] + phi[1])) if isinstance(phi, tuple) else spec.orientation_rad
    )
    xlo, xhi, ylo, yhi = reach_box(robot, spec)
    annuli = []
    for (cx, cy), (lo, hi) in zip(centres, spec.leg_limits_cm, strict=True):
        # The workspace lies in the reach box: a disc of twice the farthest corner's
        # distance covers the box (its polygons too: their inradius is above 0.92 r from 8
        # segments a turn), so larger radii give the same intersection; capped, a limit of
        # 1e199 cm no longer overflows GEOS (which gave an empty "exact" workspace).
        cap = 2.0 * max(math.hypot(x - cx, y - cy) for x in (xlo, xhi) for y in (ylo, yhi))
        if math.isfinite(cap) and cap > 0.0:
            lo, hi = min(lo, cap), min(hi, cap)
        annuli.append(annulus((cx, cy), lo, hi, segments_per_turn, outward))
    return intersection_all(annuli)


ROBOT_KIND = RobotKind("robot3rpr", Robot3RPR, example="[robot3rpr]\n")

"""The 3-PRR planar parallel robot: model, leg constraint and exact workspace reference.

Leg ``i``: an actuated slider on the base line through :math:`B_i` at the angle
:math:`\\alpha_i` (:math:`u_i = (\\cos\\alpha_i, \\sin\\alpha_i)`), at :math:`B_i + s u_i` with
the stroke :math:`s \\in [\\underline s_i, \\overline s_i]`; a distal link of length
:math:`l_i` from the slider's revolute joint to the platform point
:math:`C_i = p + R(\\varphi) q_i`. The leg closes iff (derivation in
:mod:`planar_tui.kernels.workspace3prr`)

.. math:: d(C_i, S_i) \\le l_i \\le \\max(|C_i - E_{0,i}|, |C_i - E_{1,i}|),

with :math:`S_i` the stroke's segment and :math:`E_{0,i}, E_{1,i}` its ends: :math:`C_i` in
the stadium :math:`S_i \\oplus D(0, l_i)` minus the lens
:math:`D^\\circ(E_0, l_i) \\cap D^\\circ(E_1, l_i)`. The constant-orientation workspace is the
intersection of the three regions shifted by :math:`-R(\\varphi) q_i`; its exact area is
bracketed by polygons (:func:`workspace_polygon`: stadium discs inscribed and lens discs
circumscribed for the inner polygon, the reverse for the outer; the stadium's rectangle is
exact).

The bundled design (the defaults) is illustrative, at the scale of paper B's 3-RRR: the
sliders run along the sides of its 120 cm base triangle (strokes 10-110 cm), distal links of
40 cm, its 40 × 40 cm platform (no published 3-PRR's dimensions could be sourced here).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from planar_tui.jobkind import RobotKind
from planar_tui.schema import mass_setting, numbers, setting, string
from planar_tui.workspace.paving.layout import PAPER_B_BASE_CM, paper_b_points, platform_points
from planar_tui.workspace.paving.orientation import arc_extent
from planar_tui.workspace.paving.runner import single_orientation_rad
from planar_tui.workspace.prr.tolerance import spec_thresholds


def _three_strokes(reader, name, default, context, values):
    """Three ``[lo, hi]`` rows in cm with ``lo < hi``."""
    if not reader.has(name):
        return default
    rows = reader.number_rows(name, columns=2, row_doc="[lo, hi] in cm")
    if len(rows) != 3:
        raise reader.error(name, f"has {len(rows)} rows", "3 rows [lo, hi], one per leg")
    for leg, (lo, hi) in enumerate(rows, start=1):
        if not lo < hi:
            raise reader.error(name, f"leg {leg} stroke [{lo:g}, {hi:g}]", "lo < hi")
    return rows


@dataclass(frozen=True, kw_only=True)
class Robot3PRR:
    """Geometry of a 3-PRR, the ``[robot3prr]`` table (lengths in cm, angles in degrees;
    defaults: an illustrative design at paper B's scale, see the module docstring)."""

    name: str = setting(string(), default="", type_doc="string", doc="a label")
    slider_points_cm: tuple[tuple[float, float], ...] = paper_b_points(
        PAPER_B_BASE_CM,
        "paper B's base triangle (side 120)",
        "a point `B_i` of each slider's line (the stroke's origin)",
    )
    slider_angles_deg: tuple[float, ...] = setting(
        numbers(length=3),
        default=(0.0, 120.0, 240.0),
        type_doc="3 numbers",
        doc="direction `α_i` of each slider's line (`u_i = (cos α_i, sin α_i)`)",
    )
    strokes_cm: tuple[tuple[float, float], ...] = setting(
        _three_strokes,
        default=((10.0, 110.0),) * 3,
        type_doc="3 rows `[lo, hi]`, lo < hi",
        doc="each slider's stroke `s` along its line, `B_i + s u_i`",
    )
    distal_cm: tuple[float, ...] = setting(
        numbers(length=3, positive=True),
        default=(40.0, 40.0, 40.0),
        type_doc="3 numbers > 0",
        doc="distal link lengths `l_i`",
    )
    platform_points_cm: tuple[tuple[float, float], ...] = platform_points()
    slider_mass_kg: float = mass_setting("mass of each slider (translates along its rail)")
    link_mass_kg: float = mass_setting("mass of each distal link (centre of mass mid-link)")
    link_inertia_kgm2: float = mass_setting("inertia of each distal link about its centre of mass")
    platform_mass_kg: float = mass_setting(
        "mass of the platform (centre of mass at the platform frame's origin)"
    )
    platform_inertia_kgm2: float = mass_setting("inertia of the platform about its centre of mass")
    gravity_m_s2: float = mass_setting("gravity along -y in the plane (0: a horizontal machine)")

    def shifted_ends_cm(self, orientation_rad: float) -> tuple[tuple[float, ...], ...]:
        """Per leg the stroke's ends shifted by :math:`-R(\\varphi) q_i`:
        ``(E'0x, E'0y, E'1x, E'1y)``, so that leg ``i`` tests the platform position."""
        c, s = math.cos(orientation_rad), math.sin(orientation_rad)
        ends = []
        for (bx, by), angle, (lo, hi), (qx, qy) in zip(
            self.slider_points_cm,
            self.slider_angles_deg,
            self.strokes_cm,
            self.platform_points_cm,
            strict=True,
        ):
            ux, uy = math.cos(math.radians(angle)), math.sin(math.radians(angle))
            ox, oy = bx - (c * qx - s * qy), by - (s * qx + c * qy)
            ends.append((ox + lo * ux, oy + lo * uy, ox + hi * ux, oy + hi * uy))
        return tuple(ends)


def slider_joints_cm(robot: Robot3PRR, strokes_cm) -> tuple[tuple[float, float], ...]:
    """The sliders' revolute joints :math:`B_i + s_i u_i` at the strokes :math:`s_i` (cm)."""
    return tuple(
        (bx + s * math.cos(math.radians(angle)), by + s * math.sin(math.radians(angle)))
        for (bx, by), angle, s in zip(
            robot.slider_points_cm, robot.slider_angles_deg, strokes_cm, strict=True
        )
    )


def leg_parameters(robot: Robot3PRR, spec) -> object:
    """The kernel's (3, 9) array: per leg ``E'0x, E'0y, E'1x, E'1y, l`` (cm) and the
    labels' thresholds (:func:`~planar_tui.workspace.prr.tolerance.spec_thresholds`:
    ``l`` four times for the nominal robot)."""
    import numpy as np

    ends = robot.shifted_ends_cm(spec.orientation_rad)
    thresholds = spec_thresholds(robot, spec)
    rows = [
        (*e, length, *t) for e, length, t in zip(ends, robot.distal_cm, thresholds, strict=True)
    ]
    return np.ascontiguousarray(rows, dtype=np.float64)


def reach_box(robot: Robot3PRR, spec) -> tuple[float, float, float, float]:
    """Bounding box of the intersection of the stadiums' boxes (empty when ``lo > hi``);
    over a range of orientations each stadium's box is widened by the extent of
    :math:`-R(\\varphi) q_i` over the range
    (:func:`~planar_tui.workspace.paving.orientation.arc_extent`)."""
    phi = single_orientation_rad(spec)
    extents: list[tuple[float, ...]] = [(0.0, 0.0, 0.0, 0.0)] * 3  # one φ: ends shifted
    if phi is None:
        lo, hi = (math.radians(v) for v in spec.orientation_deg)
        extents = [arc_extent(q, lo, hi) for q in robot.platform_points_cm]
    ends = robot.shifted_ends_cm(0.0 if phi is None else phi)
    if phi is None:  # unshift: E_k = E'_k(0) + q_i
        ends = tuple(
            (ax + qx, ay + qy, bx + qx, by + qy)
            for (ax, ay, bx, by), (qx, qy) in zip(ends, robot.platform_points_cm, strict=True)
        )
    boxes = [
        (
            min(ax, bx) - e[1] - r,
            max(ax, bx) - e[0] + r,
            min(ay, by) - e[3] - r,
            max(ay, by) - e[2] + r,
        )
        for (ax, ay, bx, by), r, e in zip(ends, robot.distal_cm, extents, strict=True)
    ]
    return (
        max(b[0] for b in boxes),
        min(b[1] for b in boxes),
        max(b[2] for b in boxes),
        min(b[3] for b in boxes),
    )


def leg_polygon(ends, length, segments_per_turn, outward):
    """Polygon of one leg's region (stadium minus lens): inner (``outward=False``) or outer."""
    from shapely import Polygon, union_all

    from planar_tui.workspace.paving.geometry import disc

    ax, ay, bx, by = ends
    norm = math.hypot(bx - ax, by - ay)
    nx, ny = -(by - ay) / norm * length, (bx - ax) / norm * length
    rectangle = Polygon(
        [(ax + nx, ay + ny), (bx + nx, by + ny), (bx - nx, by - ny), (ax - nx, ay - ny)]
    )
    stadium = union_all(
        [
            rectangle,
            disc((ax, ay), length, segments_per_turn, outward),
            disc((bx, by), length, segments_per_turn, outward),
        ]
    )
    lens = disc((ax, ay), length, segments_per_turn, not outward).intersection(
        disc((bx, by), length, segments_per_turn, not outward)
    )
    return stadium.difference(lens)


def workspace_polygon(robot: Robot3PRR, spec, segments_per_turn: int, outward: bool):
    """Inner (``outward=False``) or outer polygon of the workspace: three regions intersected
    (over a range of orientations, at its middle one)."""
    from shapely import intersection_all

    phi = spec.orientation_deg  # over a range, its middle orientation (a size, for estimates)
    ends = robot.shifted_ends_cm(
        math.radians(0.5 * (phi[0] + phi[1])) if isinstance(phi, tuple) else spec.orientation_rad
    )
    return intersection_all(
        [
            leg_polygon(e, length, segments_per_turn, outward)
            for e, length in zip(ends, robot.distal_cm, strict=True)
        ]
    )


ROBOT_KIND = RobotKind("robot3prr", Robot3PRR, example="[robot3prr]\n")

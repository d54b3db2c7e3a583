"""The five-bar (RRRRR): a 2-DOF planar parallel robot, its model and exact references.

Two legs share the end-effector point :math:`P = (x, y)`. Leg ``i`` has its actuated
joint at :math:`A_1 = (-d/2, 0)`, :math:`A_2 = (d/2, 0)` (``d = base_separation_cm``), a
proximal link of length :math:`l_{1,i}` at the absolute angle :math:`\\theta_i`, its elbow
:math:`B_i = A_i + l_{1,i}(\\cos\\theta_i, \\sin\\theta_i)` and a distal link of length
:math:`l_{2,i}` from :math:`B_i` to :math:`P`::

                         P (x, y)
                        / \\
               l2,1   /     \\   l2,2
                    /         \\
                  B1           B2
                 /               \\
          l1,1 /  θ1         θ2    \\ l1,2
             /                       \\
           A1 ---------- d ----------- A2       (A1 = (-d/2, 0), A2 = (d/2, 0))

Leg ``i`` reaches ``P`` iff :math:`|P - A_i - l_{1,i}(\\cos\\theta, \\sin\\theta)| =
l_{2,i}` for some :math:`\\theta \\in [\\underline\\theta_i, \\overline\\theta_i]`: the
3-RRR's leg region (paper B) with the platform a point (:math:`q_i = 0`), so the workspace
is the intersection of two :func:`planar_tui.workspace.paving.geometry.leg_region`.

**Working mode** (the elbow signs :math:`\\sigma_i = \\pm 1`, the 3-RRR's ``elbow``): with
:math:`P - A_i = r(\\cos\\alpha, \\sin\\alpha)` the inverse kinematics is
:math:`\\theta_i = \\alpha + \\sigma_i\\beta`, :math:`\\cos\\beta = (r^2 + l_1^2 -
l_2^2)/(2 l_1 r)`, :math:`\\beta \\in [0, \\pi]`. Without a working mode (``"any"``) a
point is in the workspace if either branch is within the limits. In a mode, leg ``i``'s
region :math:`R_\\sigma = \\{(r, \\alpha): |l_1 - l_2| \\le r \\le l_1 + l_2,\\ \\alpha +
\\sigma\\beta(r) \\in [\\underline\\theta, \\overline\\theta]\\}` is an annular band twisted
by :math:`\\beta(r)`, of area :math:`2 l_1 l_2 (\\overline\\theta - \\underline\\theta)`
(:math:`\\int r\\,\\Delta\\theta\\,dr`); its boundary lies on four circular arcs: the outer
and inner circles :math:`r = l_1 + l_2`, :math:`r = |l_1 - l_2|` over the joint range (the
leg extended or folded) and the circles of radius :math:`l_2` about :math:`B(\\underline
\\theta)`, :math:`B(\\overline\\theta)` over the half turn of the mode (:math:`\\sigma = 1`:
the distal link at :math:`\\theta + \\psi`, :math:`\\psi \\in [-\\pi, 0]`). The mode changes
the region (never enlarges it); the assembly mode (the side of :math:`B_1 B_2` that ``P``
lies on) follows from ``P`` and the mode, and changes across the type II singularities.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

from planar_tui.jobkind import RobotKind
from planar_tui.schema import mass_setting, number, setting, string
from planar_tui.workspace.paving.legs import branch_angles

#: The working modes: both legs' elbow signs, or any branch.
WORKING_MODES = ("any", "++", "+-", "-+", "--")


def _pair(reader, name, default, context, values):
    """Two positive lengths, one per leg."""
    if not reader.has(name):
        return default
    return reader.numbers(name, length=2, positive=True, items_doc="2 lengths, one per leg")


def _limits(reader, name, default, context, values):
    """Two ``[min, max]`` rows in degrees, each non-empty and at most 360° wide."""
    if not reader.has(name):
        return default
    rows = reader.number_rows(name, columns=2, row_doc="[min, max] in degrees")
    if len(rows) != 2:
        raise reader.error(name, f"has {len(rows)} rows", "2 rows [min, max], one per leg")
    for leg, (lo, hi) in enumerate(rows, start=1):
        if not lo < hi or hi - lo > 360.0:
            raise reader.error(
                name, f"leg {leg} range is [{lo:g}, {hi:g}]", "min < max, at most 360 deg apart"
            )
    return rows


@dataclass(frozen=True, kw_only=True)
class Robot5R:
    """Geometry of a five-bar, the ``[robot5r]`` table (lengths in cm, angles in degrees).

    Defaults: an illustrative symmetric design (not a published one) of about 100 cm reach.
    """

    name: str = setting(string(), default="", type_doc="string", doc="a label")
    base_separation_cm: float = setting(
        number(positive=True),
        default=40.0,
        type_doc="number > 0",
        doc="distance `d` between the actuated joints A1 = (-d/2, 0), A2 = (d/2, 0)",
    )
    proximal_cm: tuple[float, float] = setting(
        _pair, default=(45.0, 45.0), type_doc="2 numbers > 0", doc="proximal lengths `l1` per leg"
    )
    distal_cm: tuple[float, float] = setting(
        _pair, default=(55.0, 55.0), type_doc="2 numbers > 0", doc="distal lengths `l2` per leg"
    )
    joint_limits_deg: tuple[tuple[float, float], ...] = setting(
        _limits,
        default=((-60.0, 180.0), (0.0, 240.0)),
        type_doc="2 rows `[min, max]`",
        doc="actuated-joint limits θ1, θ2 (absolute, from the x axis)",
    )
    working_mode: str = setting(
        string(choices=WORKING_MODES),
        default="any",
        type_doc=", ".join(f"`{m}`" for m in WORKING_MODES),
        doc="elbow signs σ1σ2 (θi = αi + σi βi), or `any` branch",
    )
    proximal_mass_kg: float = mass_setting("mass of each proximal link (centre of mass mid-link)")
    distal_mass_kg: float = mass_setting("mass of each distal link (centre of mass mid-link)")
    proximal_inertia_kgm2: float = mass_setting(
        "inertia of each proximal link about its centre of mass"
    )
    distal_inertia_kgm2: float = mass_setting(
        "inertia of each distal link about its centre of mass"
    )
    end_mass_kg: float = mass_setting("a point mass at the end-effector joint P")
    gravity_m_s2: float = mass_setting("gravity along -y in the plane (0: a horizontal machine)")

    def base_joints_cm(self) -> tuple[tuple[float, float], tuple[float, float]]:
        """:math:`A_1, A_2`."""
        half = 0.5 * self.base_separation_cm
        return ((-half, 0.0), (half, 0.0))

    @property
    def limits_rad(self) -> tuple[tuple[float, float], ...]:
        """Joint limits in radians."""
        return tuple((math.radians(lo), math.radians(hi)) for lo, hi in self.joint_limits_deg)

    @property
    def elbows(self) -> tuple[int, int]:
        """The mode's elbow signs, ``(0, 0)`` for ``any``."""
        if self.working_mode == "any":
            return (0, 0)
        return (1 if self.working_mode[0] == "+" else -1, 1 if self.working_mode[1] == "+" else -1)

    def reach_box_cm(self, orientation_rad: float = 0.0) -> tuple[float, float, float, float]:
        """Bounding box of the two reach discs' intersection (empty when ``lo > hi``); the
        orientation (of a 3-RRR's platform) plays no part."""
        (ax, _), (bx, _) = self.base_joints_cm()
        r1 = self.proximal_cm[0] + self.distal_cm[0]
        r2 = self.proximal_cm[1] + self.distal_cm[1]
        return (max(ax - r1, bx - r2), min(ax + r1, bx + r2), -min(r1, r2), min(r1, r2))

    def leg_arrays(self):
        """``(legs, limits)`` for :mod:`planar_tui.kernels.workspace5r`: rows ``ax, ay, l1,
        l2, sigma`` and the elbows at both joint limits relative to ``A``, and the (2, 2)
        joint limits in radians."""
        import numpy as np

        rows = []
        for (ax, ay), l1, l2, s, (lo, hi) in zip(
            self.base_joints_cm(),
            self.proximal_cm,
            self.distal_cm,
            self.elbows,
            self.limits_rad,
            strict=True,
        ):
            ends = [l1 * math.cos(lo), l1 * math.sin(lo), l1 * math.cos(hi), l1 * math.sin(hi)]
            rows.append([ax, ay, l1, l2, s, *ends])
        legs = np.array(rows, dtype=np.float64)
        return legs, np.ascontiguousarray(np.array(self.limits_rad, dtype=np.float64))


ROBOT_KIND = RobotKind("robot5r", Robot5R, example='[robot5r]\nworking_mode = "+-"\n')


# -- exact reference ----------------------------------------------------------------------
def _arc(cx, cy, radius, start, stop, segments_per_turn):
    """Points on the arc (chords inside the circle) and the chords' sagitta."""
    import numpy as np

    n = max(2, math.ceil(abs(stop - start) / (2.0 * math.pi) * segments_per_turn))
    t = np.linspace(start, stop, n + 1)
    sagitta = radius * (1.0 - math.cos(0.5 * abs(stop - start) / n))
    return np.column_stack([cx + radius * np.cos(t), cy + radius * np.sin(t)]), sagitta


def mode_band(a, l1, l2, lo, hi, sigma, segments_per_turn):
    """``(polygon, sagitta)``: the chord polygon of leg region :math:`R_\\sigma` (vertices on
    its four boundary arcs, module docstring) and the largest chord sagitta, so that
    ``polygon`` eroded by it lies in :math:`R_\\sigma` and dilated by it contains it."""
    import numpy as np
    from shapely import Polygon

    ax, ay = a
    blo = (ax + l1 * math.cos(lo), ay + l1 * math.sin(lo))
    bhi = (ax + l1 * math.cos(hi), ay + l1 * math.sin(hi))
    fold = -sigma * math.pi
    pieces = [
        _arc(*blo, l2, lo, lo + fold, segments_per_turn),  # θ = lo, extended to folded
        _arc(ax, ay, l1 - l2, lo, hi, segments_per_turn),  # folded (radius may be < 0)
        _arc(*bhi, l2, hi + fold, hi, segments_per_turn),  # θ = hi, folded to extended
        _arc(ax, ay, l1 + l2, hi, lo, segments_per_turn),  # extended
    ]
    # consecutive arcs meet where one ends and the next starts: each junction once (two
    # float copies 1e-14 apart made a near-zero edge whose mitre GEOS computed from NaN)
    ring = np.vstack([pieces[0][0], *(p[1:] for p, _ in pieces[1:])])[:-1]
    polygon = Polygon(ring).buffer(0)
    return polygon, max(abs(s) for _, s in pieces)


def leg_polygon(robot: Robot5R, leg: int, segments_per_turn: int, outward: bool):
    """Inner (``outward=False``) or outer polygon of leg ``leg``'s region."""
    from shapely import affinity

    from planar_tui.workspace.paving.geometry import leg_region

    a = robot.base_joints_cm()[leg]
    l1, l2 = robot.proximal_cm[leg], robot.distal_cm[leg]
    lo, hi = robot.limits_rad[leg]
    sigma = robot.elbows[leg]
    if sigma == 0 or hi - lo >= 2.0 * math.pi:
        region = leg_region(l1, l2, lo, hi, segments_per_turn, outward)
        return affinity.translate(region, *a)
    band, sagitta = mode_band(a, l1, l2, lo, hi, sigma, segments_per_turn)
    return band.buffer(sagitta if outward else -sagitta, join_style="mitre")


def workspace_polygon(robot: Robot5R, segments_per_turn: int, outward: bool):
    """Inner (``outward=False``) or outer polygon of the five-bar's workspace."""
    return leg_polygon(robot, 0, segments_per_turn, outward).intersection(
        leg_polygon(robot, 1, segments_per_turn, outward)
    )


@lru_cache(maxsize=32)
def geometric_area(robot: Robot5R, relative_tolerance: float = 2e-5, max_segments: int = 1 << 17):
    """Bracket the exact workspace area (:class:`~planar_tui.workspace.paving.geometry.GeometricArea`),
    doubling the segments per turn until ``outer - inner <= relative_tolerance * outer``
    (:func:`~planar_tui.workspace.paving.geometry.polygon_bracket`)."""
    from planar_tui.workspace.paving.geometry import polygon_bracket

    def polygon(segments: int, outward: bool) -> Any:
        return workspace_polygon(robot, segments, outward)

    return polygon_bracket(polygon, relative_tolerance, max_segments)


# -- float model ---------------------------------------------------------------------------
def leg_angles(robot: Robot5R, point) -> list[dict[int, float] | None]:
    """Per leg, :func:`~planar_tui.workspace.paving.geometry.branch_angles` at ``point``."""
    return [
        branch_angles(point[0] - ax, point[1] - ay, l1, l2)
        for (ax, ay), l1, l2 in zip(
            robot.base_joints_cm(), robot.proximal_cm, robot.distal_cm, strict=True
        )
    ]


def det_at(robot: Robot5R, point, elbows) -> float:
    """:math:`\\det A = u_1 \\times u_2` (:math:`u_i = P - B_i`, the distal links; the
    parallel Jacobian's rows are :math:`u_i^T`) at ``point`` in the mode ``elbows``."""
    u = []
    for (ax, ay), l1, angles, sign in zip(
        robot.base_joints_cm(), robot.proximal_cm, leg_angles(robot, point), elbows, strict=True
    ):
        if angles is None:
            raise ValueError(f"{point} is out of reach")
        theta = angles[sign]
        u.append((point[0] - ax - l1 * math.cos(theta), point[1] - ay - l1 * math.sin(theta)))
    return u[0][0] * u[1][1] - u[0][1] * u[1][0]

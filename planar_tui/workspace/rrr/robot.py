"""The 3-RRR planar parallel robot of paper B (section 5, eqs. 17-20, Table 2).

Base joints :math:`A_i`, proximal links :math:`l_1` (active joint angle :math:`\\theta_i`,
absolute), distal links :math:`l_2`, platform points
:math:`C_i = (x, y) + R(\\varphi) q_i`. The paper's layout (the defaults): an equilateral base
of side ``a``, :math:`A_1 = (0, 0), A_2 = (a, 0), A_3 = (a/2, a\\sqrt3/2)`, and an isosceles
platform of base and height ``b``, :math:`q_1 = (0, 0), q_2 = (b, 0), q_3 = (b/2, b)`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from planar_tui.jobkind import RobotKind
from planar_tui.schema import mass_setting, number, setting, string
from planar_tui.workspace.paving.layout import three_points


def _positive_cm(default: float, doc: str):
    return setting(number(positive=True), default=default, type_doc="number > 0", doc=doc)


@dataclass(frozen=True, kw_only=True)
class Robot3RRR:
    """Geometry of a 3-RRR, the ``[robot3rrr]`` table (lengths in cm); explicit points
    override the paper's layout (defaults: paper B, Table 2)."""

    name: str = setting(string(), default="", type_doc="string", doc="a label")
    base_side_cm: float = _positive_cm(120.0, "side `a` of the equilateral base")
    platform_side_cm: float = _positive_cm(40.0, "base and height `b` of the platform")
    proximal_cm: float = _positive_cm(30.0, "proximal (active) link length `l1`")
    distal_cm: float = _positive_cm(30.0, "distal link length `l2`")
    base_joints: tuple[tuple[float, float], ...] | None = setting(
        three_points,
        name="base_joints_cm",
        default=None,
        default_doc="the paper's triangle",
        type_doc="3 points `[x, y]`",
        doc="explicit base joints `A1, A2, A3` (replace `base_side_cm`)",
    )
    platform_points: tuple[tuple[float, float], ...] | None = setting(
        three_points,
        name="platform_points_cm",
        default=None,
        default_doc="the paper's triangle",
        type_doc="3 points `[x, y]`",
        doc="explicit platform points `q1, q2, q3` in the platform frame",
    )
    proximal_mass_kg: float = mass_setting("mass of each proximal link (centre of mass mid-link)")
    distal_mass_kg: float = mass_setting("mass of each distal link (centre of mass mid-link)")
    platform_mass_kg: float = mass_setting(
        "mass of the platform (centre of mass at the platform frame's origin)"
    )
    proximal_inertia_kgm2: float = mass_setting(
        "inertia of each proximal link about its centre of mass"
    )
    distal_inertia_kgm2: float = mass_setting(
        "inertia of each distal link about its centre of mass"
    )
    platform_inertia_kgm2: float = mass_setting("inertia of the platform about its centre of mass")
    gravity_m_s2: float = mass_setting("gravity along -y in the plane (0: a horizontal machine)")

    @property
    def paper_layout(self) -> bool:
        """True when the paper's triangle layout is used (required by the expanded form)."""
        return self.base_joints is None and self.platform_points is None

    def base_joints_cm(self) -> tuple[tuple[float, float], ...]:
        """:math:`A_1, A_2, A_3` (eq. 17)."""
        if self.base_joints is not None:
            return self.base_joints
        a = self.base_side_cm
        return ((0.0, 0.0), (a, 0.0), (0.5 * a, 0.5 * a * math.sqrt(3.0)))

    def platform_points_cm(self) -> tuple[tuple[float, float], ...]:
        """:math:`q_1, q_2, q_3` in the platform frame (eqs. 18-20 at :math:`\\varphi = 0`)."""
        if self.platform_points is not None:
            return self.platform_points
        b = self.platform_side_cm
        return ((0.0, 0.0), (b, 0.0), (0.5 * b, b))

    def leg_offsets_cm(self, orientation_rad: float) -> tuple[tuple[float, float], ...]:
        """:math:`d_i = R(\\varphi) q_i - A_i`, so that :math:`C_i - A_i = (x, y) + d_i`."""
        c, s = math.cos(orientation_rad), math.sin(orientation_rad)
        return tuple(
            (c * qx - s * qy - ax, s * qx + c * qy - ay)
            for (qx, qy), (ax, ay) in zip(
                self.platform_points_cm(), self.base_joints_cm(), strict=True
            )
        )

    def reach_box_cm(self, orientation_rad: float) -> tuple[float, float, float, float]:
        """Bounding box ``(x_lo, x_hi, y_lo, y_hi)`` of the intersection of the three discs
        :math:`|(x, y) + d_i| \\le l_1 + l_2` (empty when ``lo > hi``)."""
        reach = self.proximal_cm + self.distal_cm
        centres = [(-dx, -dy) for dx, dy in self.leg_offsets_cm(orientation_rad)]
        return (
            max(cx - reach for cx, _ in centres),
            min(cx + reach for cx, _ in centres),
            max(cy - reach for _, cy in centres),
            min(cy + reach for _, cy in centres),
        )


ROBOT_KIND = RobotKind(
    "robot3rrr",
    Robot3RRR,
    example="[robot3rrr]\n",
    app_default={
        "base_side_cm": 120.0,
        "platform_side_cm": 40.0,
        "proximal_cm": 30.0,
        "distal_cm": 30.0,
    },
)


#: The 3-RRR's toleranced quantities (keys of ``tolerances_cm``).
TOLERANCE_KEYS_3RRR = ("base_joints_cm", "platform_points_cm", "proximal_cm", "distal_cm")

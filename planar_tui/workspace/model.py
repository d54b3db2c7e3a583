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

from planar_tui.presets import TableReader

ROBOT3RRR_KEYS = (
    "name",
    "base_side_cm",
    "platform_side_cm",
    "proximal_cm",
    "distal_cm",
    "base_joints_cm",
    "platform_points_cm",
)


@dataclass(frozen=True)
class Robot3RRR:
    """Geometry of a 3-RRR (lengths in cm); explicit points override the paper's layout."""

    base_side_cm: float = 120.0
    platform_side_cm: float = 40.0
    proximal_cm: float = 30.0
    distal_cm: float = 30.0
    base_joints: tuple[tuple[float, float], ...] | None = None
    platform_points: tuple[tuple[float, float], ...] | None = None
    name: str = ""

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

    def to_table(self) -> dict:
        """The robot as a ``[robot3rrr]`` TOML table."""
        table: dict = {
            "base_side_cm": self.base_side_cm,
            "platform_side_cm": self.platform_side_cm,
            "proximal_cm": self.proximal_cm,
            "distal_cm": self.distal_cm,
        }
        if self.name:
            table["name"] = self.name
        if self.base_joints is not None:
            table["base_joints_cm"] = [list(p) for p in self.base_joints]
        if self.platform_points is not None:
            table["platform_points_cm"] = [list(p) for p in self.platform_points]
        return table


def parse_robot3rrr(reader: TableReader) -> Robot3RRR:
    """Build a :class:`Robot3RRR` from a ``[robot3rrr]`` table (defaults: paper B, Table 2)."""
    points = {}
    for key in ("base_joints_cm", "platform_points_cm"):
        if reader.has(key):
            rows = reader.number_rows(key, columns=2)
            if len(rows) != 3:
                raise reader.error(key, f"has {len(rows)} points", "3 points [x, y], one per leg")
            points[key] = rows
    return Robot3RRR(
        base_side_cm=reader.number("base_side_cm", 120.0, positive=True),
        platform_side_cm=reader.number("platform_side_cm", 40.0, positive=True),
        proximal_cm=reader.number("proximal_cm", 30.0, positive=True),
        distal_cm=reader.number("distal_cm", 30.0, positive=True),
        base_joints=points.get("base_joints_cm"),
        platform_points=points.get("platform_points_cm"),
        name=reader.string("name", ""),
    )

r"""A parallel robot's bodies at one pose, as points (cm) for drawings: what
:meth:`~planar_tui.workspace.paving.mechanism.Mechanism.linkage` returns and the app draws
(the path tabs' playback), naming no robot.

A leg is a polyline from its actuated joint (a base joint, or a slider's joint on its rail)
through its passive joints to the platform joint :math:`C_i = p + R(\varphi)\,q_i`
(:func:`platform_joints`); the frame holds the fixed lines (the base triangle, the rails).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

Point = tuple[float, float]
Polyline = tuple[Point, ...]


@dataclass(frozen=True)
class Linkage:
    """``frame``: the fixed polylines; ``legs``: each leg's polyline, actuated joint first
    and platform joint last; ``platform``: the platform's joints in order (a closed
    polygon; empty for a robot whose legs meet at one point, the five-bar's ``P``)."""

    frame: tuple[Polyline, ...]
    legs: tuple[Polyline, ...]
    platform: Polyline = ()

    def points(self) -> list[Point]:
        """Every point of the drawing (its extent's)."""
        return [p for line in (*self.frame, *self.legs, self.platform) for p in line]


def platform_joints(pose: Sequence[float], points_cm: Sequence[Point]) -> Polyline:
    """The platform joints :math:`C_i = p + R(\\varphi)\\,q_i` at the pose
    ``(x_cm, y_cm, phi_rad)`` of the platform points :math:`q_i` (cm, platform frame)."""
    x, y, phi = pose
    c, s = math.cos(phi), math.sin(phi)
    return tuple((x + c * qx - s * qy, y + s * qx + c * qy) for qx, qy in points_cm)


def rotated(origin: Point, length: float, angle_rad: float) -> Point:
    """``origin + length (cos angle, sin angle)``: a link's far joint."""
    return (origin[0] + length * math.cos(angle_rad), origin[1] + length * math.sin(angle_rad))

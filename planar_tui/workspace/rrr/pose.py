"""The 3-RRR's legs at a platform position: each active angle and its working mode within
the joint limits (what the app draws at the cursor of the map it explores)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

from planar_tui.workspace.rrr.singularity import leg_angles


def on_arc(angle_rad: float, lo_rad: float, hi_rad: float) -> bool:
    """Whether ``angle`` lies on the arc from ``lo`` to ``hi`` (counter-clockwise)."""
    return (angle_rad - lo_rad) % (2.0 * math.pi) <= hi_rad - lo_rad + 1e-12


def leg_modes(
    robot: Any,
    orientation_rad: float,
    point_cm: tuple[float, float],
    limits_rad: Sequence[tuple[float, float]],
    elbow: Sequence[int] | None = None,
) -> list[tuple[float, int] | None]:
    """Per leg, the active angle θ_i (rad) and its working mode ``s`` (``θ = α + sβ``,
    :func:`planar_tui.workspace.rrr.singularity.leg_angles`) within the joint limits at
    ``point_cm``: the mode ``elbow[i]`` when given and within the limits, else the first of
    ``+1, -1`` within them; ``None`` where the leg cannot close within its limits."""
    legs: list[tuple[float, int] | None] = []
    for leg, (angles, (lo, hi)) in enumerate(
        zip(leg_angles(robot, orientation_rad, point_cm), limits_rad, strict=True)
    ):
        modes = [] if angles is None else [s for s in (1, -1) if on_arc(angles[s], lo, hi)]
        if elbow is not None and elbow[leg] in modes:
            modes = [elbow[leg]]
        legs.append((angles[modes[0]], modes[0]) if angles is not None and modes else None)
    return legs

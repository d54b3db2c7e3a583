"""The 3-RRR's exact workspace (shapely): the intersection of its legs' regions
(:func:`~planar_tui.workspace.paving.geometry.leg_region`), its area bracket and the outer
polygon's area and length the box estimate is made of."""

from __future__ import annotations

from functools import lru_cache

from planar_tui.workspace.paving.geometry import GeometricArea, leg_region, polygon_bracket


def workspace_polygon(robot, limits_rad, orientation_rad, segments_per_turn, outward):
    """Inner (``outward=False``) or outer polygon of the workspace of the point (x, y)."""
    from shapely import affinity, intersection_all

    regions = []
    for (dx, dy), (lo, hi) in zip(robot.leg_offsets_cm(orientation_rad), limits_rad, strict=True):
        leg = leg_region(robot.proximal_cm, robot.distal_cm, lo, hi, segments_per_turn, outward)
        regions.append(affinity.translate(leg, -dx, -dy))
    return intersection_all(regions)


def geometric_area(
    robot, limits_rad, orientation_rad, *, relative_tolerance=2e-5, max_segments=1 << 18
) -> GeometricArea:
    """Bracket the exact workspace area, doubling the segments per turn until
    ``outer - inner <= relative_tolerance * outer`` (or ``max_segments`` is reached).

    Computed once per geometry in a process (robot, joint limits, orientation, tolerance):
    the jobs of a preset that share them (paper B's Table 3 has seven) share the result,
    an immutable :class:`GeometricArea`."""
    return _geometric_area(
        robot, *_geometry_key(limits_rad, orientation_rad), relative_tolerance, max_segments
    )


def outer_area_and_length(
    robot, limits_rad, orientation_rad, segments_per_turn: int = 64
) -> tuple[float, float]:
    """Area A (cm²) and boundary length L (cm) of the workspace's outer polygon at
    ``segments_per_turn``: what a paving's box estimate is made of (A/ε², L/ε).

    Computed once per geometry in a process, like :func:`geometric_area`: the seven jobs
    of paper B's Table 3 estimate their boxes from one polygon."""
    return _outer_area_and_length(
        robot, *_geometry_key(limits_rad, orientation_rad), segments_per_turn
    )


def _geometry_key(limits_rad, orientation_rad) -> tuple[tuple[tuple[float, float], ...], float]:
    """Joint limits and orientation as plain hashable floats (the caches' keys)."""
    return tuple((float(lo), float(hi)) for lo, hi in limits_rad), float(orientation_rad)


@lru_cache(maxsize=64)
def _outer_area_and_length(robot, limits_rad, orientation_rad, segments_per_turn):
    polygon = workspace_polygon(robot, limits_rad, orientation_rad, segments_per_turn, True)
    return float(polygon.area), float(polygon.length)


@lru_cache(maxsize=64)
def _geometric_area(robot, limits_rad, orientation_rad, relative_tolerance, max_segments):
    def polygon(segments, outward):
        return workspace_polygon(robot, limits_rad, orientation_rad, segments, outward)

    return polygon_bracket(polygon, relative_tolerance, max_segments)

"""A certified reference for orientation workspaces by dense sampling of φ (shapely).

The exact workspace at one orientation is :math:`W(\\varphi) = \\cap_i (L_i - d_i(\\varphi))`
with :math:`L_i` leg ``i``'s feasible region relative to its base joint and
:math:`d_i(\\varphi) = R(\\varphi) q_i - A_i` (:mod:`planar_tui.workspace.paving.geometry`, which also
gives inscribed and circumscribed polygons :math:`L_i^{in} \\subseteq L_i \\subseteq
L_i^{out}`). Sample :math:`\\varphi_k = \\varphi_{lo} + k\\delta`, ``k = 0..N``,
:math:`\\delta = (\\varphi_{hi} - \\varphi_{lo}) / N`: every :math:`\\varphi` of the range is
within :math:`\\delta / 2` of a sample, so for every position :math:`p`

.. math:: |v_i(p, \\varphi) - v_i(p, \\varphi_k)| = |R(\\varphi) q_i - R(\\varphi_k) q_i|
          \\le 2 |q_i| \\sin(\\delta / 4) \\le r := 2 \\max_i |q_i| \\sin(\\delta / 4).

Hence, with :math:`\\oplus` / :math:`\\ominus` the dilation / erosion by a disc of radius
:math:`r`,

* maximal: :math:`\\cup_k \\cap_i (L_i^{in} - d_i(\\varphi_k)) \\subseteq W_\\exists \\subseteq
  \\cup_k \\cap_i (L_i^{out} \\oplus r - d_i(\\varphi_k))` (a feasible :math:`(p, \\varphi)`
  moves each leg's point by at most :math:`r` to the nearest sample);
* total: :math:`\\cap_k \\cap_i (L_i^{in} \\ominus r - d_i(\\varphi_k)) \\subseteq W_\\forall
  \\subseteq \\cap_k \\cap_i (L_i^{out} - d_i(\\varphi_k))` (a point at depth :math:`\\ge r`
  in every :math:`L_i` at every sample stays in it at every :math:`\\varphi` between).

Shapely's buffer puts the vertices of its round joins on the circle (chords inside), so it
is called with :math:`r / \\cos(\\pi / (4 n))` (``n`` segments per quarter circle), whose
chords lie at least :math:`r` out: the dilation contains, the erosion is contained in, the
exact one. This module is independent of the interval kernels (it is what the tests compare
them with).

The intersections and unions keep only the polygonal parts of each result (a line or point
where regions touch has no area) and an intersection stops as soon as it is empty (a total
workspace that vanishes part-way along the range). Should GEOS still fail on an overlay
(``GEOSException``, e.g. "Unable to determine overlay result geometry dimension" on nearly
degenerate slivers), it is retried on :func:`shapely.make_valid` operands snapped to a
:data:`GRID_CM` grid; snap rounding moves the result's boundary by at most
:math:`\\sqrt2/2` grid cells, so the snapped result is then eroded (inner side) or dilated
(outer side) by :data:`GRID_CM` (chord-corrected as above), which keeps
``inner ⊆ W ⊆ outer`` up to sets of zero area. The grid, 1e-6 cm, is far below any
certified tolerance (the paper's finest ε is about 0.015 cm; the brackets are compared to
1e-9 relative).
"""

from __future__ import annotations

import math

#: Segments per quarter circle of the buffers.
QUAD_SEGMENTS = 16
#: Segments per turn of the leg regions' polygons.
SEGMENTS_PER_TURN = 1024
#: Default samples: about one per 0.05° of the range, between 16 and 800.
DEGREES_PER_SAMPLE = 0.05
#: Snap grid (cm) of the fallback overlay when GEOS fails on the exact one.
GRID_CM = 1e-6


def _margin(radius_cm: float) -> float:
    return radius_cm / math.cos(math.pi / (4 * QUAD_SEGMENTS)) * (1 + 1e-9) + 1e-12


def _polygonal(geometry):
    """The polygonal part of ``geometry`` (lines and points where regions touch dropped)."""
    from shapely import MultiPolygon, Polygon, get_parts

    if geometry.geom_type in ("Polygon", "MultiPolygon"):
        return geometry
    polygons = []
    for part in get_parts(geometry):
        if part.geom_type == "Polygon":
            polygons.append(part)
        elif part.geom_type == "MultiPolygon":
            polygons.extend(get_parts(part))
    return MultiPolygon(polygons) if polygons else Polygon()


def _overlay(first, second, operation, outward):
    """``operation(first, second)`` (shapely's ``intersection`` or ``union``), polygonal;
    on a GEOS failure, the snapped retry of the module docstring, dilated (``outward``) or
    eroded so that it stays an outer or inner bound."""
    from shapely import make_valid
    from shapely.errors import GEOSException

    try:
        return _polygonal(operation(first, second))
    except GEOSException:
        pass
    snapped = _polygonal(operation(make_valid(first), make_valid(second), grid_size=GRID_CM))
    margin = _margin(GRID_CM)
    return _polygonal(snapped.buffer(margin if outward else -margin, quad_segs=QUAD_SEGMENTS))


def combine(geometries, operation, outward):
    """The intersection (``operation = "intersection"``) or union of ``geometries`` as an
    outer (``outward``) or inner bound, robust as the module docstring says."""
    import shapely

    parts = [_polygonal(g) for g in geometries]
    if operation == "union":
        try:
            return _polygonal(shapely.union_all(parts))
        except shapely.errors.GEOSException:
            pass
    binary = getattr(shapely, operation)
    running = parts[0]
    for part in parts[1:]:
        if operation == "intersection" and running.is_empty:
            break
        running = _overlay(running, part, binary, outward)
    return running


def reference_polygons(
    robot, limits_rad, orientation_deg, mode, samples=None, segments=SEGMENTS_PER_TURN
):
    """``(inner, outer)`` shapely polygons with ``inner ⊆ W ⊆ outer`` for the ``mode``
    (``"maximal"`` or ``"total"``) workspace over ``orientation_deg = (lo, hi)``."""
    from shapely import affinity

    from planar_tui.workspace.paving.geometry import leg_region

    lo, hi = orientation_deg
    if samples is None:
        samples = int(min(800, max(16, math.ceil((hi - lo) / DEGREES_PER_SAMPLE))))
    step = math.radians(hi - lo) / samples
    farthest = max(math.hypot(*q) for q in robot.platform_points_cm())
    margin = _margin(2.0 * farthest * math.sin(step / 4.0))
    l1, l2 = robot.proximal_cm, robot.distal_cm
    inner_legs = [leg_region(l1, l2, a, b, segments, False) for a, b in limits_rad]
    outer_legs = [leg_region(l1, l2, a, b, segments, True) for a, b in limits_rad]
    if mode == "maximal":
        outer_legs = [leg.buffer(margin, quad_segs=QUAD_SEGMENTS) for leg in outer_legs]
    else:
        inner_legs = [leg.buffer(-margin, quad_segs=QUAD_SEGMENTS) for leg in inner_legs]

    def at(legs, phi, outward):
        offsets = robot.leg_offsets_cm(phi)
        moved = [
            affinity.translate(leg, -dx, -dy) for leg, (dx, dy) in zip(legs, offsets, strict=True)
        ]
        return combine(moved, "intersection", outward)

    phis = [math.radians(lo) + k * step for k in range(samples + 1)]
    operation = "union" if mode == "maximal" else "intersection"
    return tuple(
        combine([at(legs, p, outward) for p in phis], operation, outward)
        for legs, outward in ((inner_legs, False), (outer_legs, True))
    )


def reference_area(robot, limits_rad, orientation_deg, mode, samples=None):
    """The areas of :func:`reference_polygons` as a
    :class:`~planar_tui.workspace.paving.geometry.GeometricArea` (``inner_cm2 <= exact <=
    outer_cm2``)."""
    from planar_tui.workspace.paving.geometry import GeometricArea

    inner, outer = reference_polygons(robot, limits_rad, orientation_deg, mode, samples)
    return GeometricArea(float(min(inner.area, outer.area)), float(outer.area), SEGMENTS_PER_TURN)

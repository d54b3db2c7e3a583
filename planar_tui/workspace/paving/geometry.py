"""Exact geometric workspace area of a 3-RRR with a certified discretisation bracket.

Leg ``i`` closes at :math:`C_i` iff :math:`d_{\\min} \\le l_2 \\le d_{\\max}` (distances from
:math:`C_i` to the arc of :math:`B_i`, see :mod:`kernels.workspace_arc`). Relative to
:math:`A_i`, with arc endpoints :math:`E_{lo}, E_{hi}` and the angular sector
:math:`S = [\\underline\\theta, \\overline\\theta]`:

.. math::
    \\{d_{\\min} \\le l_2\\} &= (S \\cap \\{|l_1 - l_2| \\le r \\le l_1 + l_2\\})
        \\cup D(E_{lo}, l_2) \\cup D(E_{hi}, l_2), \\\\
    \\{d_{\\max} < l_2\\} &= (S + \\pi) \\cap D(0, l_2 - l_1)
        \\;\\cup\\; (S + \\pi)^c \\cap D(E_{lo}, l_2) \\cap D(E_{hi}, l_2).

The leg region is the first set minus the second; the workspace of the platform point
:math:`(x, y)` is the intersection of the three leg regions shifted by :math:`-d_i`.

Every disc and arc is replaced by an *inscribed* polygon where it adds area and a
*circumscribed* one where it removes area (and vice versa), giving polygons
:math:`W_{in} \\subseteq W \\subseteq W_{out}` (unions, intersections and differences are
monotone). Hence :math:`|W_{in}| \\le |W| \\le |W_{out}|` exactly, up to shapely's float
round-off; the number of segments is doubled until the bracket is narrow enough.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: Radius of the polygon standing in for an unbounded angular cone (cm), scaled up by
#: the robot's size in :func:`leg_region`.
_FAR = 10.0


@dataclass(frozen=True)
class GeometricArea:
    """Inner and outer polygon areas (cm²) bracketing the exact workspace area."""

    inner_cm2: float
    outer_cm2: float
    segments_per_turn: int

    @property
    def area_cm2(self) -> float:
        """Midpoint of the bracket."""
        return 0.5 * (self.inner_cm2 + self.outer_cm2)

    @property
    def error_bound_cm2(self) -> float:
        """Half-width of the bracket: ``|area_cm2 - exact| <= error_bound_cm2``."""
        return 0.5 * (self.outer_cm2 - self.inner_cm2)


def _arc_points(radius, start, stop, segments_per_turn, outward):
    """Vertices along an arc: on the circle (chords inside the disc) or at
    ``radius / cos(delta / 2)`` (edges tangent, polygon outside the disc)."""
    span = stop - start
    n = max(2, math.ceil(abs(span) / (2.0 * math.pi) * segments_per_turn))
    angles = np.linspace(start, stop, n + 1)
    r = radius / math.cos(0.5 * abs(span) / n) if outward else radius
    return np.column_stack([r * np.cos(angles), r * np.sin(angles)])


def _disc(centre, radius, segments_per_turn, outward):
    from shapely import Polygon

    pts = _arc_points(radius, 0.0, 2.0 * math.pi, segments_per_turn, outward)[:-1]
    return Polygon(pts + np.asarray(centre))


#: A disc's inscribed (``outward=False``) or circumscribed polygon, for the other mechanisms'
#: references (:mod:`planar_tui.workspace.rpr.robot`, :mod:`planar_tui.workspace.prr.robot`).
disc = _disc


def _sector(r_in, r_out, start, stop, segments_per_turn, outward):
    """Annular sector ``r_in <= r <= r_out``, angle in ``[start, stop]`` (about the origin)."""
    from shapely import Polygon

    outer = _arc_points(r_out, start, stop, segments_per_turn, outward)
    if r_in <= 0.0:
        return Polygon(np.vstack([[[0.0, 0.0]], outer]))
    inner = _arc_points(r_in, stop, start, segments_per_turn, not outward)
    return Polygon(np.vstack([outer, inner]))


def _cone(start, stop, radius):
    """The angular sector ``[start, stop]`` cut at ``radius`` (straight-edged: exact)."""
    from shapely import Polygon

    return Polygon(np.vstack([[[0.0, 0.0]], _arc_points(radius, start, stop, 64, True)]))


def leg_region(l1, l2, lo, hi, segments_per_turn, outward):
    """Polygon of leg feasibility relative to its base joint (inner or outer approximation)."""
    from shapely import union_all

    if hi - lo >= 2.0 * math.pi:
        lo, hi = 0.0, 2.0 * math.pi - 1e-12
    far = _FAR * (l1 + l2)
    ends = [(l1 * math.cos(t), l1 * math.sin(t)) for t in (lo, hi)]
    swept = union_all(
        [
            _sector(abs(l1 - l2), l1 + l2, lo, hi, segments_per_turn, outward),
            _disc(ends[0], l2, segments_per_turn, outward),
            _disc(ends[1], l2, segments_per_turn, outward),
        ]
    )
    remove_outward = not outward
    hole_parts = []
    anti_lo, anti_hi = lo + math.pi, hi + math.pi
    if l2 > l1:
        hole_parts.append(
            _sector(0.0, l2 - l1, anti_lo, anti_hi, segments_per_turn, remove_outward)
        )
    if hi - lo < 2.0 * math.pi - 1e-9:
        lens = _disc(ends[0], l2, segments_per_turn, remove_outward).intersection(
            _disc(ends[1], l2, segments_per_turn, remove_outward)
        )
        outside_cone = _cone(anti_hi, anti_lo + 2.0 * math.pi, far)
        hole_parts.append(lens.intersection(outside_cone))
    return swept.difference(union_all(hole_parts)) if hole_parts else swept


def polygon_bracket(polygon, relative_tolerance, max_segments) -> GeometricArea:
    """Bracket an area from ``polygon(segments_per_turn, outward)``, the inner
    (``outward=False``) and outer polygon of a region bounded by circle arcs: the segments
    per turn are doubled from 4096 until ``outer - inner <= relative_tolerance * outer``
    (or ``max_segments`` is reached). Shared by every mechanism's exact reference."""
    segments = 4096
    while True:
        inner = polygon(segments, False).area
        outer = polygon(segments, True).area
        if outer - inner <= relative_tolerance * max(outer, 1e-300) or segments >= max_segments:
            return GeometricArea(float(min(inner, outer)), float(outer), segments)
        segments *= 2

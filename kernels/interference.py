"""Certified bounds of the clearance between a parallel robot's links over an (x, y) box.

A robot's kernel encloses, over the box's points in its working mode, both ends of every
moving *link* (a segment; each link a capsule of diameter :math:`w` = ``leg_width_cm``) and
the platform's vertices (the platform: their polygon, no thickness). Link ``k`` belongs to
chain ``chain[k]``; its end 1 sits at the moving joint ``joint[k]`` (a platform vertex, the
five-bar's end point; ``-1``: none), its end 0 is the other one.

**Checked pairs** (:func:`clearance_gap`), each with its required distance :math:`d_{req}`:

- two links of different chains that do not share a joint: :math:`d_{req} = w` (their
  capsules do not overlap); links of one chain share a joint in turn and are not checked;
- every link and the platform polygon: :math:`d_{req} = w / 2`. A link with no joint on the
  platform: its distance to the polygon (0 when its end 0 lies inside). A link jointed at
  vertex :math:`v`: the least of its distance to the edges not incident to :math:`v` and
  the distance of its end 0 to the polygon (the link itself touches the platform at
  :math:`v`; its other end must keep clear of it).

Every quantity is 1-Lipschitz in the ends and vertices (a segment's distance to a segment,
a point's to a polygon), which the enclosure below needs.

The *gap* of a pose is :math:`\\min_{pairs} (d - d_{req})`; the pose is interference-free
iff the gap is :math:`\\ge 0`.

**Enclosure.** With each end :math:`P` enclosed in a box of centre :math:`\\hat P` and
half-diagonal :math:`\\delta_P`, every point :math:`(1-t)P_0 + tP_1` of a link lies within
:math:`\\delta = \\max(\\delta_{P_0}, \\delta_{P_1})` of the centre segment's point, so the
link's Hausdorff distance to the centre segment is at most :math:`\\delta` and (the platform
likewise, :math:`\\delta` its vertices' largest)

.. math:: d(\\hat S, \\hat T) - \\delta_S - \\delta_T \\le d(S, T) \\le
          d(\\hat S, \\hat T) + \\delta_S + \\delta_T.

:math:`d(\\hat S, \\hat T)` is computed in floating point (:func:`segment_distance`: 0 when
the segments may cross, else the least of the four end-to-segment distances) and widened by
``SLACK_RELATIVE`` times the coordinates' magnitude, which covers its rounding. The bounds
tighten linearly with the box, so bisection converges to the point value.
"""

import math

from ._jit import kernel
from .dexterity import OUT
from .interval import down, up

#: Slack on a floating-point distance, relative to the coordinates' magnitude (+ 1 cm).
SLACK_RELATIVE = 1e-9


@kernel
def point_segment(px, py, ax, ay, bx, by):
    """The distance from the point :math:`P` to the segment :math:`AB`:
    :math:`|P - A - t(B - A)|` with :math:`t = \\mathrm{clamp}((P - A)\\cdot(B - A) /
    |B - A|^2, 0, 1)`."""
    dx = bx - ax
    dy = by - ay
    length2 = dx * dx + dy * dy
    t = 0.0
    if length2 > 0.0:
        t = min(1.0, max(0.0, ((px - ax) * dx + (py - ay) * dy) / length2))
    return math.hypot(px - ax - t * dx, py - ay - t * dy)


@kernel
def orientation(ax, ay, bx, by, cx, cy, tolerance):
    """The side of :math:`C` from the line :math:`AB`: the sign of :math:`(B - A) \\times
    (C - A)`, 0 within ``tolerance``."""
    cross = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)
    if cross > tolerance:
        return 1
    if cross < -tolerance:
        return -1
    return 0


@kernel
def segment_distance(ax, ay, bx, by, cx, cy, dx, dy, scale):
    """The distance between the segments :math:`AB` and :math:`CD`: 0 when they may cross
    (no end strictly on one side of the other's line, with cross products within
    ``SLACK_RELATIVE`` :math:`scale^2` taken as 0), else the least of the four
    end-to-segment distances (two disjoint planar segments are closest at an end)."""
    tol = SLACK_RELATIVE * scale * scale
    o1 = orientation(ax, ay, bx, by, cx, cy, tol)
    o2 = orientation(ax, ay, bx, by, dx, dy, tol)
    o3 = orientation(cx, cy, dx, dy, ax, ay, tol)
    o4 = orientation(cx, cy, dx, dy, bx, by, tol)
    if o1 * o2 <= 0 and o3 * o4 <= 0:
        return 0.0
    return min(
        min(point_segment(ax, ay, cx, cy, dx, dy), point_segment(bx, by, cx, cy, dx, dy)),
        min(point_segment(cx, cy, ax, ay, bx, by), point_segment(dx, dy, ax, ay, bx, by)),
    )


@kernel
def inside_polygon(px, py, centre, n):
    """Whether :math:`P` lies inside the polygon of the first ``n`` rows of ``centre``
    (even-odd crossing rule; on its boundary either answer, the edge distances are then 0)."""
    inside = False
    j = n - 1
    for i in range(n):
        xi, yi = centre[i, 0], centre[i, 1]
        xj, yj = centre[j, 0], centre[j, 1]
        if (yi > py) != (yj > py) and px < xi + (py - yi) * (xj - xi) / (yj - yi):
            inside = not inside
        j = i
    return inside


@kernel
def centre_radius(boxes, k, e):
    """``(cx, cy, radius)``: the centre of the box ``boxes[k, e]`` (2 coordinates, lo/hi)
    and its half-diagonal, rounded up."""
    xlo, xhi = boxes[k, e, 0, 0], boxes[k, e, 0, 1]
    ylo, yhi = boxes[k, e, 1, 0], boxes[k, e, 1, 1]
    cx = 0.5 * (xlo + xhi)
    cy = 0.5 * (ylo + yhi)
    radius = up(math.hypot(up(max(xhi - cx, cx - xlo)), up(max(yhi - cy, cy - ylo))))
    return cx, cy, up(radius)


@kernel
def pair_bounds(distance, spread, required, scale, gap_lo, gap_hi):
    """Meet the running gap bounds with one pair's: :math:`d \\mp (spread + slack) -
    d_{req}`."""
    slack = up(spread + SLACK_RELATIVE * (scale + 1.0))
    lo = down(down(distance - slack) - required)
    hi = up(up(distance + slack) - required)
    return min(gap_lo, lo), min(gap_hi, hi)


@kernel
def clearance_gap(ends, chain, joint, platform, width_cm, centre):
    """``(gap_lo, gap_hi)`` enclosing the gap (module docstring) over every pose whose link
    ends lie in ``ends`` (links, 2 ends, 2 coordinates, lo/hi) and platform vertices in
    ``platform`` (vertices, 1, 2, 2; fewer than 3 rows: no polygon); ``centre`` is scratch
    (links + vertices, 5). ``(inf, inf)`` when nothing is checked."""
    links = len(ends)
    vertices = len(platform)
    scale = 0.0
    for k in range(links):  # end 0's centre, end 1's, the larger half-diagonal
        ax, ay, ra = centre_radius(ends, k, 0)
        bx, by, rb = centre_radius(ends, k, 1)
        centre[k, 0], centre[k, 1], centre[k, 2], centre[k, 3] = ax, ay, bx, by
        centre[k, 4] = max(ra, rb)
        scale = max(scale, max(max(abs(ax), abs(ay)), max(abs(bx), abs(by))))
    polygon = centre[links : links + vertices]
    platform_radius = 0.0
    for v in range(vertices):
        polygon[v, 0], polygon[v, 1], radius = centre_radius(platform, v, 0)
        platform_radius = max(platform_radius, radius)
        scale = max(scale, max(abs(polygon[v, 0]), abs(polygon[v, 1])))
    gap_lo = math.inf
    gap_hi = math.inf
    for k in range(links):
        ax, ay, bx, by, spread_k = (
            centre[k, 0],
            centre[k, 1],
            centre[k, 2],
            centre[k, 3],
            centre[k, 4],
        )
        for m in range(k + 1, links):
            if chain[m] == chain[k] or (joint[k] >= 0 and joint[m] == joint[k]):
                continue
            d = segment_distance(
                ax, ay, bx, by, centre[m, 0], centre[m, 1], centre[m, 2], centre[m, 3], scale
            )
            spread = up(spread_k + centre[m, 4])
            gap_lo, gap_hi = pair_bounds(d, spread, width_cm, scale, gap_lo, gap_hi)
        if vertices < 3:
            continue
        d = 0.0 if inside_polygon(ax, ay, polygon, vertices) else math.inf
        for v in range(vertices):
            w = (v + 1) % vertices
            vx, vy, wx, wy = polygon[v, 0], polygon[v, 1], polygon[w, 0], polygon[w, 1]
            if joint[k] == v or joint[k] == w:  # an edge at its joint: from its end 0 only
                edge = point_segment(ax, ay, vx, vy, wx, wy)
            else:
                edge = segment_distance(ax, ay, bx, by, vx, vy, wx, wy, scale)
            d = min(d, edge)
        spread = up(spread_k + platform_radius)
        gap_lo, gap_hi = pair_bounds(d, spread, 0.5 * width_cm, scale, gap_lo, gap_hi)
    return gap_lo, gap_hi


@kernel
def settle_gap(state, bounded, ends, chain, joint, platform, width_cm, centre, verdict, gap, i):
    """Row ``i``'s verdict ``state`` and ``gap[i]``: :func:`clearance_gap` where the legs
    may close (``state != OUT``) and their links are ``bounded``, ``(-inf, inf)``
    elsewhere."""
    verdict[i] = state
    gap[i, 0] = -math.inf
    gap[i, 1] = math.inf
    if state != OUT and bounded:
        gap[i, 0], gap[i, 1] = clearance_gap(ends, chain, joint, platform, width_cm, centre)

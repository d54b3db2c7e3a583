"""The largest certified dexterous disc of any parallel robot, about a centre and over all
centres, from the dexterity paving's boxes (:mod:`planar_tui.workspace.paving.dexterity`).

The paving partitions its extent (which holds the workspace) into *inside* boxes (every
point dexterous), *boundary* boxes (undecided) and *outside* boxes (no point dexterous,
kept as :attr:`DexterityOutcome.outside`). Let :math:`G` be the union of the inside boxes,
:math:`N` the union of the outside boxes and the extent's exterior (every point of
:math:`N` is proved not dexterous) and :math:`B = N \\cup` the boundary boxes (the
complement of :math:`G`). For a centre :math:`c` the radius of the largest dexterous disc,
:math:`r^*(c) = \\sup\\{r : D(c, r) \\subseteq \\text{dexterous set}\\}` (0 when :math:`c`
is not dexterous), is bracketed by

.. math:: d(c, B) \\le r^*(c) \\le d(c, N),

a disc closer to :math:`c` than :math:`B` lying in :math:`G`, and one reaching :math:`N`
holding a point that is not dexterous. Over all centres :math:`R^* = \\sup_c r^*(c)`:
the lower bound is the best :math:`d(m, B)` over candidate centres :math:`m` (the centres
of the kept boxes, then of their quarters), the upper bound
:math:`\\max_k d(m_k, N) + h_k` over cells :math:`k` covering the kept boxes
(:math:`r^* = 0` off them; :math:`d(\\cdot, N)` is 1-Lipschitz; :math:`m_k`, :math:`h_k`
the cell's centre and half diagonal), and a cell whose upper bound exceeds the lower bound
is quartered, :data:`ROUNDS` times at most, so the bracket closes to about the boundary
band's width. Every distance is exact up to :data:`MARGIN_CM` of round-off, given to each
bound.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from planar_tui.workspace.paving.circle import MARGIN_CM

#: The summary's disc columns (after the dexterity's): about the job's centre (empty
#: without one), then over all centres.
HEADER = (
    "dexterous_circle_centre_x_cm",
    "dexterous_circle_centre_y_cm",
    "dexterous_circle_radius_lo_cm",
    "dexterous_circle_radius_hi_cm",
    "dexterous_disc_centre_x_cm",
    "dexterous_disc_centre_y_cm",
    "dexterous_disc_radius_lo_cm",
    "dexterous_disc_radius_hi_cm",
)
#: Nearest box centres measured per point and size group before any wider search.
NEAREST = 8
#: Rounds of quartering the cells whose upper bound exceeds the lower bound.
ROUNDS = 6
#: Cells quartered per round at most (those with the largest upper bounds).
CELLS_PER_ROUND = 4096


@dataclass(frozen=True)
class DexterousDisc:
    """The certified radius bracket about the job's centre (``None`` without one) and the
    best centre found over all centres with its bracket (``None`` centre: no box proved
    dexterous, so no disc certified)."""

    centre_cm: tuple[float, float] | None
    radius_lo_cm: float
    radius_hi_cm: float
    best_centre_cm: tuple[float, float] | None
    best_lo_cm: float
    best_hi_cm: float

    def columns(self) -> list:
        """The summary's :data:`HEADER` cells."""
        about: list = ["", "", "", ""]
        if self.centre_cm is not None:
            about = [*self.centre_cm, self.radius_lo_cm, self.radius_hi_cm]
        best = ["", ""] if self.best_centre_cm is None else list(self.best_centre_cm)
        return [*about, *best, self.best_lo_cm, self.best_hi_cm]

    def describe(self) -> str:
        """``dexterous disc r ∈ [lo, hi] cm about (x, y)[; largest r ∈ [lo, hi] cm at (x,
        y)]``."""
        text = f"; largest dexterous disc r ∈ [{self.best_lo_cm:.5g}, {self.best_hi_cm:.5g}] cm"
        if self.best_centre_cm is not None:
            text += f" at ({self.best_centre_cm[0]:.4g}, {self.best_centre_cm[1]:.4g})"
        if self.centre_cm is None:
            return text
        cx, cy = self.centre_cm
        return (
            f"; dexterous disc r ∈ [{self.radius_lo_cm:.5g}, {self.radius_hi_cm:.5g}] cm "
            f"about ({cx:.4g}, {cy:.4g}){text}"
        )


def job_centre(spec: Any) -> tuple[float, float] | None:
    """The job's circle centre (``circle_centre_cm``; the five-bar's
    ``singularity_free_circle``), ``None`` where not given."""
    centre = getattr(spec, "circle_centre_cm", None)
    return centre if centre is not None else getattr(spec, "singularity_free_circle", None)


def exterior_distance(points: Any, extent: tuple[float, float, float, float]) -> Any:
    """The distance from each point (rows ``x, y``) to the complement of the extent
    ``x_lo, x_hi, y_lo, y_hi`` (0 outside it)."""
    import numpy as np

    xlo, xhi, ylo, yhi = extent
    x, y = points[:, 0], points[:, 1]
    inner = np.minimum(np.minimum(x - xlo, xhi - x), np.minimum(y - ylo, yhi - y))
    return np.maximum(inner, 0.0)


def point_box_distance(px: Any, py: Any, boxes: Any) -> Any:
    """The distance from each point ``(px, py)`` to the closed box in the same row of
    ``boxes`` (rows ``x_lo, x_hi, y_lo, y_hi``; 0 inside)."""
    import numpy as np

    dx = np.maximum(np.maximum(boxes[..., 0] - px, px - boxes[..., 1]), 0.0)
    dy = np.maximum(np.maximum(boxes[..., 2] - py, py - boxes[..., 3]), 0.0)
    return np.hypot(dx, dy)


class NearestBox:
    """The distance from points to the nearest of the closed boxes (rows ``x_lo, x_hi,
    y_lo, y_hi``), exactly. The boxes are grouped by their half diagonal :math:`h` (within
    a factor 2), a k-d tree of centres per group; a box of a group is at least its centre's
    distance less :math:`h_{max}` away, so once the :data:`NEAREST` nearest centres are
    measured, a point whose last centre lies at least :math:`h_{max}` beyond the nearest
    box measured is done, and the others measure every box within that reach."""

    def __init__(self, boxes: Any):
        import numpy as np
        from scipy.spatial import cKDTree

        self.boxes = boxes
        centres = np.column_stack(
            [0.5 * (boxes[:, 0] + boxes[:, 1]), 0.5 * (boxes[:, 2] + boxes[:, 3])]
        )
        half = 0.5 * np.hypot(boxes[:, 1] - boxes[:, 0], boxes[:, 3] - boxes[:, 2])
        group = np.floor(np.log2(np.maximum(half, 1e-300))).astype(np.int64)
        self.groups = []
        for g in np.unique(group):
            members = np.flatnonzero(group == g)
            reach = float(half[members].max()) + MARGIN_CM
            self.groups.append((members, reach, cKDTree(centres[members])))

    def distance(self, points: Any) -> Any:
        """The distance from each point (rows ``x, y``) to the nearest box (``inf``
        without boxes)."""
        import numpy as np

        best = np.full(len(points), np.inf)
        px, py = points[:, 0], points[:, 1]
        for members, reach, tree in self.groups if len(points) else ():
            k = min(NEAREST, len(members))
            far, index = tree.query(points, k=k)
            far, index = far.reshape(len(points), k), index.reshape(len(points), k)
            boxes = self.boxes[members[index]]
            near = point_box_distance(px[:, None], py[:, None], boxes).min(axis=1)
            best = np.minimum(best, near)
            unsure = np.flatnonzero((far[:, -1] - reach < near) & (k < len(members)))
            if len(unsure) == 0:
                continue
            found = tree.query_ball_point(points[unsure], near[unsure] + reach)
            counts = np.fromiter((len(f) for f in found), dtype=np.int64, count=len(unsure))
            rows = np.repeat(unsure, counts)
            ball = members[np.concatenate([np.asarray(f, dtype=np.int64) for f in found])]
            distance = point_box_distance(px[rows], py[rows], self.boxes[ball])
            np.minimum.at(best, rows, distance)
        return best


def boxes_distance(points: Any, boxes: Any) -> Any:
    """The distance from each point (rows ``x, y``) to the nearest of the closed boxes
    (:class:`NearestBox`)."""
    return NearestBox(boxes).distance(points)


class DiscBounds:
    """The certified bracket :math:`d(c, B) \\le r^*(c) \\le d(c, N)` (module docstring)
    of the dexterity paving ``outcome`` over ``extent``, about any centres."""

    def __init__(self, outcome: Any, extent: tuple[float, float, float, float]):
        self.extent = extent
        self.outside = NearestBox(outcome.outside)
        self.boundary = NearestBox(outcome.boxes[outcome.status != 2])

    def bounds(self, points: Any) -> tuple[Any, Any]:
        """The bracket about each centre of ``points`` (rows ``x, y``), each bound given
        :data:`MARGIN_CM` of round-off."""
        import numpy as np

        points = np.asarray(points, dtype=float).reshape(-1, 2)
        upper = np.minimum(self.outside.distance(points), exterior_distance(points, self.extent))
        lower = np.minimum(upper, self.boundary.distance(points))
        return np.maximum(lower - MARGIN_CM, 0.0), upper + MARGIN_CM


def radius_bounds(
    outcome: Any, extent: tuple[float, float, float, float], points: Any
) -> tuple[Any, Any]:
    """:meth:`DiscBounds.bounds` of the paving ``outcome`` over ``extent`` about ``points``."""
    return DiscBounds(outcome, extent).bounds(points)


def quarters(cells: Any) -> Any:
    """Each cell's four quarters (rows ``x_lo, x_hi, y_lo, y_hi``)."""
    from planar_tui.workspace.paving.boxes import sub_grid

    return sub_grid(cells, 2)


def centres_of(cells: Any) -> Any:
    """The cells' centres (rows ``x, y``)."""
    import numpy as np

    return np.column_stack([0.5 * (cells[:, 0] + cells[:, 1]), 0.5 * (cells[:, 2] + cells[:, 3])])


def certified_disc(
    outcome: Any, extent: tuple[float, float, float, float], centre: tuple[float, float] | None
) -> DexterousDisc:
    """The bracket about ``centre`` and over all centres (module docstring) of the
    dexterity paving ``outcome`` over ``extent``."""
    import numpy as np

    radii = DiscBounds(outcome, extent)
    about = (0.0, 0.0)
    if centre is not None:
        lo, hi = radii.bounds([centre])
        about = (float(lo[0]), float(hi[0]))
    best_centre, best_lo, best_hi = None, 0.0, 0.0
    cells = outcome.boxes
    for round_ in range(ROUNDS + 1):
        if len(cells) == 0:
            break
        middle = centres_of(cells)
        lo, hi = radii.bounds(middle)
        if lo.max() > best_lo:
            best_lo = float(lo.max())
            best_centre = (float(middle[lo.argmax(), 0]), float(middle[lo.argmax(), 1]))
        hi += 0.5 * np.hypot(cells[:, 1] - cells[:, 0], cells[:, 3] - cells[:, 2])
        open_ = hi > best_lo + MARGIN_CM
        settled = float(hi[~open_].max()) if (~open_).any() else 0.0
        cells, hi = cells[open_], hi[open_]
        if round_ == ROUNDS or len(cells) == 0:
            best_hi = max(best_hi, settled, float(hi.max()) if len(hi) else 0.0)
            break
        order = np.argsort(hi)[::-1]
        split, rest = order[:CELLS_PER_ROUND], order[CELLS_PER_ROUND:]
        best_hi = max(best_hi, settled, float(hi[rest].max()) if len(rest) else 0.0)
        cells = quarters(cells[split])
    best_hi = max(best_hi, best_lo)
    return DexterousDisc(centre, about[0], about[1], best_centre, best_lo, best_hi)

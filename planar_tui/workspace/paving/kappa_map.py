"""The κ map of a dexterous region as terminal text: each cell shows the worst certified
upper bound of κ over the dexterity boxes that touch it, in four bands of
:math:`[1, \\kappa_{max}]`, ``?`` where a box's bound exceeds ``kappa_max`` (a boundary box)
and a blank where no box is kept; the dexterous region's own map (proved and boundary boxes)
is :func:`~planar_tui.workspace.paving.map.render_map` of its boxes."""

from __future__ import annotations

from typing import Any

import numpy as np

from planar_tui.workspace.paving.map import CELL_ASPECT, fit_extent

#: The bands' glyphs, best (κ near 1) to worst (κ near kappa_max), then "not proved".
BAND_GLYPHS = ("1", "2", "3", "4")
UNPROVED_GLYPH = "?"


def kappa_cells(outcome: Any, extent, columns: int, rows: int) -> np.ndarray:
    """Per cell (``rows`` x ``columns``, row 0 at the bottom) the largest ``kappa_hi`` of
    the boxes that touch it (``nan`` where none)."""
    return worst_cells(outcome.boxes, outcome.kappa[:, 1], extent, columns, rows)


def worst_cells(boxes: Any, values: Any, extent, columns: int, rows: int) -> np.ndarray:
    """Per cell (``rows`` x ``columns``, row 0 at the bottom) the largest of ``values`` (one
    per box) over the boxes that touch it (``nan`` where none)."""
    xlo, xhi, ylo, yhi = extent
    boxes = np.asarray(boxes).reshape(-1, 4)
    worst = np.full(rows * columns, -np.inf)
    cw, ch = (xhi - xlo) / columns, (yhi - ylo) / rows
    i0 = np.clip(np.floor((boxes[:, 0] - xlo) / cw), 0, columns - 1).astype(int)
    i1 = np.clip(np.ceil((boxes[:, 1] - xlo) / cw) - 1, i0, columns - 1).astype(int)
    j0 = np.clip(np.floor((boxes[:, 2] - ylo) / ch), 0, rows - 1).astype(int)
    j1 = np.clip(np.ceil((boxes[:, 3] - ylo) / ch) - 1, j0, rows - 1).astype(int)
    small = (i0 == i1) & (j0 == j1)
    np.maximum.at(worst, j0[small] * columns + i0[small], values[small])
    for k in np.flatnonzero(~small):  # a box over several cells (few: inside boxes)
        block = worst.reshape(rows, columns)[j0[k] : j1[k] + 1, i0[k] : i1[k] + 1]
        np.maximum(block, values[k], out=block)
    worst[worst == -np.inf] = np.nan
    return worst.reshape(rows, columns)


def band_edges(kappa_max: float) -> np.ndarray:
    """The upper edges of the four bands of :math:`[1, \\kappa_{max}]`."""
    return 1.0 + (kappa_max - 1.0) * np.arange(1, 5) / 4


def cell_glyph(value: float, edges: np.ndarray, kappa_max: float) -> str:
    """A cell's glyph: blank (``nan``: no box), its band, or ``?`` above ``kappa_max``."""
    if np.isnan(value):
        return " "
    if value > kappa_max:
        return UNPROVED_GLYPH
    return BAND_GLYPHS[int(np.searchsorted(edges, value))]


def legend_items(kappa_max: float) -> list[str]:
    """The bands' legend items and the "not proved" item."""
    bands = [f"{g} κ ≤ {e:.3g}" for g, e in zip(BAND_GLYPHS, band_edges(kappa_max), strict=True)]
    return [*bands, f"{UNPROVED_GLYPH} not proved ≤ {kappa_max:g}"]


def view_cells(outcome: Any, extent, columns: int, rows: int) -> np.ndarray:
    """:func:`kappa_cells` of the boxes that overlap ``extent`` alone (a box outside a
    zoomed view marks no cell at its edge)."""

    kappa = np.asarray(outcome.kappa).reshape(-1, 2)[:, 1]
    return view_worst_cells(outcome.boxes, kappa, extent, columns, rows)


def view_worst_cells(boxes: Any, values: Any, extent, columns: int, rows: int) -> np.ndarray:
    """:func:`worst_cells` of the boxes that overlap ``extent`` alone (a box outside a
    zoomed view marks no cell at its edge)."""
    xlo, xhi, ylo, yhi = extent
    boxes = np.asarray(boxes).reshape(-1, 4)
    seen = (boxes[:, 1] > xlo) & (boxes[:, 0] < xhi) & (boxes[:, 3] > ylo) & (boxes[:, 2] < yhi)
    return worst_cells(boxes[seen], np.asarray(values)[seen], extent, columns, rows)


def render_kappa_map(outcome: Any, width: int = 80) -> list[str]:
    """The κ map of a :class:`~planar_tui.workspace.paving.dexterity.DexterityOutcome` as
    lines of at most ``width`` columns (module docstring), with its extent and legend."""
    extent = fit_extent(np.asarray(outcome.boxes).reshape(-1, 4), (0.0, 1.0, 0.0, 1.0))
    xlo, xhi, ylo, yhi = extent
    columns = max(10, width - 2)
    rows = int(min(40, max(5, round(columns * (yhi - ylo) / (xhi - xlo) / CELL_ASPECT))))
    worst = kappa_cells(outcome, extent, columns, rows)
    edges = band_edges(outcome.kappa_max)
    lines = [
        f"κ map, x in [{xlo:.4g}, {xhi:.4g}] cm, y in [{ylo:.4g}, {yhi:.4g}] cm "
        "(worst certified upper bound per cell)"[:width]
    ]
    for j in range(rows - 1, -1, -1):
        cells = [cell_glyph(value, edges, outcome.kappa_max) for value in worst[j]]
        lines.append("│" + "".join(cells))
    legend = "  ".join(legend_items(outcome.kappa_max))
    return [*lines, legend[:width]]

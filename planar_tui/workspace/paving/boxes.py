"""Arrays of (x, y) boxes, rows ``x_lo, x_hi, y_lo, y_hi, ...``: their summed area, their
distinct rows, a grown copy. Shared by the pavings (:mod:`planar_tui.workspace.paving.levels`,
:mod:`planar_tui.workspace.rrr.joint`, :mod:`planar_tui.workspace.rrr.singularity`)."""

from __future__ import annotations

import numpy as np


def xy_area(boxes: np.ndarray) -> float:
    """Sum of the (x, y) areas of rows ``x_lo, x_hi, y_lo, y_hi, ...`` (>= their union)."""
    return float(np.sum((boxes[:, 1] - boxes[:, 0]) * (boxes[:, 3] - boxes[:, 2])))


def unique_rows(boxes: np.ndarray) -> np.ndarray:
    """Distinct rows of ``boxes`` (lexicographic order); several times faster than
    ``np.unique(axis=0)``, which sorts a structured view. Cells of one grid (the kept
    boxes of a bisection: every row ``x_lo, x_hi, y_lo, y_hi`` the same size, the Table 3
    paving's 944 417 rows of 10 732 cells) are told apart by their cell numbers without
    sorting (:func:`_unique_grid_cells`: 0.07 s against the sort's 0.21 s there)."""
    if len(boxes) == 0:
        return boxes.copy()
    cells = _unique_grid_cells(boxes)
    if cells is not None:
        return cells
    ordered = boxes[np.lexsort(boxes.T[::-1])]
    first = np.ones(len(ordered), dtype=bool)
    first[1:] = np.any(ordered[1:] != ordered[:-1], axis=1)
    return np.ascontiguousarray(ordered[first])


#: The most grid cells :func:`_unique_grid_cells` marks (8 MiB of flags and indices).
MAX_GRID_CELLS = 1 << 20


def _unique_grid_cells(boxes: np.ndarray) -> np.ndarray | None:
    """The distinct rows of ``boxes`` in lexicographic order when they are cells of one
    grid: four columns, one width ``w_x`` and one height ``w_y`` for every row, at most
    :data:`MAX_GRID_CELLS` cells between the lowest and highest corners. Row ``r`` gets
    cell ``(i, j) = ((x_lo - x_min) / w_x, (y_lo - y_min) / w_y)`` rounded, numbered
    ``i n_y + j``; one row per marked cell is returned in cell order. Every row is then
    checked equal to the row chosen for its cell, so rows that merely round to the same
    cell (not a grid after all) give ``None`` (the caller sorts) rather than a wrong
    answer; so does anything else that is not a grid."""
    if boxes.ndim != 2 or boxes.shape[1] != 4 or not np.all(np.isfinite(boxes)):
        return None
    width = boxes[:, 1] - boxes[:, 0]
    height = boxes[:, 3] - boxes[:, 2]
    if not (width[0] > 0 and height[0] > 0):
        return None
    if np.any(width != width[0]) or np.any(height != height[0]):
        return None
    x_min = boxes[:, 0].min()
    y_min = boxes[:, 2].min()
    n_x = int(np.rint((boxes[:, 0].max() - x_min) / width[0])) + 1
    n_y = int(np.rint((boxes[:, 2].max() - y_min) / height[0])) + 1
    if n_x * n_y > MAX_GRID_CELLS:
        return None
    i = np.rint((boxes[:, 0] - x_min) / width[0]).astype(np.int64)
    j = np.rint((boxes[:, 2] - y_min) / height[0]).astype(np.int64)
    cell = i * n_y + j
    chosen = np.full(n_x * n_y, -1, dtype=np.int64)
    chosen[cell] = np.arange(len(boxes))
    if not np.array_equal(boxes, boxes[chosen[cell]]):  # two different rows in one cell
        return None
    return np.ascontiguousarray(boxes[chosen[chosen >= 0]])


def grow(array: np.ndarray) -> np.ndarray:
    """``array`` with its first axis doubled (the new rows zero)."""
    grown = np.zeros((2 * array.shape[0], *array.shape[1:]), dtype=array.dtype)
    grown[: array.shape[0]] = array
    return grown


__all__ = ["grow", "unique_rows", "xy_area"]


def append_rows(array: np.ndarray, count: int, rows: np.ndarray) -> tuple[np.ndarray, int]:
    """Append ``rows`` after the first ``count`` rows of ``array`` (doubling it when full)."""
    needed = count + len(rows)
    if needed > array.shape[0]:
        grown = np.zeros((max(needed, 2 * array.shape[0]), *array.shape[1:]), array.dtype)
        grown[:count] = array[:count]
        array = grown
    array[count:needed] = rows
    return array, needed


def sub_grid(boxes: np.ndarray, n: int) -> np.ndarray:
    """Each box's ``n`` x ``n`` sub-boxes, ``n²`` consecutive rows per box."""
    steps = np.arange(n + 1) / n
    x = boxes[:, :1] + (boxes[:, 1:2] - boxes[:, :1]) * steps
    y = boxes[:, 2:3] + (boxes[:, 3:4] - boxes[:, 2:3]) * steps
    x[:, -1], y[:, -1] = boxes[:, 1], boxes[:, 3]
    out = np.empty((len(boxes), n, n, 4))
    out[..., 0] = x[:, :-1, None]
    out[..., 1] = x[:, 1:, None]
    out[..., 2] = y[:, None, :-1]
    out[..., 3] = y[:, None, 1:]
    return out.reshape(-1, 4)

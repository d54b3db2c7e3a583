"""Arrays of (x, y) boxes, rows ``x_lo, x_hi, y_lo, y_hi, ...``: their summed area, their
distinct rows, a grown copy. Shared by the pavings (:mod:`planar_tui.workspace.compute`,
:mod:`planar_tui.workspace.joint`, :mod:`planar_tui.workspace.singularity`)."""

from __future__ import annotations

import numpy as np


def xy_area(boxes: np.ndarray) -> float:
    """Sum of the (x, y) areas of rows ``x_lo, x_hi, y_lo, y_hi, ...`` (>= their union)."""
    return float(np.sum((boxes[:, 1] - boxes[:, 0]) * (boxes[:, 3] - boxes[:, 2])))


def unique_rows(boxes: np.ndarray) -> np.ndarray:
    """Distinct rows of ``boxes`` (lexicographic order); several times faster than
    ``np.unique(axis=0)``, which sorts a structured view."""
    if len(boxes) == 0:
        return boxes.copy()
    ordered = boxes[np.lexsort(boxes.T[::-1])]
    first = np.ones(len(ordered), dtype=bool)
    first[1:] = np.any(ordered[1:] != ordered[:-1], axis=1)
    return np.ascontiguousarray(ordered[first])


def grow(array: np.ndarray) -> np.ndarray:
    """``array`` with its first axis doubled (the new rows zero)."""
    grown = np.zeros((2 * array.shape[0], *array.shape[1:]), dtype=array.dtype)
    grown[: array.shape[0]] = array
    return grown


__all__ = ["grow", "unique_rows", "xy_area"]

"""Exact area of a union of axis-aligned rectangles (sweep line over a segment tree).

.. math:: |\\cup_k R_k| = \\sum_j (x_{j+1} - x_j)\\, L(x_j),

where :math:`x_j` are the sorted rectangle edges and :math:`L(x_j)` is the length of the
y-axis covered by the rectangles active on :math:`[x_j, x_{j+1})`, kept in a bottom-up
segment tree over the compressed y-coordinates with cover counts. Exact up to the
round-off of the final float sums (no discretisation), :math:`O(n \\log n)`.
"""

import numpy as np

from ._jit import kernel


@kernel
def _refresh(node, size, count, covered, full):
    """Covered length of ``node``: all of it with a positive count, else what its children
    cover (nothing for a leaf)."""
    if count[node] > 0:
        covered[node] = full[node]
    elif node >= size:
        covered[node] = 0.0
    else:
        covered[node] = covered[2 * node] + covered[2 * node + 1]


@kernel
def _update(lo, hi, delta, size, count, covered, full):
    """Add ``delta`` to the cover count of leaf segments ``[lo, hi)`` and refresh the
    covered lengths (see :func:`_refresh`). The nodes whose count changes are children
    of the two root paths from leaves ``lo`` and ``hi - 1``, refreshed bottom-up after."""
    left = lo + size
    right = hi + size
    while left < right:
        if left & 1:
            count[left] += delta
            _refresh(left, size, count, covered, full)
            left += 1
        if right & 1:
            right -= 1
            count[right] += delta
            _refresh(right, size, count, covered, full)
        left >>= 1
        right >>= 1
    for leaf in (lo + size, hi - 1 + size):
        node = leaf >> 1
        while node >= 1:
            _refresh(node, size, count, covered, full)
            node >>= 1


@kernel
def _sweep(boxes, order, event_x, ylo_index, yhi_index, ys):
    """Sweep the sorted edge events over a segment tree of the y-segments ``ys``."""
    m = ys.shape[0] - 1
    size = 1
    while size < m:
        size *= 2
    full = np.zeros(2 * size)
    for i in range(m):
        full[size + i] = ys[i + 1] - ys[i]
    for node in range(size - 1, 0, -1):
        full[node] = full[2 * node] + full[2 * node + 1]
    count = np.zeros(2 * size, dtype=np.int64)
    covered = np.zeros(2 * size)
    area = 0.0
    previous = event_x[order[0]]
    for e in range(order.shape[0]):
        k2 = order[e]
        x = event_x[k2]
        area += covered[1] * (x - previous)
        previous = x
        k = k2 // 2
        if boxes[k, 1] <= boxes[k, 0] or yhi_index[k] <= ylo_index[k]:
            continue
        delta = 1 if k2 % 2 == 0 else -1
        _update(ylo_index[k], yhi_index[k], delta, size, count, covered, full)
    return area


def union_area(boxes):
    """Area of the union of the rectangles ``x_lo, x_hi, y_lo, y_hi`` (rows of ``boxes``).

    The sorting is done by numpy here; the sweep is the compiled :func:`_sweep`.
    """
    boxes = np.ascontiguousarray(boxes, dtype=np.float64).reshape(-1, 4)
    if boxes.shape[0] == 0:
        return 0.0
    ys = np.unique(boxes[:, 2:4])
    if ys.shape[0] < 2:
        return 0.0
    event_x = np.ascontiguousarray(boxes[:, 0:2]).reshape(-1)
    order = np.argsort(event_x, kind="stable")
    ylo_index = np.searchsorted(ys, boxes[:, 2])
    yhi_index = np.searchsorted(ys, boxes[:, 3])
    return float(_sweep(boxes, order, event_x, ylo_index, yhi_index, ys))

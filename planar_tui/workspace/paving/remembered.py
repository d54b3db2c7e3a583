"""An evaluator that remembers what it returned for each box, so the kept boxes' enclosures
need no second evaluation once a paving is over.

The dexterity paving (:func:`~planar_tui.workspace.paving.dexterity.compute_dexterity`)
labels every box by its enclosure and keeps the enclosures of the kept ones; evaluating
them all again cost a quarter of the Table-3 region's paving (16 564 kept boxes, 0.37 s
of 1.45 s at load 12). The kernels are deterministic, so a remembered row is the row a
second call would return; a box never evaluated (or not remembered) is evaluated then.
Rows are matched by their bytes: a sorted search over the remembered rows viewed as
32-byte keys, no Python loop per box.
"""

from __future__ import annotations

from typing import Any


def _keys(boxes: Any) -> Any:
    """Each row of a contiguous float64 (k, 4) array as one 32-byte key."""
    import numpy as np

    boxes = np.ascontiguousarray(boxes, dtype=np.float64)
    return boxes.view(np.dtype((np.void, boxes.itemsize * boxes.shape[1]))).ravel()


class RememberingEvaluator:
    """``evaluate`` (boxes (k, 4) to ``(verdict, enclosure)``) remembering the enclosure
    of every box it has seen not ``OUT`` (``verdict != 0``: the boxes a paving may keep)."""

    def __init__(self, evaluate: Any):
        self._evaluate = evaluate
        self._rows: list[Any] = []
        self._enclosures: list[Any] = []

    def __call__(self, boxes: Any) -> tuple[Any, Any]:
        verdict, enclosure = self._evaluate(boxes)
        kept = verdict != 0
        self._rows.append(boxes[kept])
        self._enclosures.append(enclosure[kept])
        return verdict, enclosure

    def enclosures(self, boxes: Any) -> Any:
        """The enclosure (k, 2) of each of ``boxes``: remembered, or evaluated now."""
        import numpy as np

        boxes = np.ascontiguousarray(boxes, dtype=np.float64)
        out = np.empty((len(boxes), 2))
        found = np.zeros(len(boxes), dtype=bool)
        if self._rows and len(boxes):
            known = _keys(np.concatenate(self._rows))
            values = np.concatenate(self._enclosures)
            order = np.argsort(known, kind="stable")
            known = known[order]
            query = _keys(boxes)
            at = np.minimum(np.searchsorted(known, query), len(known) - 1)
            found = known[at] == query
            out[found] = values[order[at[found]]]
        if not found.all():
            out[~found] = self._evaluate(np.ascontiguousarray(boxes[~found]))[1]
        return out

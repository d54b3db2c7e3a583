"""The leg-wise paving stage of a workspace run (``strategy = "legwise"``).

Breadth-first over the (x, y) boxes: each level of the frontier is decided in slices of at
most ``SLICE_BOXES`` boxes by the parallel kernel
:func:`planar_tui.kernels.workspace_legwise.pave_level` (a 1-D θ search per leg and box,
see that module); after each slice the boxes it kept and the halves it split are appended
in frontier order, the progress is reported (area bracket, partial boxes) and a cancel is
honoured. A box's outcome depends on the box alone and the order is the frontier's, so
the boxes, their order and the areas are the same whatever the number of threads.
"""

from __future__ import annotations

import time

import numpy as np

from planar_tui.progress import read_only
from planar_tui.workspace.paving.boxes import append_rows

#: Boxes per kernel call: a slice takes well under 0.2 s (CHECK_INTERVAL_S) at a few µs
#: per box on one core, so progress and cancel stay responsive.
SLICE_BOXES = 8192
#: Wall time one slice may take before the next is made smaller (cancel latency).
SLICE_TARGET_S = 0.05


def _area(rows: np.ndarray) -> float:
    return float(np.sum((rows[:, 1] - rows[:, 0]) * (rows[:, 3] - rows[:, 2])))


def legwise_stage(form_code, p, spec, box, budget, tol=None):
    """Pave the (x, y) search ``box`` leg-wise down to ``spec.precision_cm``.

    Returns ``(boxes, status, xy_boxes)``: kept rows ``x_lo, x_hi, y_lo, y_hi``, their
    status (2 = inside, proved by the form; 1 = boundary) and the number of (x, y) boxes
    decided. The boxes processed counted against ``box_budget`` (``budget``) are the
    ``(x, y, θ_i)`` boxes on which a leg's interval form was evaluated, the unit of work
    comparable with the joint strategy's 5-D boxes. ``tol``: the kernels' tolerance vector
    (:mod:`planar_tui.workspace.paving.tolerance`; ``None``: the nominal robot).
    """
    from planar_tui.kernels.workspace_arc import limits_array
    from planar_tui.kernels.workspace_legwise import (
        BOUNDARY,
        INSIDE,
        NO_TOLERANCE,
        ROW_COLUMNS,
        SPLIT,
        pave_level,
        root_row,
    )

    limits = limits_array(spec.limits_rad)
    tol = NO_TOLERANCE if tol is None else tol
    frontier = root_row(box, spec.limits_rad)[None, :]
    root_area = _area(frontier)
    kept = np.zeros((4096, 4))
    status = np.zeros(4096, dtype=np.int64)
    n_kept = 0
    inside_area = kept_area = 0.0
    xy_boxes = 0
    slice_boxes = SLICE_BOXES
    while len(frontier):
        following = np.zeros((2 * len(frontier), ROW_COLUMNS))
        n_following = 0
        start = 0
        while start < len(frontier):
            stop = min(len(frontier), start + slice_boxes)
            n = stop - start
            children = np.empty((2 * n, ROW_COLUMNS))
            outcome = np.empty(n, dtype=np.int64)
            counts = np.empty(n, dtype=np.int64)
            started = time.perf_counter()
            pave_level(
                form_code,
                p,
                spec.precision_cm,
                spec.angle_scale,
                frontier,
                start,
                stop,
                children,
                outcome,
                counts,
                limits,
                tol,
            )
            elapsed = time.perf_counter() - started
            if elapsed > SLICE_TARGET_S and slice_boxes > 256:
                slice_boxes //= 2
            elif elapsed < SLICE_TARGET_S / 4:
                slice_boxes = min(8 * SLICE_BOXES, 2 * slice_boxes)
            xy_boxes += n
            keep = (outcome == BOUNDARY) | (outcome == INSIDE)
            new_rows = children[0::2][keep, :4]
            kept, _ = append_rows(kept, n_kept, new_rows)
            status, n_kept = append_rows(status, n_kept, outcome[keep])
            inside_area += _area(new_rows[outcome[keep] == INSIDE])
            kept_area += _area(new_rows)
            split = outcome == SPLIT
            halves = np.empty((2 * int(split.sum()), ROW_COLUMNS))
            halves[0::2] = children[0::2][split]
            halves[1::2] = children[1::2][split]
            following[n_following : n_following + len(halves)] = halves
            n_following += len(halves)
            start = stop
            pending = _area(frontier[stop:]) + _area(following[:n_following])
            if n_kept:
                budget.progress.show_partial(
                    boxes_cm=read_only(kept[:n_kept]), status=read_only(status[:n_kept])
                )
            budget.spend(
                int(counts.sum()), 1.0 - pending / root_area, inside_area, kept_area + pending
            )
        frontier = following[:n_following]
    return kept[:n_kept], status[:n_kept], xy_boxes

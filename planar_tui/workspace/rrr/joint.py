"""The ``joint`` strategy's paving: paper B's Algorithm 1 over ``(x, y, θ1, θ2, θ3)`` boxes,
on every thread.

Algorithm 1 is a depth-first bisection: pop a box, discard it when some leg's enclosure
:math:`F_i` excludes 0, keep its (x, y) projection when its x and y widths are both
:math:`\\le \\varepsilon`, else halve its widest side and push both halves
(:func:`planar_tui.kernels.bisection3rrr.bisect_chunk`). Every box is decided from itself
alone, so the boxes can be shared among threads in any way: each block (one per Numba
thread) runs the bisection on its own stack
(:func:`~planar_tui.kernels.bisection3rrr.bisect_blocks`, ``prange``), at most
``CHUNK_BOXES / blocks`` boxes a block between two returns to Python so that progress and
Cancel/Ctrl-C are honoured within a fraction of a second. A block whose stack runs empty
ends the kernel's round, and before the next it takes the bottom half of the fullest
stack: the shallowest boxes, the largest pieces of work left (work sharing,
:func:`~planar_tui.kernels.bisection3rrr.share_work`, in compiled code). Whatever the
number of threads or the sharing, the job's result (the distinct kept rows,
:func:`planar_tui.workspace.paving.boxes.unique_rows`) and the count of processed boxes are the
sequential bisection's.

A leg's verdict (:math:`0 \\notin F_i`) depends on the box's ``(x, y, θ_i)`` alone, and the
bisection meets the same such box again under other angles of the other legs: 12.4
million leg evaluations of Table 3's expanded form hold 0.9 million distinct boxes. Each
block keeps the verdicts it computed in a direct-mapped memo (:func:`new_memos`; one
verdict per slot, used only when all six bounds match, so bit for bit the verdict computed
afresh), which answers 86.9 % of them and made that bisection about twice as fast on one
thread. The memo also holds the cells the block kept, so that a cell kept again under
other angles is not written again.
"""

from __future__ import annotations

from typing import Protocol

import numpy as np

from planar_tui.progress import Progress, read_only
from planar_tui.workspace.paving.boxes import xy_area


class Budget(Protocol):
    """What the paving reports to (:class:`planar_tui.workspace.paving.levels.BoxBudget`)."""

    @property
    def progress(self) -> Progress: ...

    def spend(
        self, processed: int, fraction: float, lower_cm2: float, upper_cm2: float
    ) -> None: ...


def grow_axis1(array: np.ndarray) -> np.ndarray:
    """``array`` with its second axis doubled (the new rows zero)."""
    grown = np.zeros((array.shape[0], 2 * array.shape[1], *array.shape[2:]), array.dtype)
    grown[:, : array.shape[1]] = array
    return grown


def new_memos(blocks: int, slots: int | None = None) -> np.ndarray:
    """Empty memos for ``blocks`` bisection blocks: the legs' verdicts
    (:func:`planar_tui.kernels.bisection3rrr.leg_excludes_zero`) and the boxes kept
    (:func:`~planar_tui.kernels.bisection3rrr.kept_before`), ``slots`` each (a power of
    two; default ``MEMO_SLOTS``; 0: none), every row NaN (matching no box)."""
    from planar_tui.kernels.bisection3rrr import MEMO_COLUMNS, MEMO_PLANES, MEMO_SLOTS

    slots = MEMO_SLOTS if slots is None else slots
    if slots & (slots - 1):
        raise ValueError(f"memo slots must be a power of two or 0, not {slots}")
    return np.full((blocks, MEMO_PLANES, slots, MEMO_COLUMNS), np.nan)


def joint_stage(
    form_code: int,
    p: np.ndarray,
    precision_cm: float,
    angle_scale: float,
    limits_rad: np.ndarray,
    box: tuple[tuple[float, float], tuple[float, float]],
    budget: Budget,
    chunk_boxes: int,
    blocks: int | None = None,
    memo_slots: int | None = None,
) -> np.ndarray:
    """The kept (x, y) boxes of Algorithm 1 from the root ``box × limits_rad`` (rows
    ``x_lo, x_hi, y_lo, y_hi``; a box may repeat), on ``blocks`` stacks (default: one per
    Numba thread). After each round the budget gets the boxes processed, the fraction of
    the root's 5-D volume decided and an upper bound of the kept area (the kept boxes'
    areas summed, plus the pending boxes' (x, y) areas), and the progress a read-only view
    of the boxes kept so far (once there are some). Each block remembers its legs'
    verdicts and the cells it kept in a memo of ``memo_slots`` slots a plane
    (:func:`new_memos`); the memo changes no box processed or cell kept, only the time and
    how often a kept cell repeats (0 slots: every kept box is returned, repeats
    included)."""
    from numba import get_num_threads

    from planar_tui.kernels.bisection3rrr import STACK_COLUMNS, bisect_blocks, root_row
    from planar_tui.kernels.workspace3rrr import STACK_FULL

    blocks = blocks or get_num_threads()
    stacks = np.zeros((blocks, 256, STACK_COLUMNS))
    root_row(
        stacks[0, 0],
        box[0][0],
        box[0][1],
        box[1][0],
        box[1][1],
        np.asarray(limits_rad, dtype=np.float64).reshape(3, 2),
    )
    root_volume = float(np.prod(stacks[0, 0, 1:10:2] - stacks[0, 0, 0:10:2]))
    n_stack = np.zeros(blocks, dtype=np.int64)
    n_stack[0] = 1
    per_round = max(1, chunk_boxes // blocks)
    kept = np.zeros((blocks, per_round, 4))  # a processed box keeps at most one row
    n_kept = np.zeros(blocks, dtype=np.int64)
    processed = np.zeros(blocks, dtype=np.int64)
    codes = np.zeros(blocks, dtype=np.int64)
    memos = new_memos(blocks, memo_slots)
    found = np.zeros((4096, 4))
    n_found = 0
    kept_area = 0.0  # sum over kept boxes: with repeats, an upper bound of their union
    while n_stack.sum() > 0:
        n_kept[:] = 0
        bisect_blocks(
            form_code,
            p,
            precision_cm,
            angle_scale,
            stacks,
            n_stack,
            kept,
            n_kept,
            per_round,
            processed,
            codes,
            memos,
        )
        for block in range(blocks):
            rows = kept[block, : n_kept[block]]
            while n_found + len(rows) > len(found):
                found = np.concatenate([found, np.zeros_like(found)])
            found[n_found : n_found + len(rows)] = rows
            n_found += len(rows)
            kept_area += xy_area(rows)
        if np.any(codes == STACK_FULL):
            stacks = grow_axis1(stacks)
        pending = np.concatenate([stacks[b, : n_stack[b]] for b in range(blocks)])
        volume = float(np.sum(np.prod(pending[:, 1:10:2] - pending[:, 0:10:2], axis=1)))
        if n_found:
            budget.progress.show_partial(boxes_cm=read_only(found[:n_found]), status=None)
        budget.spend(
            int(processed.sum()), 1.0 - volume / root_volume, 0.0, kept_area + xy_area(pending)
        )
    return found[:n_found]

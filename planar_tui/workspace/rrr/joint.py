"""The ``joint`` strategy's paving: paper B's Algorithm 1 over ``(x, y, θ1, θ2, θ3)`` boxes,
on every thread.

Algorithm 1 is a depth-first bisection: pop a box, discard it when some leg's enclosure
:math:`F_i` excludes 0, keep its (x, y) projection when its x and y widths are both
:math:`\\le \\varepsilon`, else halve its widest side and push both halves
(:func:`planar_tui.kernels.bisection3rrr.bisect_chunk`). Every box is decided from itself
alone, so the boxes can be shared among threads in any way. A paving starts on one stack
in the calling thread (:func:`serial_blocks`) and, past :data:`SERIAL_BOXES` boxes, goes on
with one block per Numba thread, each running the bisection on its own stack
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


#: Boxes the bisection processes on one stack in this thread before it shares the rest
#: among the Numba threads (:func:`joint_stage`): about 0.1-0.2 s of work on one core,
#: more than Table 3's interval jobs (350 000-370 000 boxes), whose second thread won
#: 4-11 % of their 0.06-0.08 s but whose warm process paid more than that to load the
#: parallel kernel and start the threading layer.
SERIAL_BOXES = 1_000_000


def serial_blocks(
    form,
    p,
    precision,
    angle_scale,
    stacks,
    n_stack,
    kept,
    n_kept,
    max_boxes,
    processed,
    codes,
    memos,
):
    """:func:`~planar_tui.kernels.bisection3rrr.bisect_blocks` for one block, in this
    thread: :func:`~planar_tui.kernels.bisection3rrr.bisect_chunk` on ``stacks[0]``, no
    threading layer started."""
    from planar_tui.kernels.bisection3rrr import bisect_chunk

    n_stack[0], n_kept[0], processed[0], codes[0] = bisect_chunk(
        form,
        p,
        precision,
        angle_scale,
        stacks[0],
        n_stack[0],
        kept[0],
        n_kept[0],
        max_boxes,
        memos[0],
    )


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
    serial_boxes: int = SERIAL_BOXES,
) -> np.ndarray:
    """The kept (x, y) boxes of Algorithm 1 from the root ``box × limits_rad`` (rows
    ``x_lo, x_hi, y_lo, y_hi``; a box may repeat), on ``blocks`` stacks; by default
    (``blocks`` ``None``) on one stack in this thread for the first ``serial_boxes``
    boxes (:func:`serial_blocks`: a small paving starts no threads and loads no parallel
    kernel), then on one stack per Numba thread. After each round the budget gets the
    boxes processed, the fraction of the root's 5-D volume decided and an upper bound of
    the kept area (the kept boxes' areas summed, plus the pending boxes' (x, y) areas),
    and the progress a read-only view of the boxes kept so far (once there are some).
    Each block remembers its legs' verdicts and the cells it kept in a memo of
    ``memo_slots`` slots a plane (:func:`new_memos`); the memo changes no box processed or
    cell kept, only the time and how often a kept cell repeats (0 slots: every kept box is
    returned, repeats included)."""
    from planar_tui.kernels.bisection3rrr import STACK_COLUMNS, root_row

    stacks = np.zeros((1, 256, STACK_COLUMNS))
    root_row(
        stacks[0, 0],
        box[0][0],
        box[0][1],
        box[1][0],
        box[1][1],
        np.asarray(limits_rad, dtype=np.float64).reshape(3, 2),
    )
    paving = _Paving(stacks, budget, new_memos(1, memo_slots))
    if blocks is None:
        while paving.pending() and paving.processed < serial_boxes:
            paving.round(serial_blocks, (form_code, p, precision_cm, angle_scale), chunk_boxes)
    if paving.pending():
        from numba import get_num_threads

        from planar_tui.kernels.bisection3rrr import bisect_blocks

        paving.spread(blocks or get_num_threads(), memo_slots)
        per_round = max(1, chunk_boxes // len(paving.stacks))
        while paving.pending():
            paving.round(bisect_blocks, (form_code, p, precision_cm, angle_scale), per_round)
    return paving.found[: paving.n_found]


class _Paving:
    """The state of :func:`joint_stage`: every block's stack and memo, the boxes kept so
    far (``found[:n_found]``), their summed area, the boxes processed, the root's volume."""

    def __init__(self, stacks: np.ndarray, budget: Budget, memos: np.ndarray) -> None:
        self.stacks = stacks
        self.n_stack = np.ones(1, dtype=np.int64)
        self.memos = memos
        self.budget = budget
        self.root_volume = float(np.prod(stacks[0, 0, 1:10:2] - stacks[0, 0, 0:10:2]))
        self.found = np.zeros((4096, 4))
        self.n_found = 0
        self.kept_area = 0.0  # sum over kept boxes: with repeats, an upper bound of their union
        self.processed = 0

    def pending(self) -> bool:
        return bool(self.n_stack.sum() > 0)

    def spread(self, blocks: int, memo_slots: int | None) -> None:
        """Go on with ``blocks`` blocks: the stack and memo so far become block 0's."""
        stacks = np.zeros((blocks, *self.stacks.shape[1:]))
        stacks[0] = self.stacks[0]
        memos = new_memos(blocks, memo_slots)
        memos[0] = self.memos[0]
        n_stack = np.zeros(blocks, dtype=np.int64)
        n_stack[0] = self.n_stack[0]
        self.stacks, self.memos, self.n_stack = stacks, memos, n_stack

    def round(self, kernel, problem: tuple, per_round: int) -> None:
        """One call of ``kernel`` (``bisect_blocks`` or :func:`serial_blocks`) of at most
        ``per_round`` boxes a block; the kept boxes collected and the budget told."""
        from planar_tui.kernels.workspace3rrr import STACK_FULL

        blocks = len(self.stacks)
        kept = np.zeros((blocks, per_round, 4))  # a processed box keeps at most one row
        n_kept = np.zeros(blocks, dtype=np.int64)
        processed = np.zeros(blocks, dtype=np.int64)
        codes = np.zeros(blocks, dtype=np.int64)
        kernel(
            *problem,
            self.stacks,
            self.n_stack,
            kept,
            n_kept,
            per_round,
            processed,
            codes,
            self.memos,
        )
        for block in range(blocks):
            rows = kept[block, : n_kept[block]]
            while self.n_found + len(rows) > len(self.found):
                self.found = np.concatenate([self.found, np.zeros_like(self.found)])
            self.found[self.n_found : self.n_found + len(rows)] = rows
            self.n_found += len(rows)
            self.kept_area += xy_area(rows)
        if np.any(codes == STACK_FULL):
            self.stacks = grow_axis1(self.stacks)
        pending = np.concatenate([self.stacks[b, : self.n_stack[b]] for b in range(blocks)])
        volume = float(np.sum(np.prod(pending[:, 1:10:2] - pending[:, 0:10:2], axis=1)))
        if self.n_found:
            self.budget.progress.show_partial(
                boxes_cm=read_only(self.found[: self.n_found]), status=None
            )
        self.processed += int(processed.sum())
        self.budget.spend(
            int(processed.sum()),
            1.0 - volume / self.root_volume,
            0.0,
            self.kept_area + xy_area(pending),
        )

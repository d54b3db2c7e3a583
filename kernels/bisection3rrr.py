"""Paper B's Algorithm 1 over 5-D boxes ``(x, y, θ1, θ2, θ3)``: the ``joint`` strategy's
bisection, on an explicit stack per thread.

Pop a box; discard it when :math:`0 \\notin F_i` for some leg (the enclosures of
:mod:`kernels.workspace3rrr`); keep its (x, y) projection when its x and y widths are both
:math:`\\le \\varepsilon`; else halve the widest of
:math:`x, y, k\\theta_1, k\\theta_2, k\\theta_3` and push both halves
(:func:`bisect_chunk`). What makes it fast changes no box:

* after a :math:`\\theta_j` bisection only leg j is re-evaluated (the others' enclosures
  are the parent's, which contained 0);
* each stack row keeps the libm ``sin``/``cos`` at its angle ends, computed once at the
  split that makes an end (:func:`~kernels.interval.isincos_ends`);
* each leg's verdict is remembered in a direct-mapped memo keyed by the leg's own
  ``(x, y, θ_i)`` box (:func:`leg_excludes_zero`);
* every Numba thread runs its own stack, the work shared out between rounds in compiled
  code (:func:`bisect_blocks`).
"""

import math

import numpy as np
from numba import prange

from ._jit import kernel
from .interval import isincos_ends
from .workspace3rrr import (
    CHUNK_LIMIT,
    DONE,
    KEPT_FULL,
    STACK_FULL,
    leg_enclosure_sc,
    pop_row,
)

# Stack layout: one row per box, x_lo, x_hi, y_lo, y_hi, t1_lo, t1_hi, t2_lo, t2_hi, t3_lo,
# t3_hi, split, then per leg i the libm values at its angle's ends, sin(lo), sin(hi),
# cos(lo), cos(hi) (columns ENDS + 4 i .. ENDS + 4 i + 3; split: index 0-4 of the
# variable whose bisection made the box, -1 for the root).
ENDS = 11
STACK_COLUMNS = ENDS + 12

#: Slots of a bisection's memo per plane (a power of two): 4 096 slots (three legs, 688 kB
#: a thread; 917 kB with the kept boxes' plane) answer 86.9 % of the leg evaluations of
#: Table 3's expanded form (92.7 % repeat one; 1 024 slots: 82.3 %, 65 536: 91.9 %), and
#: ran fastest.
MEMO_SLOTS = 4096
#: A memo row: the leg's box ``x_lo, x_hi, y_lo, y_hi, t_lo, t_hi`` and its verdict (1.0
#: when the leg's enclosure excludes 0, else 0.0); a row of NaN matches no box.
MEMO_COLUMNS = 7
#: Planes of a memo: one per leg, then :data:`KEPT_PLANE`.
MEMO_PLANES = 4
#: The memo's plane of (x, y) boxes already kept (columns ``x_lo .. y_hi``).
KEPT_PLANE = 3


@kernel
def memo_slot(xlo, xhi, ylo, yhi, tlo, thi, slots):
    """The memo slot (``0 .. slots - 1``, ``slots`` a power of two) of a leg's
    ``(x, y, θ)`` box: the fractional part of a mix of its bounds times the golden ratio's
    inverse (Knuth's multiplicative hashing). Any slot is correct, since a row is used
    only when all six bounds match; the mix only spreads the boxes."""
    mix = (
        xlo * 0.7548776662466927
        + xhi * 0.5698402909980532
        + ylo * 0.3247179572447460
        + yhi * 0.8191725133961645
        + tlo * 97.41935483870968
        + thi * 61.80339887498949
    )
    f = mix * 0.6180339887498949
    return int((f - math.floor(f)) * slots) & (slots - 1)


@kernel(inline=True)
def leg_excludes_zero(form, leg, stack, row, p, memo):
    """:math:`0 \\notin F_{leg}` over the box ``stack[row]`` (its (x, y) box and the leg's
    angle, with the angle's end values), by ``form``; remembered in ``memo`` (shape
    ``(MEMO_PLANES, slots, MEMO_COLUMNS)``, ``slots`` a power of two, or 0 for no memo).

    A leg's verdict depends on its own ``(x, y, θ_leg)`` box alone, and Algorithm 1 meets
    the same such box again and again under other angles of the other legs (92.7 % of
    Table 3's expanded-form evaluations repeat one). A memo row is used only when all six
    bounds are equal to the box's, so the verdict is the one computed afresh, bit for
    bit; a slot holds the latest box that fell into it. Inlined into the bisection
    (passing the arrays to a call cost a third of its time).
    """
    xlo = stack[row, 0]
    xhi = stack[row, 1]
    ylo = stack[row, 2]
    yhi = stack[row, 3]
    tlo = stack[row, 4 + 2 * leg]
    thi = stack[row, 5 + 2 * leg]
    slots = memo.shape[1]
    slot = 0
    if slots > 0:
        slot = memo_slot(xlo, xhi, ylo, yhi, tlo, thi, slots)
        if (
            memo[leg, slot, 0] == xlo
            and memo[leg, slot, 1] == xhi
            and memo[leg, slot, 2] == ylo
            and memo[leg, slot, 3] == yhi
            and memo[leg, slot, 4] == tlo
            and memo[leg, slot, 5] == thi
        ):
            return memo[leg, slot, 6] != 0.0
    e = ENDS + 4 * leg  # the ends' libm values: no sin or cos computed here
    slo, shi, clo, chi = isincos_ends(
        tlo, thi, stack[row, e], stack[row, e + 1], stack[row, e + 2], stack[row, e + 3]
    )
    flo, fhi = leg_enclosure_sc(form, leg, xlo, xhi, ylo, yhi, tlo, thi, slo, shi, clo, chi, p)
    excluded = flo > 0.0 or fhi < 0.0
    if slots > 0:
        memo[leg, slot, 0] = xlo
        memo[leg, slot, 1] = xhi
        memo[leg, slot, 2] = ylo
        memo[leg, slot, 3] = yhi
        memo[leg, slot, 4] = tlo
        memo[leg, slot, 5] = thi
        memo[leg, slot, 6] = 1.0 if excluded else 0.0
    return excluded


@kernel(inline=True)
def kept_before(stack, row, memo):
    """True if the (x, y) box of ``stack[row]`` is the one remembered in its slot of the
    memo's :data:`KEPT_PLANE` (kept before by this block); else it is remembered there and
    False (always False without a memo).

    Algorithm 1 keeps the same (x, y) cell under many angles (Table 3's expanded form:
    944 417 kept boxes, 10 732 cells, the repeats far apart in the order of the search);
    a box kept before is not written again, which spares the copies and the distinct-rows
    pass that follow. A box's fate, and the count of boxes processed, do not change."""
    slots = memo.shape[1]
    if slots == 0:
        return False
    xlo = stack[row, 0]
    xhi = stack[row, 1]
    ylo = stack[row, 2]
    yhi = stack[row, 3]
    slot = memo_slot(xlo, xhi, ylo, yhi, 0.0, 0.0, slots)
    if (
        memo[KEPT_PLANE, slot, 0] == xlo
        and memo[KEPT_PLANE, slot, 1] == xhi
        and memo[KEPT_PLANE, slot, 2] == ylo
        and memo[KEPT_PLANE, slot, 3] == yhi
    ):
        return True
    memo[KEPT_PLANE, slot, 0] = xlo
    memo[KEPT_PLANE, slot, 1] = xhi
    memo[KEPT_PLANE, slot, 2] = ylo
    memo[KEPT_PLANE, slot, 3] = yhi
    return False


@kernel
def bisect_chunk(form, p, precision, angle_scale, stack, n_stack, kept, n_kept, max_boxes, memo):
    """Run at most ``max_boxes`` steps of Algorithm 1 on an explicit stack (no recursion).

    Pop a box; if :math:`0 \\notin F_i` for some leg, discard it (only the leg whose angle
    was just bisected is re-evaluated: the others' enclosures are unchanged; a leg's
    verdict met before is taken from ``memo``, :func:`leg_excludes_zero`); else if its x
    and y widths are both :math:`\\le \\varepsilon`, append its (x, y) projection to
    ``kept`` (unless this block kept it before, :func:`kept_before`); else bisect the
    widest of :math:`x, y, k\\theta_1, k\\theta_2, k\\theta_3` and push both halves.

    Returns ``(n_stack, n_kept, processed, status)``; ``status`` is ``DONE`` (stack empty),
    ``CHUNK_LIMIT``, ``KEPT_FULL`` or ``STACK_FULL`` (grow the array and call again).
    """
    processed = 0
    refuter = 0  # the leg that last excluded a box: tried first (neighbours often agree)
    while n_stack > 0:
        halt, row = pop_row(processed, max_boxes, n_kept, kept, n_stack, stack)
        if halt != DONE:
            return n_stack, n_kept, processed, halt
        n_stack = row
        processed += 1
        # A theta_j bisection leaves F_i (i != j) as the parent's, which contained 0.
        split = int(stack[row, 10])
        first_leg, n_legs = (split - 2, 1) if split >= 2 else (refuter, 3)
        feasible = True
        for k in range(n_legs):
            leg = (first_leg + k) % 3
            if leg_excludes_zero(form, leg, stack, row, p, memo):
                feasible = False
                refuter = leg
                break
        if not feasible:
            continue
        wx = stack[row, 1] - stack[row, 0]
        wy = stack[row, 3] - stack[row, 2]
        if wx <= precision and wy <= precision:
            if not kept_before(stack, row, memo):
                for j in range(4):
                    kept[n_kept, j] = stack[row, j]
                n_kept += 1
            continue
        widest = 0
        wmax = wx
        if wy > wmax:
            widest = 1
            wmax = wy
        for leg in range(3):
            w = angle_scale * (stack[row, 5 + 2 * leg] - stack[row, 4 + 2 * leg])
            if w > wmax:
                widest = 2 + leg
                wmax = w
        lo = stack[row, 2 * widest]
        hi = stack[row, 2 * widest + 1]
        mid = 0.5 * (lo + hi)
        child = n_stack + 1
        for j in range(STACK_COLUMNS):
            stack[child, j] = stack[row, j]
        stack[row, 2 * widest + 1] = mid
        stack[child, 2 * widest] = mid
        stack[row, 10] = widest
        stack[child, 10] = widest
        if widest >= 2:  # the new end's sin and cos, once for both halves
            e = ENDS + 4 * (widest - 2)
            s = math.sin(mid)
            c = math.cos(mid)
            stack[row, e + 1] = s
            stack[row, e + 3] = c
            stack[child, e] = s
            stack[child, e + 2] = c
        n_stack += 2
    return n_stack, n_kept, processed, DONE


@kernel
def root_row(row, xlo, xhi, ylo, yhi, limits):
    """Fill ``row`` (a stack row) with the root box ``[xlo, xhi] × [ylo, yhi] × limits``
    (``limits[i] = (lo, hi)`` of leg i's angle, rad) and its angles' end values."""
    row[0] = xlo
    row[1] = xhi
    row[2] = ylo
    row[3] = yhi
    for leg in range(3):
        lo = limits[leg, 0]
        hi = limits[leg, 1]
        row[4 + 2 * leg] = lo
        row[5 + 2 * leg] = hi
        e = ENDS + 4 * leg
        row[e] = math.sin(lo)
        row[e + 1] = math.sin(hi)
        row[e + 2] = math.cos(lo)
        row[e + 3] = math.cos(hi)
    row[10] = -1.0


#: Boxes a block of :func:`bisect_blocks` bisects between two looks at the other blocks.
SHARE_QUOTA = 512


@kernel
def share_work(stacks, n_stack):
    """Give every block with an empty stack the bottom half of the fullest stack (rows
    ``0 .. k-1``, pushed first: the shallowest boxes, the largest pieces of work left), in
    place; a stack of one box is not split."""
    for block in range(stacks.shape[0]):
        if n_stack[block] != 0:
            continue
        donor = np.argmax(n_stack)
        count = n_stack[donor]
        if count < 2:
            return
        moved = count // 2
        for i in range(moved):
            for j in range(stacks.shape[2]):
                stacks[block, i, j] = stacks[donor, i, j]
        for i in range(count - moved):  # down the stack: row moved + i is read before written
            for j in range(stacks.shape[2]):
                stacks[donor, i, j] = stacks[donor, moved + i, j]
        n_stack[block] = moved
        n_stack[donor] = count - moved


@kernel(parallel=True)
def bisect_round(
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
    """One round of :func:`bisect_blocks`: :func:`bisect_chunk` on every block ``b`` at
    once (``prange``), each on its own stack ``stacks[b, :n_stack[b]]`` and kept rows
    ``kept[b, n_kept[b]:]``, until it has processed ``max_boxes`` boxes in all
    (``processed[b]`` counts them), in steps of :data:`SHARE_QUOTA`: a block whose stack
    runs empty raises a shared flag and the others return after their current step.
    Block ``b`` keeps its legs' verdicts and the boxes it kept in ``memos[b]``; its halt
    code goes to ``codes[b]``."""
    hungry = np.zeros(1, dtype=np.int64)  # set by a block whose stack ran empty
    for b in prange(stacks.shape[0]):
        ns = n_stack[b]
        nk = n_kept[b]
        done = processed[b]
        code = DONE
        while done < max_boxes:
            ns, nk, step, code = bisect_chunk(
                form,
                p,
                precision,
                angle_scale,
                stacks[b],
                ns,
                kept[b],
                nk,
                min(SHARE_QUOTA, max_boxes - done),
                memos[b],
            )
            done += step
            if code != CHUNK_LIMIT or hungry[0] != 0:
                break
        if done >= max_boxes and code == DONE and ns > 0:
            code = CHUNK_LIMIT
        if ns == 0:
            hungry[0] = 1
        n_stack[b] = ns
        n_kept[b] = nk
        processed[b] = done
        codes[b] = code


@kernel
def bisect_blocks(
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
    """Algorithm 1 on every block at once for at most ``max_boxes`` boxes a block: rounds
    of :func:`bisect_round`, the work shared out (:func:`share_work`) before each, until
    every stack is empty, a block has processed ``max_boxes`` boxes, or a block's kept
    rows or stack are full (``KEPT_FULL``, ``STACK_FULL``: the caller grows them and
    calls again). Writes back ``n_stack[b]``, ``n_kept[b]`` (rows ``kept[b, :n_kept[b]]``,
    appended to what was there), ``processed[b]`` (this call's boxes) and the halt code
    ``codes[b]``. Every box is decided from itself alone, so the same boxes are kept
    (as distinct cells; a cell comes once a block, but for memo collisions) and counted
    however they are shared among blocks. The rounds stay in compiled code: a block whose
    stack runs empty costs a share of the work, not a return to Python (2 threads
    returned 346 times in Table 3's expanded paving where 144 returns were for progress)."""
    for b in range(stacks.shape[0]):
        processed[b] = 0
        codes[b] = DONE
    while True:
        share_work(stacks, n_stack)
        bisect_round(
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
        )
        if n_stack.sum() == 0:
            return
        for b in range(stacks.shape[0]):
            if codes[b] == KEPT_FULL or codes[b] == STACK_FULL or processed[b] >= max_boxes:
                return

"""The joint strategy's bisection (paper B, Algorithm 1) shared among threads
(:mod:`planar_tui.workspace.rrr.joint`): the same kept boxes and processed count as the
sequential depth-first bisection, whatever the number of blocks and with or without the
legs' verdict memo."""

import math

import numpy as np
import pytest
from planar_tui.kernels.bisection3rrr import (
    STACK_COLUMNS,
    bisect_chunk,
    root_row,
    share_work,
)
from planar_tui.kernels.workspace3rrr import (
    DONE,
    KEPT_FULL,
    MEAN_VALUE,
    NATURAL,
    NATURAL_EXPANDED,
    SLOPE,
    STACK_FULL,
    leg_enclosure,
)

from planar_tui.progress import Progress
from planar_tui.workspace.paving.boxes import unique_rows
from planar_tui.workspace.rrr.joint import joint_stage, new_memos
from planar_tui.workspace.rrr.robot import Robot3RRR

LIMITS_RAD = np.radians([[20, 70], [110, 160], [245, 295]])
BOX = ((0.0, 120.0), (0.0, 120.0))


class Budget:
    """Counts the boxes processed; keeps the last progress fraction."""

    def __init__(self):
        self.progress = Progress()
        self.processed = 0
        self.fractions = []

    def spend(self, processed, fraction, lower_cm2, upper_cm2):
        self.processed += processed
        self.fractions.append(fraction)


def parameters(phi_rad=0.0):
    from planar_tui.kernels.workspace3rrr import parameter_vector

    robot = Robot3RRR()
    return parameter_vector(
        robot.proximal_cm,
        robot.distal_cm,
        robot.leg_offsets_cm(phi_rad),
        robot.base_side_cm,
        robot.platform_side_cm,
        phi_rad,
    )


def sequential(form, p, precision_cm, memo_slots=None):
    """The plain depth-first Algorithm 1: one stack, bisect_chunk until DONE (with a memo
    of ``memo_slots`` slots per leg, default the product's)."""
    stack = np.zeros((4096, STACK_COLUMNS))
    root_row(stack[0], *BOX[0], *BOX[1], LIMITS_RAD)
    kept = np.zeros((1 << 20, 4))
    memo = new_memos(1, memo_slots)[0]
    n_stack, n_kept, total = 1, 0, 0
    while True:
        n_stack, n_kept, processed, code = bisect_chunk(
            form, p, precision_cm, 10.0, stack, n_stack, kept, n_kept, 10**9, memo
        )
        total += processed
        assert code not in (KEPT_FULL, STACK_FULL)
        if code == DONE:
            return kept[:n_kept], total


def algorithm_1(form, p, precision_cm, angle_scale=10.0):
    """Paper B's Algorithm 1 as printed, in Python: every leg's enclosure computed afresh
    (:func:`leg_enclosure`, its own sin and cos) for every box; none inherited, no end
    values kept. The kept (x, y) rows (one per kept box) and the number of boxes."""
    stack = [(*BOX[0], *BOX[1], *LIMITS_RAD.ravel())]
    kept, processed = [], 0
    while stack:
        box = stack.pop()
        processed += 1
        if any(
            not (lo <= 0.0 <= hi)
            for lo, hi in (
                leg_enclosure(form, leg, *box[:4], box[4 + 2 * leg], box[5 + 2 * leg], p)
                for leg in range(3)
            )
        ):
            continue
        widths = [box[1] - box[0], box[3] - box[2]]
        if widths[0] <= precision_cm and widths[1] <= precision_cm:
            kept.append(box[:4])
            continue
        widths += [angle_scale * (box[5 + 2 * leg] - box[4 + 2 * leg]) for leg in range(3)]
        widest = max(range(5), key=lambda k: (widths[k], -k))  # the first of the widest
        mid = 0.5 * (box[2 * widest] + box[2 * widest + 1])
        lower, upper = list(box), list(box)
        lower[2 * widest + 1] = mid
        upper[2 * widest] = mid
        stack += [tuple(upper), tuple(lower)]
    return np.array(kept), processed


@pytest.mark.parametrize("form", [NATURAL, NATURAL_EXPANDED, MEAN_VALUE, SLOPE])
def test_the_kernel_keeps_the_boxes_of_algorithm_1_as_printed(form):
    """The kernel's shortcuts (a θ_j bisection re-evaluates leg j only; the angles' end
    values computed once, at the split that makes them; the legs' verdicts and the boxes
    kept remembered, in a memo of any size, one slot making every box collide) change no
    box: the same count of boxes as Algorithm 1 evaluated afresh box by box, and the same
    kept boxes: every one, repeats included, without a memo; the same distinct ones, each
    written at least once and at most as often, with one."""
    p = parameters()
    precision = 120 / 2**6
    expected, expected_processed = algorithm_1(form, p, precision)
    assert len(expected) > 50  # a paving with a boundary, not a trivial one
    assert len(unique_rows(expected)) < len(expected)  # Algorithm 1 keeps cells repeatedly
    for memo_slots in (None, 0, 1, 64):
        kept, processed = sequential(form, p, precision, memo_slots)
        assert processed == expected_processed
        if memo_slots == 0:
            np.testing.assert_array_equal(
                np.sort(kept.view("f8,f8,f8,f8"), axis=0),
                np.sort(expected.view("f8,f8,f8,f8"), axis=0),
            )
        else:
            np.testing.assert_array_equal(unique_rows(kept), unique_rows(expected))
            assert len(kept) <= len(expected)


@pytest.mark.parametrize("form", [NATURAL, NATURAL_EXPANDED])
def test_a_cell_kept_again_is_written_once_with_the_memo(form):
    """The memo's plane of kept boxes: a (x, y) cell that Algorithm 1 keeps again under
    other angles is written once (up to the memo's collisions), not once a time."""
    p = parameters()
    precision = 120 / 2**7
    every, _ = sequential(form, p, precision, 0)
    remembered, _ = sequential(form, p, precision)
    cells = len(unique_rows(every))
    assert len(every) > 3 * cells  # the repeats the memo spares
    assert cells <= len(remembered) <= 1.1 * cells


def root_stack():
    stack = np.zeros((64, STACK_COLUMNS))
    root_row(stack[0], *BOX[0], *BOX[1], LIMITS_RAD)
    return stack


def test_a_remembered_verdict_is_used_for_its_own_box_only():
    """The memo is consulted: a row holding the root's leg-0 box with the verdict
    "excludes 0" (false: the root holds the workspace) discards the root at once; the
    same row with one bound an ulp off is not used."""
    from planar_tui.kernels.bisection3rrr import MEMO_SLOTS, memo_slot

    p = parameters()
    leg0 = (*BOX[0], *BOX[1], *LIMITS_RAD[0])

    def run(memo):
        kept = np.zeros((16, 4))
        _, n_kept, processed, _ = bisect_chunk(
            NATURAL, p, 1.0, 10.0, root_stack(), 1, kept, 0, 3, memo
        )
        return processed, n_kept

    assert run(new_memos(1)[0]) == (3, 0)  # the root is split, its halves popped
    lying = new_memos(1)[0]
    lying[0, memo_slot(*leg0, MEMO_SLOTS)] = (*leg0, 1.0)
    assert run(lying) == (1, 0)  # the lie is believed: the root is gone
    off_by_an_ulp = (*leg0[:5], np.nextafter(leg0[5], np.inf))
    memo = new_memos(1)[0]
    memo[0, memo_slot(*leg0, MEMO_SLOTS)] = (*off_by_an_ulp, 1.0)
    assert run(memo) == (3, 0)


def test_memo_slots_are_a_power_of_two_and_in_range():
    from planar_tui.kernels.bisection3rrr import memo_slot

    with pytest.raises(ValueError, match="power of two"):
        new_memos(1, 3000)
    rng = np.random.default_rng(3)
    bounds = rng.uniform(-1e6, 1e6, size=(2000, 6))
    for slots in (1, 2, 4096):
        seen = {memo_slot(*row, slots) for row in bounds}
        assert min(seen) >= 0 and max(seen) < slots
        assert len(seen) >= min(slots, 2000) // 2  # the boxes spread out


@pytest.mark.parametrize("form", [NATURAL, MEAN_VALUE, SLOPE])
def test_every_block_count_keeps_the_sequential_boxes(form):
    p = parameters()
    precision = 120 / 2**6
    expected, expected_processed = sequential(form, p, precision, 0)
    assert len(expected) > 100  # a paving with a boundary, not a trivial one
    for blocks in (1, 2, 3, 7):
        budget = Budget()
        kept = joint_stage(form, p, precision, 10.0, LIMITS_RAD, BOX, budget, 5000, blocks, 0)
        # without a memo: the same multiset of kept boxes, so the same distinct rows
        assert len(kept) == len(expected)
        np.testing.assert_array_equal(unique_rows(kept), unique_rows(expected))
        # with the memo: the same distinct rows, about once a block (a cell whose slot
        # another cell took in between is written again)
        remembered = joint_stage(form, p, precision, 10.0, LIMITS_RAD, BOX, Budget(), 5000, blocks)
        cells = unique_rows(expected)
        np.testing.assert_array_equal(unique_rows(remembered), cells)
        assert len(remembered) <= min(len(expected), 2 * blocks * len(cells))
        assert budget.processed == expected_processed
        assert budget.fractions[-1] == pytest.approx(1.0)
        assert all(
            b >= a - 1e-12 for a, b in zip(budget.fractions, budget.fractions[1:], strict=False)
        )


def test_share_work_moves_the_bottom_half_of_the_fullest_stack():
    stacks = np.zeros((3, 8, STACK_COLUMNS))
    stacks[1, :5, 0] = [1, 2, 3, 4, 5]  # pushed first at the bottom
    stacks[2, :2, 0] = [6, 7]
    n_stack = np.array([0, 5, 2])
    share_work(stacks, n_stack)
    assert list(n_stack) == [2, 3, 2]
    assert list(stacks[0, :2, 0]) == [1, 2]  # the shallowest boxes move
    assert list(stacks[1, :3, 0]) == [3, 4, 5]
    # a single box is never split
    one = np.zeros((2, 4, STACK_COLUMNS))
    counts = np.array([1, 0])
    share_work(one, counts)
    assert list(counts) == [1, 0]


def test_the_shared_paving_reproduces_table3_natural_area_bracket():
    """Independent check of the threaded paving at the paper's precision: the natural
    form's kept area covers the exact area 106.750 cm² (paper B, Table 3)."""
    from planar_tui.workspace.paving.boxes import xy_area

    p = parameters()
    budget = Budget()
    kept = unique_rows(joint_stage(SLOPE, p, 120 / 2**8, 10.0, LIMITS_RAD, BOX, budget, 20000, 2))
    assert xy_area(kept) >= 106.75
    assert math.isfinite(xy_area(kept))


@pytest.mark.parametrize("serial_boxes", [0, 700, 10**9])
def test_a_serial_start_keeps_the_sequential_boxes(serial_boxes):
    """The default start (``blocks`` ``None``): the first ``serial_boxes`` boxes on one
    stack in this thread, then the rest shared among the threads (0: threads from the
    start; 10⁹: never); the same distinct cells and processed count as Algorithm 1."""
    p = parameters()
    precision = 120 / 2**6
    expected, expected_processed = sequential(MEAN_VALUE, p, precision, 0)
    assert expected_processed > 2 * 700  # the serial start ends before the paving does
    budget = Budget()
    kept = joint_stage(
        MEAN_VALUE, p, precision, 10.0, LIMITS_RAD, BOX, budget, 500, serial_boxes=serial_boxes
    )
    np.testing.assert_array_equal(unique_rows(kept), unique_rows(expected))
    assert budget.processed == expected_processed
    assert budget.fractions[-1] == pytest.approx(1.0)


def test_a_small_paving_starts_no_thread_and_the_warmup_reaches_the_parallel_kernel():
    """Table 3's size of paving runs in this thread: numba's threading layer is not
    started (a fresh process); the joint warm-up's second example is large enough (by the
    job's own estimate, within about 2x of the count) to go on in parallel, so that the
    warm-up compiles the parallel kernel as well."""
    import os
    import subprocess
    import sys

    from planar_tui.presets import parse_preset, parse_toml
    from planar_tui.warmup import example
    from planar_tui.workspace.rrr.compute import estimate_boxes
    from planar_tui.workspace.rrr.joint import SERIAL_BOXES
    from tests.conftest import REPO

    code = (
        "from planar_tui.runtime import prepare_kernels\n"
        "prepare_kernels()\n"
        "import numba.np.ufunc.parallel as parallel\n"
        "from tests.test_workspace_joint_parallel import *\n"
        "kept = joint_stage(SLOPE, parameters(), 120 / 2**8, 10.0, LIMITS_RAD, BOX, Budget(),"
        " 200_000)\n"
        "print(len(unique_rows(kept)) > 300, parallel._is_initialized)\n"
    )
    env = dict(os.environ, PYTHONPATH=str(REPO))
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True, cwd=REPO
    )
    assert out.stdout.split() == ["True", "False"]
    text = example("workspace:joint")
    assert text is not None
    jobs = parse_preset("warm-up", parse_toml("warm-up", text)).jobs
    assert estimate_boxes(jobs[0].robot, jobs[0].spec) < SERIAL_BOXES // 2
    assert estimate_boxes(jobs[1].robot, jobs[1].spec) > 2 * SERIAL_BOXES

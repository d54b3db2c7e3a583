"""Certified interference-free regions of any parallel robot: the paving, its bracket and
its columns.

With ``leg_width_cm`` = :math:`w` a single-orientation workspace job also paves its search
box for the *interference-free region*: the points where the working mode (the job's
``elbow``, resolved as with ``singularities = true``) closes every leg within its limits
and no two of its moving links, each a capsule of diameter :math:`w` about its segment,
overlap, nor a link and the platform polygon (:mod:`kernels.interference` names the pairs
checked: links of different chains at distance :math:`\\ge w` unless they share a moving
joint, every link at distance :math:`\\ge w/2` from the platform but where it is jointed to
it; the links of one chain share a joint in turn and are not checked).

A robot's :class:`~planar_tui.workspace.paving.mechanism.Mechanism` gives an *evaluator*
(its ``interference`` method): for (k, 4) boxes, each box's verdict in the mode (as the
dexterity evaluator's) and a certified enclosure ``(gap_lo, gap_hi)`` of the gap
:math:`\\min_{pairs}(d - d_{req})` over the box's points in the mode's workspace. The paving
is the dexterity paving's (:mod:`planar_tui.workspace.paving.dexterity`) with the bound
:math:`-gap \\le 0`: a box is *inside* when ``IN`` with ``gap_lo >= 0``, *outside* when
``OUT`` or ``gap_hi < 0``, else halved down to ``precision_cm`` and its leaves refined on a
grid; so ``|inside| <= interference-free area <= |kept|``.

Over an orientation range ``orientation_deg = [lo, hi]`` (the working mode given: the
3-RRR's ``elbow``, the 3-PRR's ``slider_modes``) a point is interference-free when *every*
φ of the range closes its legs in the mode and keeps the clearance; the evaluator
(:func:`range_interference`) is the robot's pose-box clearance (its mechanism's
``pose_clearance``, the certified paths' test) sliced over the range
(:mod:`planar_tui.workspace.paving.orientation_dexterity`): a box's gap enclosure is the
minimum over its slices, so the paving, the columns, the boxes and the map are the
one-orientation ones.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from planar_tui.csvio import CsvTable
from planar_tui.schema import TableReader, number, setting
from planar_tui.workspace.paving.dexterity import IN, OUT, decider, refine_leaves, refuse_unpaved
from planar_tui.workspace.paving.orientation_dexterity import range_phi_rad, sliced
from planar_tui.workspace.paving.rows import AppendedRows

if TYPE_CHECKING:
    import numpy as np

    from planar_tui.workspace.paving.levels import BoxBudget

#: The summary's interference columns (after the dexterity's, before the wall time).
HEADER = (
    "leg_width_cm",
    "interference_free_area_inside_cm2",
    "interference_free_area_kept_cm2",
)
#: The interference boxes' labels in the boxes CSV.
STATUS_NAMES = {2: "interference-free", 1: "interference-boundary"}

Evaluator = Callable[["np.ndarray"], tuple["np.ndarray", "np.ndarray"]]


def width_setting() -> Any:
    """``leg_width_cm``: the links' capsule diameter :math:`w` (> 0)."""
    return setting(
        number(positive=True),
        default=None,
        type_doc="number > 0",
        doc="also certify the interference-free region: links as capsules of this width, "
        "the platform as its polygon (docs/interference.md)",
    )


def check_interference(values: dict[str, Any], reader: TableReader) -> None:
    """``leg_width_cm`` needs a form with boxes and no tolerance (with a range of
    orientations, the working mode ``elbow`` or ``slider_modes`` given)."""
    if values.get("leg_width_cm") is not None:
        refuse_unpaved("leg_width_cm", values, reader, ranges=True)


@dataclass
class InterferenceOutcome:
    """The interference paving's kept boxes (rows ``x_lo, x_hi, y_lo, y_hi``; ``status`` 2
    = interference-free, 1 = boundary), their gap enclosures (``gap`` (k, 2), cm), the
    certified area bracket and the working mode (``"1 -1 1"``)."""

    boxes: np.ndarray
    status: np.ndarray
    gap: np.ndarray
    width_cm: float
    area_inside_cm2: float
    area_kept_cm2: float
    elbow: str
    seconds: float

    def columns(self) -> list:
        """The summary's :data:`HEADER` cells."""
        return [self.width_cm, self.area_inside_cm2, self.area_kept_cm2]

    def describe(self) -> str:
        """``interference-free (legs 2 cm wide): area in [lo, hi] cm2, elbow [1 -1 1]``."""
        mode = f", elbow [{self.elbow}]" if self.elbow else ""
        return (
            f"interference-free (links {self.width_cm:g} cm wide): area in "
            f"[{self.area_inside_cm2:.5g}, {self.area_kept_cm2:.5g}] cm2{mode}"
        )


def as_bound(evaluate: Evaluator) -> Evaluator:
    """The evaluator as the dexterity paving's: ``(verdict, [-gap_hi, -gap_lo])``, a bound
    to hold at most 0."""
    import numpy as np

    def bound(boxes: Any) -> tuple[Any, Any]:
        verdict, gap = evaluate(boxes)
        return verdict, np.ascontiguousarray(-gap[:, ::-1])

    return bound


def range_interference(mechanism: Any, job: Any) -> Evaluator:
    r"""The evaluator of a job with ``leg_width_cm`` and ``orientation_deg = [lo, hi]``:
    its ``mechanism``'s pose-box clearance (``pose_clearance``, built at the first call: its
    kernels import after ``prepare_kernels``) sliced over the range
    (:func:`~planar_tui.workspace.paving.orientation_dexterity.sliced`, on the bound
    :math:`-gap \le 0`): a slice holds when ``IN`` with ``gap_lo >= 0``, fails when
    ``OUT`` or ``gap_hi < 0``; a box's gap enclosure is ``(min_s gap_lo, min_s gap_hi)``
    over its final and its tested slices."""
    import numpy as np

    robot, spec = job.robot, job.spec

    def make_test() -> Any:
        clearance = mechanism.pose_clearance(robot, spec)

        def test(rows: Any) -> tuple[Any, Any, Any]:
            verdict, gap = clearance(rows)
            return verdict, -gap[:, 1:], -gap[:, :1]

        return test

    evaluate = sliced(
        make_test,
        range_phi_rad(spec),
        mechanism.characteristic_length_cm(robot, spec),
        1,
        lambda verdict, lo, hi: (verdict == IN) & (hi[:, 0] <= 0.0),
        lambda verdict, lo, hi: (verdict == OUT) | (lo[:, 0] > 0.0),
    )

    def evaluate_gap(boxes: Any) -> tuple[Any, Any]:
        verdict, lower, upper = evaluate(boxes)
        return verdict, np.column_stack([-upper[:, 0], -lower[:, 0]])

    return evaluate_gap


def compute_interference(
    evaluate: Evaluator,
    extent: tuple[float, float, float, float],
    precision_cm: float,
    width_cm: float,
    elbow: str,
    budget: BoxBudget,
) -> InterferenceOutcome:
    """Pave ``extent`` (``x_lo, x_hi, y_lo, y_hi``, holding the workspace) for the
    interference-free region down to ``precision_cm`` (module docstring)."""
    import numpy as np

    from planar_tui.workspace.paving.boxes import xy_area
    from planar_tui.workspace.paving.levels import pave_in_levels
    from planar_tui.workspace.paving.remembered import RememberingEvaluator

    started = time.perf_counter()
    budget.progress.start(1.0, f"interference-free region (links {width_cm:g} cm wide)")
    remembered = RememberingEvaluator(evaluate)  # the kept boxes' gaps without a second pass
    bound = as_bound(remembered)
    decide = decider(bound, 0.0, precision_cm)
    boxes, status = pave_in_levels(np.array([extent], dtype=float), budget, decide)
    boxes, status = refine_leaves(bound, boxes, status, 0.0, budget)
    gap = remembered.enclosures(boxes)
    return InterferenceOutcome(
        boxes=boxes,
        status=status,
        gap=gap,
        width_cm=width_cm,
        area_inside_cm2=xy_area(boxes[status == 2]),
        area_kept_cm2=xy_area(boxes),
        elbow=elbow,
        seconds=time.perf_counter() - started,
    )


def job_interference(job: Any, prepared: Any, extent, budget: BoxBudget, elbow: str = ""):
    """The interference-free region of a job with ``leg_width_cm`` (its Mechanism's
    evaluator in the prepared working mode ``elbow``)."""
    spec = job.spec
    evaluate = spec.mechanism.interference(job, prepared)
    return compute_interference(
        evaluate, extent, spec.precision_cm, spec.leg_width_cm, elbow, budget
    )


def interference_names(job: Any) -> tuple[str, ...]:
    """A job's interference columns: :data:`HEADER` with ``leg_width_cm``, none without."""
    return HEADER if getattr(job.spec, "leg_width_cm", None) is not None else ()


class InterferenceRows(AppendedRows):
    """The boxes CSV's rows with ``leg_width_cm``: the table's rows, then the interference
    boxes labelled ``interference-free`` or ``interference-boundary`` (the table's extra
    columns empty)."""

    def __init__(self, rows: Any, width: int, outcome: InterferenceOutcome):
        super().__init__(rows, outcome)
        self._pad = [""] * (width - 5)

    def stage_row(self, i: int) -> list:
        name = STATUS_NAMES[int(self._outcome.status[i])]
        return [*self._outcome.boxes[i].tolist(), name, *self._pad]


def boxes_table(table: Any, outcome: InterferenceOutcome | None) -> Any:
    """The boxes CSV ``table`` with, with ``leg_width_cm``, the interference boxes
    (:class:`InterferenceRows`)."""
    if outcome is None:
        return table
    return CsvTable(table.header, InterferenceRows(table.rows, len(table.header), outcome))

"""Certified dexterous regions of any parallel robot: the paving, its bracket and its columns.

With ``kappa_max`` a single-orientation workspace job also paves its search box for the
*dexterous region*: the points where the working mode (the job's ``elbow``, resolved as with
``singularities = true``) closes every leg within its limits and the condition number
:math:`\\kappa = \\sigma_{max}(J) / \\sigma_{min}(J)` of the Jacobian :math:`J` mapping the
actuated joint rates to the twist :math:`(\\dot x, \\dot y, L\\dot\\varphi)` (the five-bar:
to :math:`(\\dot x, \\dot y)`) is at most ``kappa_max``; :math:`\\kappa = \\infty` where
:math:`J` is singular. :math:`L` is ``characteristic_length_cm`` (default: the platform's
circumradius, :func:`circumradius_cm`). With a range of orientations the evaluator is
:mod:`~planar_tui.workspace.paving.orientation_dexterity`'s, with a tolerance
:mod:`~planar_tui.workspace.paving.tolerance_dexterity`'s (every robot or some robot within
it); the paving below is the same.

A robot's :class:`~planar_tui.workspace.paving.mechanism.Mechanism` gives an *evaluator*
(its ``dexterity`` method): for (k, 4) boxes, each box's verdict in the mode
(:data:`OUT`: some leg cannot close within its limits at any point; :data:`IN`: every leg
closes at every point; else unsure) and a certified enclosure ``(kappa_lo, kappa_hi)`` of κ
over the box's points in the mode's workspace (:mod:`kernels.dexterity`). The paving
(:func:`compute_dexterity`, level by level with
:func:`~planar_tui.workspace.paving.levels.pave_in_levels`) labels a box *inside* when it is
``IN`` with ``kappa_hi <= kappa_max``, *outside* when it is ``OUT`` or ``kappa_lo >
kappa_max``, and halves the rest down to ``precision_cm``; a leaf left undecided is
replaced by its ``LEAF_GRID`` x ``LEAF_GRID`` sub-boxes, each labelled the same way, those
not proved outside kept (*inside*, or *boundary*). So every dexterous point lies in a kept box and
every point of an inside box is dexterous: ``|inside| <= dexterous area <= |kept|``.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from planar_tui.csvio import CsvTable
from planar_tui.schema import TableReader, number, setting
from planar_tui.workspace.paving.rows import AppendedRows

if TYPE_CHECKING:
    import numpy as np

    from planar_tui.workspace.paving.levels import BoxBudget

#: The summary's dexterity columns (after the circle's, before the wall time).
HEADER = (
    "kappa_max",
    "characteristic_length_cm",
    "dexterous_area_inside_cm2",
    "dexterous_area_kept_cm2",
)
#: The boxes CSV's extra columns with ``kappa_max``: each box's κ enclosure (the workspace's
#: boxes leave them empty; an empty ``kappa_hi`` is unbounded).
BOXES_COLUMNS = ("kappa_lo", "kappa_hi")
#: The dexterity boxes' labels in the boxes CSV.
STATUS_NAMES = {2: "dexterous", 1: "dexterous-boundary"}
#: The evaluator's verdicts (:mod:`kernels.dexterity`).
OUT, UNSURE, IN = 0, 1, 2
#: A boundary leaf is replaced by its LEAF_GRID x LEAF_GRID sub-boxes not proved outside.
LEAF_GRID = 4
#: Boundary leaves refined per evaluator call.
CHUNK_LEAVES = 512

Evaluator = Callable[["np.ndarray"], tuple["np.ndarray", "np.ndarray"]]


def kappa_setting() -> Any:
    """``kappa_max``: the dexterous region's bound on κ (> 1)."""
    return setting(
        number(positive=True),
        default=None,
        type_doc="number > 1",
        doc="also certify the dexterous region: the working mode's points with κ ≤ kappa_max "
        "(docs/dexterity.md)",
    )


def length_setting() -> Any:
    """``characteristic_length_cm``: :math:`L` of the twist :math:`(\\dot x, \\dot y,
    L\\dot\\varphi)`."""
    return setting(
        number(positive=True),
        default=None,
        type_doc="number > 0",
        default_doc="the platform's circumradius",
        doc="length L weighting the platform's rotation in κ (with kappa_max)",
    )


def check_dexterity(values: dict[str, Any], reader: TableReader, tolerances=False) -> None:
    """``kappa_max`` is above 1 and needs a form with boxes (with a range of orientations,
    the working mode ``elbow`` or ``slider_modes`` given) and, unless the kind certifies
    them (``tolerances``, :mod:`~planar_tui.workspace.paving.tolerance_dexterity`), no
    tolerance; ``characteristic_length_cm`` goes with it."""
    kappa = values["kappa_max"]
    length = values.get("characteristic_length_cm")
    if kappa is None:
        if length is not None:
            raise reader.error("characteristic_length_cm", "is set without kappa_max", "kappa_max")
        return
    if not kappa > 1.0:
        raise reader.error("kappa_max", f"is {kappa:g}: κ is at least 1", "a number > 1")
    refuse_unpaved("kappa_max", values, reader, ranges=True, tolerances=tolerances)


def refuse_unpaved(
    key: str, values: dict[str, Any], reader: TableReader, ranges=False, tolerances=False
) -> None:
    """A certifying stage's ``key`` needs a form with boxes, (unless ``ranges``) a single
    orientation and (unless ``tolerances``) no tolerance; with a range, its working mode
    given (``elbow``, ``slider_modes``, where the kind has one): one line naming what is
    set with it otherwise."""
    ranged = isinstance(values.get("orientation_deg"), tuple)
    if ranged and not ranges:
        raise reader.error(
            key, "is set with orientation_deg = [lo, hi]", "a single orientation_deg"
        )
    for mode in ("elbow", "slider_modes") if ranged else ():  # a range's mode is given
        if mode in values and values[mode] is None:
            raise reader.error(
                mode,
                f"is not set with {key} and orientation_deg = [lo, hi]",
                f"{mode} = [s1, s2, s3], each 1 or -1",
            )
    if values.get("form") == "geometric":
        raise reader.error(key, 'is set with form = "geometric"', "a form with boxes")
    if not tolerances and values.get("tolerance_mode") is not None:
        raise reader.error(key, "is set with a tolerance", "no tolerance_cm")


def circumradius_cm(points: Sequence[Sequence[float]]) -> float:
    """The circumradius :math:`abc / (4 \\cdot \\text{area})` of the platform triangle (half
    its longest side when the points are collinear)."""
    (ax, ay), (bx, by), (cx, cy) = points[:3]
    a = math.hypot(bx - cx, by - cy)
    b = math.hypot(ax - cx, ay - cy)
    c = math.hypot(ax - bx, ay - by)
    area = 0.5 * abs((bx - ax) * (cy - ay) - (by - ay) * (cx - ax))
    if area <= 1e-12 * max(a, b, c) ** 2:
        return 0.5 * max(a, b, c)
    return a * b * c / (4.0 * area)


@dataclass
class DexterityOutcome:
    """The dexterity paving's kept boxes (rows ``x_lo, x_hi, y_lo, y_hi``; ``status`` 2 =
    dexterous, 1 = boundary), their κ enclosures (``kappa`` (k, 2); ``inf`` unbounded), the
    certified area bracket and the working mode (``"1 -1 1"``)."""

    boxes: np.ndarray
    status: np.ndarray
    kappa: np.ndarray
    kappa_max: float
    length_cm: float | None
    area_inside_cm2: float
    area_kept_cm2: float
    elbow: str
    boxes_processed: int
    seconds: float
    #: The boxes proved outside (rows as ``boxes``): with the kept ones they partition the
    #: extent (:mod:`planar_tui.workspace.paving.disc`).
    outside: np.ndarray | None = None
    #: The largest certified dexterous disc (set by the dexterity stage).
    disc: Any = None

    def columns(self) -> list:
        """The summary's :data:`HEADER` cells (``characteristic_length_cm`` empty for a
        robot without orientation)."""
        length = "" if self.length_cm is None else self.length_cm
        return [self.kappa_max, length, self.area_inside_cm2, self.area_kept_cm2]

    def describe(self) -> str:
        """``dexterous (κ ≤ 4, L = 25 cm): area in [lo, hi] cm2, elbow [+1 -1 +1]``."""
        length = "" if self.length_cm is None else f", L = {self.length_cm:.4g} cm"
        mode = f", elbow [{self.elbow}]" if self.elbow else ""
        return (
            f"dexterous (κ ≤ {self.kappa_max:g}{length}): area in "
            f"[{self.area_inside_cm2:.5g}, {self.area_kept_cm2:.5g}] cm2{mode}"
        )


def label_boxes(evaluate: Evaluator, boxes: np.ndarray, kappa_max: float) -> np.ndarray:
    """Each box's label: 2 inside (``IN``, ``kappa_hi <= kappa_max``), 0 outside (``OUT``
    or ``kappa_lo > kappa_max``), 1 undecided."""
    import numpy as np

    verdict, kappa = evaluate(np.ascontiguousarray(boxes))
    label = np.ones(len(boxes), dtype=np.int64)
    label[(verdict == IN) & (kappa[:, 1] <= kappa_max)] = 2
    label[proved_outside(verdict, kappa, kappa_max)] = 0
    return label


def proved_outside(verdict: np.ndarray, kappa: np.ndarray, kappa_max: float) -> np.ndarray:
    """The boxes with no dexterous point: ``OUT`` or ``kappa_lo > kappa_max``."""
    return (verdict == OUT) | (kappa[:, 0] > kappa_max)


def decider(evaluate: Evaluator, kappa_max: float, precision_cm: float) -> Callable[..., None]:
    """One level's decision of the dexterity paving (module docstring), with the signature
    :func:`~planar_tui.workspace.paving.levels.pave_in_levels` drives."""
    import numpy as np

    from planar_tui.kernels.workspace_arc import SPLIT

    def decide(rows: Any, start: int, stop: int, children: Any, outcome: Any) -> None:
        boxes = rows[start:stop]
        label = label_boxes(evaluate, boxes, kappa_max)
        widths = np.maximum(boxes[:, 1] - boxes[:, 0], boxes[:, 3] - boxes[:, 2])
        split = (label == 1) & (widths > precision_cm)
        children[0::2] = boxes
        children[1::2] = boxes
        wide_x = (boxes[:, 1] - boxes[:, 0]) >= (boxes[:, 3] - boxes[:, 2])
        mid_x = 0.5 * (boxes[:, 0] + boxes[:, 1])
        mid_y = 0.5 * (boxes[:, 2] + boxes[:, 3])
        first, second = children[0::2], children[1::2]  # views
        on_x, on_y = split & wide_x, split & ~wide_x
        first[on_x, 1] = second[on_x, 0] = mid_x[on_x]
        first[on_y, 3] = second[on_y, 2] = mid_y[on_y]
        outcome[:] = np.where(split, SPLIT, label)

    return decide


def refine_leaves(
    evaluate: Evaluator, boxes: Any, status: Any, kappa_max: float, budget: BoxBudget
) -> tuple[Any, Any]:
    """Replace each boundary leaf by its ``LEAF_GRID`` x ``LEAF_GRID`` sub-boxes that are
    not proved outside, each with its own label (:func:`label_boxes`), in chunks of
    ``CHUNK_LEAVES`` leaves (progress and Cancel between them)."""
    import numpy as np

    from planar_tui.workspace.paving.boxes import sub_grid

    boundary = status == 1
    leaves = boxes[boundary]
    parts, labels = [boxes[~boundary]], [status[~boundary]]
    for start in range(0, len(leaves), CHUNK_LEAVES):
        cells = sub_grid(leaves[start : start + CHUNK_LEAVES], LEAF_GRID)
        label = label_boxes(evaluate, cells, kappa_max)
        parts.append(cells[label > 0])
        labels.append(label[label > 0])
        done = min(len(leaves), start + CHUNK_LEAVES)
        budget.progress.advance(0.0, f"{done:,} of {len(leaves):,} boundary leaves refined")
    return np.ascontiguousarray(np.concatenate(parts)), np.concatenate(labels)


def compute_dexterity(
    evaluate: Evaluator,
    extent: tuple[float, float, float, float],
    precision_cm: float,
    kappa_max: float,
    length_cm: float | None,
    elbow: str,
    budget: BoxBudget,
) -> DexterityOutcome:
    """Pave ``extent`` (``x_lo, x_hi, y_lo, y_hi``, holding the workspace) for the dexterous
    region down to ``precision_cm`` (module docstring), then enclose κ on each kept box."""
    import numpy as np

    from planar_tui.workspace.paving.boxes import xy_area
    from planar_tui.workspace.paving.levels import pave_in_levels
    from planar_tui.workspace.paving.remembered import RememberingEvaluator

    started = time.perf_counter()
    processed = budget.processed
    budget.progress.start(1.0, f"dexterous region (κ ≤ {kappa_max:g})")
    remembered = RememberingEvaluator(evaluate)  # the kept boxes' κ without a second pass
    outside: list[np.ndarray] = []
    recorded = recording_outside(remembered, kappa_max, outside)
    decide = decider(recorded, kappa_max, precision_cm)
    boxes, status = pave_in_levels(np.array([extent], dtype=float), budget, decide)
    boxes, status = refine_leaves(recorded, boxes, status, kappa_max, budget)
    kappa = remembered.enclosures(boxes)
    inside = xy_area(boxes[status == 2])
    return DexterityOutcome(
        boxes=boxes,
        status=status,
        kappa=kappa,
        kappa_max=kappa_max,
        length_cm=length_cm,
        area_inside_cm2=inside,
        area_kept_cm2=xy_area(boxes),
        elbow=elbow,
        boxes_processed=budget.processed - processed,
        seconds=time.perf_counter() - started,
        outside=np.concatenate(outside) if outside else np.empty((0, 4)),
    )


def recording_outside(evaluate: Evaluator, kappa_max: float, outside: list) -> Evaluator:
    """``evaluate``, appending to ``outside`` the boxes it proves outside (``OUT`` or
    ``kappa_lo > kappa_max``, :func:`proved_outside`): the paving drops them."""

    def recorded(boxes: Any) -> tuple[Any, Any]:
        verdict, kappa = evaluate(boxes)
        out = proved_outside(verdict, kappa, kappa_max)
        if out.any():
            outside.append(boxes[out].copy())
        return verdict, kappa

    return recorded


def planar_dexterity(job: Any, prepared: Any, extent, budget: BoxBudget) -> DexterityOutcome:
    """The dexterous region of a 3-RPR or 3-PRR job with ``kappa_max`` (its Mechanism's
    evaluator, :math:`L` as the evaluator takes it: the job's or the circumradius)."""
    spec = job.spec
    points = job.robot.platform_points_cm
    length = spec.characteristic_length_cm or circumradius_cm(points)
    evaluate = spec.mechanism.dexterity(job, prepared)
    return compute_dexterity(
        evaluate, extent, spec.precision_cm, spec.kappa_max, length, "", budget
    )


def dexterity_names(job: Any) -> tuple[str, ...]:
    """A job's dexterity columns: :data:`HEADER` and the dexterous disc's
    (:data:`planar_tui.workspace.paving.disc.HEADER`) with ``kappa_max``, none without."""
    from planar_tui.workspace.paving.disc import HEADER as DISC_HEADER

    return (*HEADER, *DISC_HEADER) if getattr(job.spec, "kappa_max", None) is not None else ()


class DexterityRows(AppendedRows):
    """The boxes CSV's rows with ``kappa_max``: the workspace's rows (a
    :class:`~planar_tui.workspace.paving.levels.BoxRows`) with empty κ cells, then the
    dexterity boxes labelled ``dexterous`` or ``dexterous-boundary`` with their κ enclosure
    (an empty ``kappa_hi``: unbounded)."""

    def table_row(self, row: Any) -> list:
        return [*row, "", ""]

    def stage_row(self, i: int) -> list:
        out = self._outcome
        lo, hi = (float(v) for v in out.kappa[i])
        name = STATUS_NAMES[int(out.status[i])]
        return [*out.boxes[i].tolist(), name, lo, hi if math.isfinite(hi) else ""]


def boxes_table(workspace: Any, outcome: DexterityOutcome | None) -> Any:
    """The boxes CSV: the workspace's table ``workspace``, with ``kappa_max`` its rows and
    the dexterity boxes (:class:`DexterityRows`)."""
    if outcome is None:
        return workspace
    return CsvTable((*workspace.header, *BOXES_COLUMNS), DexterityRows(workspace.rows, outcome))

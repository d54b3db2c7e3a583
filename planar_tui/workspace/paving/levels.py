"""Runner of the ``[workspace]`` job: chunked bisection, certified bracket, union areas.

Before it starts, :func:`report_estimate` puts the estimated box count in the progress
figures (``boxes_estimate``) and warns when it exceeds ``box_budget``. While it runs, the
progress carries the boxes kept so far as read-only views into the runner's arrays
(``ProgressState.partial``: ``boxes_cm`` (k, 4) rows ``x_lo, x_hi, y_lo, y_hi`` and
``status`` (k,) 2 = inside, 1 = boundary, or ``None`` in the 5-D stage, where kept boxes
may repeat and are classified at the end); in the refinement stage they are the refined
boxes only (the inside boxes of the first stage are final). No copy is made per update.

Stages (each in kernel chunks of at most ``CHUNK_BOXES`` boxes, or for the 2-D pavings
slices of about ``SLICE_TARGET_S`` (:func:`pave_in_levels`), so progress is reported and
Cancel/Ctrl-C is honoured within a fraction of a second):

1. *Paving* down to ``precision_cm`` with the chosen interval form (``natural``,
   ``mean-value``, ``slope``): ``strategy = "legwise"`` paves (x, y) boxes and decides each
   leg by its own 1-D θ search (:mod:`planar_tui.workspace.rrr.legwise`; boxes it proves are
   inside and not split), ``"joint"`` is the paper's Algorithm 1 over
   ``(x, y, θ1, θ2, θ3)``; or the 2-D bisection with the exact leg-wise test
   (``arc-distance``).
2. *Classification*: every kept (x, y) box is tested with the exact leg-wise test;
   boxes it proves (or the leg-wise paving proved) are ``inside``, the rest ``boundary``.
3. *Boundary-only refinement* (``refine_precision_cm``): boundary boxes are bisected
   again with the exact test; inside boxes are never split.

The areas are exact unions of the (x, y) projections: ``area_inside <= exact <= area_kept``.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Protocol

import numpy as np

from planar_tui.csvio import CsvTable
from planar_tui.errors import JobError
from planar_tui.jobkind import Job, option_or_key
from planar_tui.progress import Progress, read_only
from planar_tui.workspace.paving.boxes import append_rows, xy_area

if TYPE_CHECKING:
    from planar_tui.workspace.paving.geometry import GeometricArea


class BudgetSpec(Protocol):
    """What :class:`BoxBudget` reads of a workspace job's settings."""

    @property
    def box_budget(self) -> int: ...


#: Wall time one slice of a level-wise 2-D paving (:func:`pave_in_levels`) aims at.
SLICE_TARGET_S = 0.05
#: Largest slice of a level-wise 2-D paving (boxes per kernel call).
MAX_SLICE_BOXES = 1 << 16

SUMMARY_HEADER = (
    "form",
    "strategy",
    "precision_cm",
    "refine_precision_cm",
    "boxes_processed",
    "boxes_kept",
    "boxes_inside",
    "area_kept_cm2",
    "area_inside_cm2",
    "area_geometric_cm2",
    "area_geometric_error_cm2",
    "seconds",
)
BOXES_HEADER = ("x_lo_cm", "x_hi_cm", "y_lo_cm", "y_hi_cm", "status")
STATUS_NAMES = {1: "boundary", 2: "inside"}
INSIDE = 2
BOUNDARY = 1


@dataclass
class WorkspaceOutcome:
    """Everything a workspace run produced (areas in cm², boxes as rows of
    ``x_lo, x_hi, y_lo, y_hi`` with ``status`` 2 = inside, 1 = boundary)."""

    form: str
    precision_cm: float
    refine_precision_cm: float | None
    boxes: np.ndarray
    status: np.ndarray
    boxes_processed: int
    area_kept_cm2: float
    area_inside_cm2: float
    geometric: GeometricArea | None
    seconds: float
    extent_cm: tuple[float, float, float, float]
    #: ``legwise`` or ``joint`` for the interval forms, ``""`` for arc-distance and geometric.
    strategy: str = ""
    #: (x, y) boxes the leg-wise paving decided (0 otherwise); its ``boxes_processed``
    #: counts the (x, y, θ_i) boxes on which a leg's form was evaluated.
    xy_boxes: int = 0

    def summary_row(self) -> list:
        g = self.geometric
        return [
            self.form,
            self.strategy,
            self.precision_cm,
            "" if self.refine_precision_cm is None else self.refine_precision_cm,
            self.boxes_processed,
            len(self.boxes),
            int(np.count_nonzero(self.status == INSIDE)),
            self.area_kept_cm2,
            self.area_inside_cm2,
            "" if g is None else g.area_cm2,
            "" if g is None else g.error_bound_cm2,
            round(self.seconds, 6),
        ]


class BoxBudget:
    """Counts processed boxes across stages, stops at the job's budget, and reports the
    live area bracket as progress figures (``area_lower_cm2``, ``area_upper_cm2``,
    ``boxes_processed``).

    ``job`` (a workspace :class:`~planar_tui.jobkind.Job`) gives the budget and names what
    to change when it is exceeded.
    """

    def __init__(self, job: Job[BudgetSpec, object], progress: Progress):
        self.job = job
        self.progress = progress
        self.processed = 0

    def count(self, processed: int, precision_key: str = "precision_cm") -> None:
        """Add ``processed`` boxes; past the job's ``box_budget`` the job fails
        (:class:`~planar_tui.errors.JobError`, exit code 1, nothing written), naming
        ``--precision`` when the command line set the precision that ``precision_key``
        (or, unset, ``precision_cm``) gives, else the preset's ``box_budget``."""
        self.processed += processed
        budget = self.job.spec.box_budget
        if self.processed <= budget:
            return
        problem = f"the bisection exceeded {budget:,} boxes; nothing was written"
        causes = ("precision_cm",) if getattr(self.job.spec, precision_key) is None else ()
        where, key = option_or_key(self.job, precision_key, *causes)
        if where == "command line":
            raise JobError(where, key, problem, f"a coarser {key} or a larger box_budget")
        raise JobError(
            self.job.preset_path,
            f"{self.job.key}.box_budget",
            problem,
            f"a larger box_budget or a coarser {precision_key}",
        )

    def spend(self, processed: int, fraction: float, lower_cm2: float, upper_cm2: float) -> None:
        """Count ``processed`` boxes (:meth:`count`) and report the paving's progress."""
        self.count(processed)
        self.progress.advance(
            max(0.0, fraction - self.progress.completed),
            self.bracket_text(lower_cm2, upper_cm2),
            area_lower_cm2=lower_cm2,
            area_upper_cm2=upper_cm2,
            boxes_processed=float(self.processed),
        )

    def bracket_text(self, lower_cm2: float, upper_cm2: float) -> str:
        """The progress detail: boxes processed so far and the area bracket."""
        return f"{self.processed:,} boxes, area in [{lower_cm2:.5g}, {upper_cm2:.5g}] cm2"

    def finish(self, lower_cm2: float, upper_cm2: float) -> None:
        """Report the final, certified bracket as the last progress update (the last
        in-progress bracket is looser: the inside boxes are classified at the end)."""
        self.progress.advance(
            self.progress.total,
            self.bracket_text(lower_cm2, upper_cm2),
            area_lower_cm2=lower_cm2,
            area_upper_cm2=upper_cm2,
            boxes_processed=float(self.processed),
        )


def pave_in_levels(seeds, budget: BoxBudget, decide, inside_cm2: float = 0.0):
    """Drive a level-wise 2-D paving from the disjoint (x, y) boxes ``seeds`` until no box
    is left: each level (frontier) is decided in slices by ``decide(rows, start, stop,
    children, outcome)``, a parallel kernel writing per row ``start + i`` its
    :func:`~planar_tui.kernels.workspace_arc.settle_xy_box` outcome and children
    (``children[2 i]``, ``children[2 i + 1]``). Kept boxes and the halves of split ones are
    appended in frontier order, so the result is the same whatever the number of threads.
    A slice is sized to about ``SLICE_TARGET_S`` of wall time (measured as it goes, from one
    box up, halved down to one box when a slice runs long); after
    each, the budget gets the boxes decided, the fraction of the seeds' area decided and
    the live bracket ``[inside_cm2 + inside kept, kept + pending]``, and the progress the
    kept boxes so far (read-only views): progress and Cancel/Ctrl-C within a fraction of a
    second. Returns the kept boxes and their status."""
    from planar_tui.kernels.workspace_arc import SPLIT

    frontier = np.array(seeds, dtype=np.float64).reshape(-1, 4)
    root_area = xy_area(frontier)
    kept = np.zeros((4096, 4))
    status = np.zeros(4096, dtype=np.int64)
    n_kept = 0
    lower = upper = inside_cm2
    slice_boxes = 1  # grows while slices are quick: one box can take a long time
    while len(frontier):
        following = np.zeros((2 * len(frontier), 4))
        n_following = 0
        start = 0
        while start < len(frontier):
            stop = min(len(frontier), start + slice_boxes)
            n = stop - start
            children = np.empty((2 * n, 4))
            outcome = np.empty(n, dtype=np.int64)
            started = time.perf_counter()
            decide(frontier, start, stop, children, outcome)
            elapsed = time.perf_counter() - started
            if elapsed > SLICE_TARGET_S and slice_boxes > 1:
                slice_boxes //= 2
            elif elapsed < SLICE_TARGET_S / 4 and slice_boxes < MAX_SLICE_BOXES:
                slice_boxes *= 2
            keep = (outcome == BOUNDARY) | (outcome == INSIDE)
            new_rows = children[0::2][keep]
            kept, _ = append_rows(kept, n_kept, new_rows)
            status, n_kept = append_rows(status, n_kept, outcome[keep])
            lower += xy_area(new_rows[outcome[keep] == INSIDE])
            upper += xy_area(new_rows)
            split = outcome == SPLIT
            n_split = int(split.sum())
            following[n_following : n_following + 2 * n_split : 2] = children[0::2][split]
            following[n_following + 1 : n_following + 2 * n_split : 2] = children[1::2][split]
            n_following += 2 * n_split
            start = stop
            pending = xy_area(frontier[stop:]) + xy_area(following[:n_following])
            budget.progress.show_partial(
                boxes_cm=read_only(kept[:n_kept]), status=read_only(status[:n_kept])
            )
            budget.spend(n, 1.0 - pending / max(root_area, 1e-300), lower, upper + pending)
        frontier = following[:n_following]
    return kept[:n_kept], status[:n_kept]


def square_about(
    reach: tuple[float, float, float, float], precision_cm: float
) -> tuple[tuple[float, float], tuple[float, float]]:
    """The square of :func:`default_search_box` about the box ``reach``
    (``x_lo, x_hi, y_lo, y_hi``; empty when ``lo > hi``), for any mechanism."""
    xlo, xhi, ylo, yhi = reach
    if xlo > xhi or ylo > yhi:  # the legs' reach discs do not meet: any small box will do
        xlo = xhi = ylo = yhi = 0.0
    side = precision_cm
    while side < max(xhi - xlo, yhi - ylo):
        side *= 2.0
    cx, cy = 0.5 * (xlo + xhi), 0.5 * (ylo + yhi)
    return ((cx - 0.5 * side, cx + 0.5 * side), (cy - 0.5 * side, cy + 0.5 * side))


def report_boxes(estimate: int, spec, progress: Progress) -> int:
    """Put a workspace job's box ``estimate`` in ``progress.figures["boxes_estimate"]`` and
    warn (``progress.warning``) when it exceeds the job's ``box_budget``."""
    progress.figures["boxes_estimate"] = float(estimate)
    if estimate > spec.box_budget:
        progress.warn(
            f"about {estimate:,} boxes expected, more than box_budget = {spec.box_budget:,}: "
            "the run will probably stop there (a coarser precision_cm or a larger box_budget)"
        )
    return estimate


def finished_outcome(
    spec,
    boxes,
    status,
    refine,
    budget,
    geometric,
    started,
    extent,
    *,
    form,
    disjoint=False,
    **extra,
) -> WorkspaceOutcome:
    """The stages every paving ends with: with ``refine_precision_cm``, the boundary boxes
    paved again by ``refine(seeds, inside_cm2)`` (returning boxes and status); then the
    certified areas ``inside = |∪ inside boxes|``, ``kept = |∪ kept boxes|`` (plain sums
    when the boxes are ``disjoint``, as a paving's are; unions otherwise) reported to the
    budget, and the :class:`WorkspaceOutcome` (``extra``: its optional fields)."""
    from planar_tui.kernels.workspace_union import union_area

    if spec.refine_precision_cm is not None:
        budget.progress.start(1.0, "boundary refinement")
        inside = status == INSIDE
        proved = xy_area(boxes[inside]) if disjoint else float(union_area(boxes[inside]))
        refined, refined_status = refine(np.ascontiguousarray(boxes[~inside]), proved)
        boxes = np.concatenate([boxes[inside], refined])
        status = np.concatenate([status[inside], refined_status])
    boxes = np.ascontiguousarray(boxes)
    if disjoint:  # a paving (and its refinement): disjoint boxes, the union's area is the sum
        area_kept_cm2 = xy_area(boxes)
        area_inside_cm2 = xy_area(boxes[status == INSIDE])
    else:
        area_kept_cm2 = float(union_area(boxes))
        area_inside_cm2 = float(union_area(np.ascontiguousarray(boxes[status == INSIDE])))
    budget.finish(area_inside_cm2, area_kept_cm2)
    return WorkspaceOutcome(
        form=form,
        precision_cm=spec.precision_cm,
        refine_precision_cm=spec.refine_precision_cm,
        boxes=boxes,
        status=status,
        boxes_processed=budget.processed,
        area_kept_cm2=area_kept_cm2,
        area_inside_cm2=area_inside_cm2,
        geometric=geometric,
        seconds=time.perf_counter() - started,
        extent_cm=extent,
        **extra,
    )


class BoxRows(Sequence):
    """The rows ``x_lo_cm, x_hi_cm, y_lo_cm, y_hi_cm, status`` of (B, 4) boxes and their
    status codes, made only when read (a run that writes no boxes CSV never builds its
    millions of Python rows), with a vectorised finiteness test for
    :meth:`~planar_tui.csvio.CsvTable.first_non_finite_column`."""

    def __init__(self, boxes: np.ndarray, status: np.ndarray):
        self._boxes = boxes
        self._status = status

    def __len__(self) -> int:
        return len(self._boxes)

    def _rows(self, boxes: np.ndarray, status: np.ndarray) -> list[list]:
        return [
            [*box, STATUS_NAMES[code]]
            for box, code in zip(boxes.tolist(), status.tolist(), strict=True)
        ]

    def __getitem__(self, index):
        if isinstance(index, slice):
            return self._rows(self._boxes[index], self._status[index])
        one = slice(index, index + 1 or None)  # index -1: [-1:None]
        return self._rows(self._boxes[one], self._status[one])[0]

    def __iter__(self):
        for start in range(0, len(self), 65536):
            yield from self[start : start + 65536]

    def non_finite_column(self) -> int | None:
        """Index of the first column holding a NaN or an infinity, or ``None``."""
        finite = np.isfinite(self._boxes)
        return None if finite.all() else int(np.flatnonzero(~finite.all(axis=0))[0])


def boxes_table(outcome: WorkspaceOutcome) -> CsvTable:
    """The kept boxes as CSV rows ``x_lo_cm, x_hi_cm, y_lo_cm, y_hi_cm, status``
    (:class:`BoxRows`: made when read)."""
    return CsvTable(BOXES_HEADER, BoxRows(outcome.boxes, outcome.status))


def summary_line(outcome: WorkspaceOutcome) -> str:
    """One short line: form, precision, certified bracket, geometric area."""
    text = (
        f"{outcome.form} eps={outcome.precision_cm:.4g}: "
        f"[{outcome.area_inside_cm2:.5g}, {outcome.area_kept_cm2:.5g}] cm2"
    )
    if outcome.geometric is not None:
        text += f", exact {outcome.geometric.area_cm2:.5g}"
    return text

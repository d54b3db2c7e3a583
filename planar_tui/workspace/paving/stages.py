"""A parallel robot's workspace job in stages: ``pave → singularities → dexterity →
interference → accuracy → tolerance → result``, each stage a named function and :func:`run_stages`
their composition.

The core names no robot: a kind supplies its differences as :class:`Stages` (how it paves,
the summary row's head, its singularity columns, its dexterity and working mode). Every
stage after the paving appends its columns and its part of the one-line summary to the
:class:`SummaryRow`; the wall time stays the last column (the only one not reproducible).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from planar_tui.csvio import CsvTable
from planar_tui.jobkind import PreparedJob
from planar_tui.progress import Progress
from planar_tui.workspace.paving.accuracy import HEADER as ACCURACY_HEADER
from planar_tui.workspace.paving.accuracy import boxes_table as accuracy_boxes
from planar_tui.workspace.paving.accuracy import job_accuracy
from planar_tui.workspace.paving.dexterity import HEADER as DEXTERITY_HEADER
from planar_tui.workspace.paving.dexterity import boxes_table as dexterity_boxes
from planar_tui.workspace.paving.disc import HEADER as DISC_HEADER
from planar_tui.workspace.paving.disc import certified_disc, job_centre
from planar_tui.workspace.paving.interference import HEADER as INTERFERENCE_HEADER
from planar_tui.workspace.paving.interference import boxes_table as interference_boxes
from planar_tui.workspace.paving.interference import job_interference
from planar_tui.workspace.paving.result import WorkspaceResult
from planar_tui.workspace.paving.tolerance import tolerance_report

if TYPE_CHECKING:
    from planar_tui.workspace.paving.levels import BoxBudget


@dataclass
class SummaryRow:
    """The summary CSV's one row as the stages build it: ``header`` and ``cells`` before
    the wall time ``seconds``, and the one-line ``text``."""

    header: tuple[str, ...]
    cells: list
    text: str
    seconds: Any = None

    def extend(self, header: tuple[str, ...], cells: list, text: str = "") -> None:
        """Append a stage's columns and its part of the summary line."""
        self.header += tuple(header)
        self.cells += list(cells)
        self.text += text

    def table(self) -> CsvTable:
        """The summary CSV: the columns, then the wall time."""
        from planar_tui.workspace.paving.levels import SUMMARY_HEADER  # numpy

        return CsvTable((*self.header, SUMMARY_HEADER[-1]), [[*self.cells, self.seconds]])


@dataclass(frozen=True)
class Stages:
    """One kind's differences (every callable takes the job, ``PreparedJob`` ``ready``, the
    workspace outcome or its extent and the :class:`BoxBudget` as named):

    - ``pave(job, budget)``: the workspace outcome of the job (its estimate reported first
      where the kind reports one);
    - ``compute(robot, spec, budget)``: one paving at one spec, what the tolerance stage runs
      for the nominal and toleranced robots;
    - ``head(job, outcome)``: the :class:`SummaryRow` of the paving alone;
    - ``singularities(ready, outcome, budget)``: ``None`` (no singularity columns) or the
      columns' header and the certified singularities (``None`` where not asked for);
    - ``dexterity(ready, extent, budget)``: the dexterous region of a job with ``kappa_max``;
    - ``elbow(ready)``: the working mode the interference stage names (``""``: none);
    - ``result``: the job result class (a :class:`WorkspaceResult`'s fields).
    """

    pave: Callable[[Any, BoxBudget], Any]
    compute: Callable[[Any, Any, BoxBudget], Any]
    head: Callable[[Any, Any], SummaryRow]
    singularities: Callable[[Any, Any, BoxBudget], tuple[tuple[str, ...], Any] | None]
    dexterity: Callable[[Any, Any, BoxBudget], Any]
    elbow: Callable[[Any], str]
    result: type = WorkspaceResult


def singularity_stage(stages: Stages, ready: Any, outcome: Any, budget: Any, row: SummaryRow):
    """The certified singularities (``None`` where not asked for) and their columns (empty
    cells without them; none at all for a kind without singularities)."""
    found = stages.singularities(ready, outcome, budget)
    if found is None:
        return None
    header, singular = found
    cells = [""] * len(header) if singular is None else singular.columns()
    row.extend(header, cells, "" if singular is None else f"; {singular.describe()}")
    return singular


def dexterity_stage(stages: Stages, ready: Any, extent: Any, budget: Any, row: SummaryRow):
    """The dexterous region of a job with ``kappa_max`` and its columns (``None``, no
    columns, without)."""
    if ready.job.spec.kappa_max is None:
        return None
    dexterous = stages.dexterity(ready, extent, budget)
    row.extend(DEXTERITY_HEADER, dexterous.columns(), f"; {dexterous.describe()}")
    dexterous.disc = certified_disc(dexterous, extent, job_centre(ready.job.spec))
    row.extend(DISC_HEADER, dexterous.disc.columns(), dexterous.disc.describe())
    return dexterous


def interference_stage(stages: Stages, ready: Any, extent: Any, budget: Any, row: SummaryRow):
    """The interference-free region of a job with ``leg_width_cm`` and its columns
    (``None``, no columns, without)."""
    if ready.job.spec.leg_width_cm is None:
        return None
    clear = job_interference(ready.job, ready.prepared, extent, budget, stages.elbow(ready))
    row.extend(INTERFERENCE_HEADER, clear.columns(), f"; {clear.describe()}")
    return clear


def accuracy_stage(stages: Stages, ready: Any, extent: Any, budget: Any, row: SummaryRow):
    """The certified worst-case accuracy of a job with ``accuracy`` and its columns
    (``None``, no columns, without)."""
    if getattr(ready.job.spec, "accuracy", None) is None:
        return None
    errors = job_accuracy(ready.job, ready.prepared, extent, budget, stages.elbow(ready))
    row.extend(ACCURACY_HEADER, errors.columns(), f"; {errors.describe()}")
    return errors


def tolerance_stage(stages: Stages, job: Any, progress: Progress, row: SummaryRow):
    """The toleranced workspaces of a job with a tolerance
    (:func:`~planar_tui.workspace.paving.tolerance.tolerance_report`, each paving on a
    fresh budget) and their columns (``None``, no columns, without)."""
    from planar_tui.workspace.paving.levels import BoxBudget  # numpy

    report = tolerance_report(job, lambda: BoxBudget(job, progress), stages.compute)
    if report is not None:
        row.extend(report.header, report.cells, report.text)
    return report


def run_stages(stages: Stages, ready: PreparedJob[Any, Any, Any], progress: Progress) -> Any:
    """One workspace job: ``pave → singularities → dexterity → interference → accuracy →
    tolerance``, then the kind's result (``stages.result``: the summary CSV, the boxes CSV
    with the dexterity, interference and accuracy boxes, the outcomes the map and figure
    draw)."""
    from planar_tui.workspace.paving.levels import BoxBudget, boxes_table  # numpy

    job = ready.job
    budget = BoxBudget(job, progress)
    outcome = stages.pave(job, budget)
    row = stages.head(job, outcome)
    singular = singularity_stage(stages, ready, outcome, budget, row)
    dexterous = dexterity_stage(stages, ready, outcome.extent_cm, budget, row)
    clear = interference_stage(stages, ready, outcome.extent_cm, budget, row)
    errors = accuracy_stage(stages, ready, outcome.extent_cm, budget, row)
    report = tolerance_stage(stages, job, progress, row)
    boxes = interference_boxes(dexterity_boxes(boxes_table(outcome), dexterous), clear)
    boxes = accuracy_boxes(boxes, errors)
    return stages.result(
        table=row.table(),
        summary=row.text,
        extra_tables={"boxes": boxes},
        outcome=outcome,
        singularity=singular,
        dexterity=dexterous,
        interference=clear,
        accuracy=errors,
        companions=None if report is None else report.companions,
    )


__all__ = ["Stages", "SummaryRow", "run_stages"]

"""The result of a workspace job of any kind and its terminal view: the typed result
(boxes, certified bracket, singular boxes, tolerance companions), the map's title and
content, a sweep row's figures, and the command-line options every workspace kind has."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Protocol

from planar_tui.jobkind import Job, JobResult, Option, OutputOption
from planar_tui.workspace.paving.orientation import describe
from planar_tui.workspace.paving.tolerance import describe as describe_tolerance
from planar_tui.workspace.paving.tolerance import map_layers, tolerance_of

if TYPE_CHECKING:
    from planar_tui.workspace.paving.accuracy import AccuracyOutcome
    from planar_tui.workspace.paving.dexterity import DexterityOutcome
    from planar_tui.workspace.paving.interference import InterferenceOutcome
    from planar_tui.workspace.paving.levels import WorkspaceOutcome


class SingularOverlay(Protocol):
    """What the map draws of a kind's singularity outcome: the kept singular boxes and
    the certified circle (its centre ``None`` when a kind certifies none)."""

    @property
    def singular_boxes(self) -> Any: ...

    @property
    def centre_cm(self) -> tuple[float, float] | None: ...

    @property
    def radius_lo_cm(self) -> float: ...

    def describe(self) -> str: ...


@dataclass(frozen=True, kw_only=True)
class WorkspaceResult(JobResult):
    """The workspace's boxes, certified area bracket and geometric reference
    (:class:`~planar_tui.workspace.paving.levels.WorkspaceOutcome`); the kept boxes are also
    ``extra_tables["boxes"]``."""

    outcome: WorkspaceOutcome
    #: The robot's singularity outcome, with ``singularities``.
    singularity: SingularOverlay | None = None
    #: With a tolerance: the nominal and the other mode's outcomes (map and figure).
    companions: dict[str, WorkspaceOutcome] | None = None
    #: The certified dexterous region, with ``kappa_max``.
    dexterity: DexterityOutcome | None = None
    #: The certified interference-free region, with ``leg_width_cm``.
    interference: InterferenceOutcome | None = None
    #: The certified worst-case accuracy, with ``accuracy``.
    accuracy: AccuracyOutcome | None = None


def map_title(job: Job[Any, Any], outcome: WorkspaceOutcome) -> str:
    """What a map shows: ``paper-b-table3:workspace[4]: mean-value, ε = 0.1172 cm`` (and
    the refinement precision), as run, overrides included."""
    title = f"{job.label}: {outcome.form}, ε = {outcome.precision_cm:.4g} cm"
    if isinstance(getattr(job.spec, "orientation_deg", None), tuple):  # a five-bar has none
        title += f", {describe(job.spec)}"
    if outcome.refine_precision_cm is not None:
        title += f", boundary refined to {outcome.refine_precision_cm:.4g} cm"
    tolerance = tolerance_of(job.spec)
    if tolerance is not None:
        title += f", {describe_tolerance(tolerance)}"
    return title


def render_workspace(job: Job[Any, Any], result: WorkspaceResult, console: Any) -> None:
    """Print the titled map of a finished workspace job (CLI view), fitted to the console
    width; a job without boxes (the geometric form) prints its summary under the title."""
    from planar_tui.workspace.paving.map import render_map

    outcome = result.outcome
    if outcome is not None:
        console.print(map_title(job, outcome), markup=False, highlight=False)
    if outcome is None or len(outcome.boxes) == 0:
        console.print(result.summary, markup=False)
        return
    width = min(console.width or 80, 120)
    singular = result.singularity
    if singular is not None:
        console.print(singular.describe(), markup=False, highlight=False)
    boxes, status, drawn = map_content(job, result)
    lines = render_map(boxes, status, width=width, **drawn)
    dexterous = getattr(result, "dexterity", None)
    if dexterous is not None:  # its region (proved, boundary) and its κ map below
        from planar_tui.workspace.paving.kappa_map import render_kappa_map

        lines += [dexterous.describe(), *render_map(dexterous.boxes, dexterous.status, width=width)]
        lines += render_kappa_map(dexterous, width)
    clear = getattr(result, "interference", None)
    if clear is not None:  # its region: proved interference-free, boundary
        lines += [clear.describe(), *render_map(clear.boxes, clear.status, width=width)]
    errors = getattr(result, "accuracy", None)
    if errors is not None:  # its boxes (certified, not) and its error map below
        from planar_tui.workspace.paving.accuracy import render_error_map

        lines += [errors.describe(), *render_map(errors.boxes, errors.status, width=width)]
        lines += render_error_map(errors, width)
    for line in lines:
        console.print(line, markup=False, highlight=False, crop=True, soft_wrap=False)


def point_figures(job: Job[Any, Any], result: WorkspaceResult) -> dict[str, Any]:
    """A sweep row's figures: the summary CSV's columns but its ``seconds`` (the sweep row
    has its own timing)."""
    header, (row,) = result.table.header, result.table.rows
    return {name: value for name, value in zip(header, row, strict=True) if name != "seconds"}


def map_content(job: Job[Any, Any], result: Any) -> tuple[Any, Any, dict[str, Any]]:
    """What the map of a finished workspace job (any parallel kind) shows: its boxes, their
    status and the ``render_map`` keywords: the singular boxes and the circle
    (:func:`overlays`) and, for a tolerance-certified job, the robust workspace's boxes
    with the nominal and "some" workspaces as ``layers``
    (:func:`planar_tui.workspace.paving.tolerance.map_layers`). The CLI's map and the app's
    workspace tabs draw the same."""
    outcome = result.outcome
    drawn = overlays(getattr(result, "singularity", None))
    companions = getattr(result, "companions", None)
    if not companions:
        return outcome.boxes, outcome.status, drawn
    boxes, status, layers = map_layers(outcome, companions, job.spec.tolerance_mode or "all")
    return boxes, status, {**drawn, "layers": layers}


def overlays(singular: SingularOverlay | None) -> dict[str, Any]:
    """``render_map`` keywords drawing the singular boxes and the circle (none without)."""
    if singular is None:
        return {}
    drawn: dict[str, Any] = {"singular": singular.singular_boxes}
    if singular.centre_cm is not None:  # a five-bar's singularities may come without one
        drawn["circle"] = (*singular.centre_cm, singular.radius_lo_cm)
    return drawn


#: The workspace kinds' command-line option, boxes output and map view.
PRECISION_OPTION = Option(
    "--precision", "precision_cm", "Precision epsilon in cm; overrides `precision_cm`.", float
)


BOXES_OPTION = OutputOption(
    "--boxes", "boxes", "CSV of the kept boxes (with several jobs: FILE-1.csv ...)."
)


MAP_VIEW = ("--map/--no-map", "Print the character-cell map.")


def extra_outputs(job: Job[Any, Any]) -> dict[str, str]:
    """The boxes CSV the preset names (``boxes_output``), if any."""
    return {"boxes": job.spec.boxes_output} if job.spec.boxes_output else {}

"""The ``[[workspace5r]]`` job: the certified workspace of a five-bar (``[robot5r]``,
:mod:`planar_tui.workspace.fivebar.robot`), its type I and II singularities and the largest
singularity-free circle (:mod:`planar_tui.workspace.fivebar.singularity`).

The paving is the 3-RRR's (:func:`planar_tui.workspace.paving.levels.pave_in_levels`) with the
five-bar's exact leg-wise test (:mod:`planar_tui.kernels.workspace5r`): boxes proved inside
are never split, boundary boxes are halved down to ``precision_cm`` (and again down to
``refine_precision_cm``); ``area_inside <= exact <= area_kept``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

from planar_tui.jobkind import (
    Command,
    JobKind,
    JobResult,
    PreparedJob,
    Tab,
)
from planar_tui.progress import Progress
from planar_tui.schema import (
    TableReader,
    boolean,
    number,
    plot_setting,
    setting,
    string,
)
from planar_tui.workspace.fivebar.mechanism import MECHANISM
from planar_tui.workspace.fivebar.robot import Robot5R
from planar_tui.workspace.fivebar.singularity import HEADER, centre_problem, compute_singularities
from planar_tui.workspace.fivebar.tolerance import (
    TOLERANCE_FIELDS_5R,
    TOLERANCE_KEYS_5R,
    check_search_box,
)
from planar_tui.workspace.paving.accuracy import accuracy_names, accuracy_setting, check_accuracy
from planar_tui.workspace.paving.circle import read_centre, refuse_without_singularities
from planar_tui.workspace.paving.columns import tolerance_names
from planar_tui.workspace.paving.dexterity import (
    check_dexterity,
    compute_dexterity,
    dexterity_names,
    kappa_setting,
)
from planar_tui.workspace.paving.estimate import check_needs, estimate, report_box_estimate
from planar_tui.workspace.paving.interference import (
    check_interference,
    interference_names,
    width_setting,
)
from planar_tui.workspace.paving.mechanism import Mechanism
from planar_tui.workspace.paving.result import (
    BOXES_OPTION,
    MAP_VIEW,
    PRECISION_OPTION,
    extra_outputs,
    point_figures,
    render_workspace,
)
from planar_tui.workspace.paving.runner import compute_workspace
from planar_tui.workspace.paving.settings import (
    boxes_setting,
    budget_setting,
    check_paving,
    reference_setting,
    refine_setting,
    search_box_setting,
    singularity_precision_setting,
)
from planar_tui.workspace.paving.stages import Stages, SummaryRow, run_stages
from planar_tui.workspace.paving.tolerance import (
    check_tolerance,
    refuse_reference,
)

if TYPE_CHECKING:
    from planar_tui.workspace.fivebar.singularity import FiveBarSingularities
    from planar_tui.workspace.paving.accuracy import AccuracyOutcome
    from planar_tui.workspace.paving.dexterity import DexterityOutcome
    from planar_tui.workspace.paving.interference import InterferenceOutcome
    from planar_tui.workspace.paving.levels import BoxBudget, WorkspaceOutcome

#: The forms: the exact leg-wise paving, or the exact area only.
FORMS = ("arc-distance", "geometric")


def _search_box(reader: TableReader, name, default, robot: Robot5R, values):
    """An (x, y) box in cm that contains both legs' reach."""
    if not reader.has(name):
        return None
    rows = reader.number_rows(name, columns=2, row_doc="[min, max] in cm")
    rxlo, rxhi, rylo, ryhi = robot.reach_box_cm()
    expected = f"[[x_min, x_max], [y_min, y_max]] containing x in [{rxlo:.4g}, {rxhi:.4g}], "
    expected += f"y in [{rylo:.4g}, {ryhi:.4g}] cm"
    if len(rows) != 2 or any(not lo < hi for lo, hi in rows):
        raise reader.error(name, f"is {[list(r) for r in rows]}", expected)
    (xlo, xhi), (ylo, yhi) = rows
    if rxlo <= rxhi and not (xlo <= rxlo and rxhi <= xhi and ylo <= rylo and ryhi <= yhi):
        raise reader.error(name, "cannot contain the robot's reach", expected)
    return rows


@dataclass(frozen=True, kw_only=True)
class FiveBarSpec:
    """Settings of one five-bar workspace computation (lengths in cm)."""

    precision_cm: float = setting(
        number(positive=True), type_doc="number > 0", doc="paving precision ε"
    )
    form: str = setting(
        string(choices=FORMS),
        default="arc-distance",
        type_doc=", ".join(f"`{f}`" for f in FORMS),
        doc="the exact leg-wise paving, or the exact (shapely) area only",
    )
    refine_precision_cm: float | None = refine_setting()
    search_box_cm: tuple[tuple[float, float], tuple[float, float]] | None = search_box_setting(
        _search_box
    )
    box_budget: int = budget_setting(
        "most (x, y) boxes one job may decide (then it fails, writing nothing); the default "
        "is lowered to fit the memory limit"
    )
    geometric_reference: bool = reference_setting()
    boxes_output: str | None = boxes_setting()
    singularities: bool = setting(
        boolean(),
        default=False,
        type_doc="boolean",
        doc="also pave the type I (serial) and type II (parallel) singularities",
    )
    singularity_precision_cm: float | None = singularity_precision_setting()
    singularity_free_circle: tuple[float, float] | None = setting(
        read_centre,
        default=None,
        type_doc="`[x, y]`",
        default_doc="(no circle)",
        doc="centre of the largest singularity-free circle to certify (needs "
        "`singularities = true` and a working mode), and of the dexterous disc (with kappa_max)",
    )
    kappa_max: float | None = kappa_setting()
    leg_width_cm: float | None = width_setting()
    accuracy: tuple[tuple[str, float], ...] | None = accuracy_setting()
    tolerance_cm: float | None = TOLERANCE_FIELDS_5R[0]
    tolerances_cm: tuple[tuple[str, float], ...] | None = TOLERANCE_FIELDS_5R[1]
    tolerance_mode: str | None = TOLERANCE_FIELDS_5R[2]
    plot: str | None = plot_setting()

    #: The robot's toleranced quantities (:mod:`planar_tui.workspace.fivebar.tolerance`).
    tolerance_keys: ClassVar[tuple[str, ...]] = TOLERANCE_KEYS_5R
    #: The robot's separator (its reach box and polygon for the estimate).
    mechanism: ClassVar[Mechanism] = MECHANISM

    @staticmethod
    def check(values: dict[str, Any], reader: TableReader, robot: Robot5R) -> dict[str, Any]:
        """The refinement is at most the precision; the circle goes with ``singularities``
        and a working mode; a tolerance (:mod:`planar_tui.workspace.fivebar.tolerance`) is
        below the shortest link and takes the paving form, no singularities and no
        geometric reference; a "some" job's search box holds the reach grown by the
        tolerances."""
        lengths = {"proximal_cm": min(robot.proximal_cm), "distal_cm": min(robot.distal_cm)}
        check_tolerance(values, reader, TOLERANCE_KEYS_5R, lengths)
        refuse_reference(values, reader)
        if values["search_box_cm"] is not None and values["tolerance_mode"] == "some":
            check_search_box(values, reader, robot)
        if not values["singularities"]:
            centre = () if values["kappa_max"] is not None else ("singularity_free_circle",)
            refuse_without_singularities(values, reader, (*centre, "singularity_precision_cm"))
        elif values["singularity_free_circle"] is not None and robot.working_mode == "any":
            raise reader.error(
                "singularity_free_circle",
                "needs a working mode (the robot's working_mode is any)",
                'working_mode = "++", "+-", "-+" or "--" in [robot5r]',
            )
        elif values["singularity_free_circle"] is not None:
            problem = centre_problem(robot, values["singularity_free_circle"])
            if problem is not None:
                raise reader.error(
                    "singularity_free_circle",
                    problem,
                    "a centre inside the workspace, off its singularities",
                )
        check_dexterity(values, reader, tolerances=True)
        check_interference(values, reader)
        check_accuracy(values, reader, MECHANISM.accuracy_unit)
        for key in ("kappa_max", "leg_width_cm", "accuracy"):
            if values[key] is not None and robot.working_mode == "any":
                raise reader.error(
                    key,
                    "needs a working mode (the robot's working_mode is any)",
                    'working_mode = "++", "+-", "-+" or "--" in [robot5r]',
                )
        values = check_paving(values, reader)
        check_needs("workspace5r", FiveBarSpec(**values), reader, robot)  # memory and time
        return values


@dataclass(frozen=True, kw_only=True)
class FiveBarResult(JobResult):
    """The workspace's boxes and certified bracket, and the singularities (or ``None``)."""

    outcome: WorkspaceOutcome
    singularity: FiveBarSingularities | None = None
    #: With a tolerance: the nominal and the other mode's outcomes (map and figure).
    companions: dict[str, WorkspaceOutcome] | None = None
    #: The certified dexterous region, with ``kappa_max``.
    dexterity: DexterityOutcome | None = None
    #: The certified interference-free region, with ``leg_width_cm``.
    interference: InterferenceOutcome | None = None
    #: The certified worst-case accuracy, with ``accuracy``.
    accuracy: AccuracyOutcome | None = None


def compute_fivebar(robot: Robot5R, spec: FiveBarSpec, budget: BoxBudget) -> WorkspaceOutcome:
    """Pave the search box with the five-bar's exact test (module docstring):
    :func:`~planar_tui.workspace.paving.runner.compute_workspace` with its Mechanism."""
    return compute_workspace(MECHANISM, robot, spec, budget, label="five-bar paving")


def pave_fivebar(job: Any, budget: BoxBudget) -> WorkspaceOutcome:
    """The pave stage: the box estimate reported (warned of over the box budget), then
    :func:`compute_fivebar`."""
    report_box_estimate(job, budget.progress)
    return compute_fivebar(job.robot, job.spec, budget)


def fivebar_head(job: Any, outcome: WorkspaceOutcome) -> SummaryRow:
    """The summary row of the paving: the 3-RRR's columns, the working mode in place of the
    strategy."""
    from planar_tui.workspace.paving.levels import SUMMARY_HEADER, summary_line

    base, mode = outcome.summary_row(), job.robot.working_mode
    header = (SUMMARY_HEADER[0], "working_mode", *SUMMARY_HEADER[2:-1])
    summary = f"{summary_line(outcome)}, working mode {mode}"
    return SummaryRow(header, [base[0], mode, *base[2:-1]], summary, base[-1])


def fivebar_singularities(ready: Any, outcome: WorkspaceOutcome, budget: BoxBudget) -> Any:
    """The type I and II singularities' columns, computed with ``singularities``."""
    if not ready.job.spec.singularities:
        return HEADER, None
    return HEADER, compute_singularities(ready.job, outcome.extent_cm, budget)


def fivebar_elbow(ready: Any) -> str:
    """The robot's working mode, ``1 -1``."""
    return " ".join(str(s) for s in ready.job.robot.elbows)


def fivebar_dexterity(ready: Any, extent: Any, budget: BoxBudget) -> Any:
    """The dexterous region of a job with ``kappa_max`` (no characteristic length)."""
    spec = ready.job.spec
    evaluate = MECHANISM.dexterity(ready.job, None)
    elbow = fivebar_elbow(ready)
    return compute_dexterity(
        evaluate, extent, spec.precision_cm, spec.kappa_max, None, elbow, budget
    )


#: The stages of a five-bar job (:func:`~planar_tui.workspace.paving.stages.run_stages`).
STAGES = Stages(
    pave=pave_fivebar,
    compute=compute_fivebar,
    head=fivebar_head,
    singularities=fivebar_singularities,
    dexterity=fivebar_dexterity,
    elbow=fivebar_elbow,
    result=FiveBarResult,
)


def run_fivebar(
    ready: PreparedJob[FiveBarSpec, Robot5R, object], progress: Progress
) -> FiveBarResult:
    """Compute one ``[[workspace5r]]`` job (:data:`STAGES`)."""
    return run_stages(STAGES, ready, progress)


def fivebar_figure_names(job: Any) -> tuple[str, ...]:
    """The columns of a five-bar job (:func:`planar_tui.workspace.fivebar.job.run_fivebar`)."""
    from planar_tui.workspace.paving.levels import SUMMARY_HEADER

    return (
        SUMMARY_HEADER[0],
        "working_mode",
        *SUMMARY_HEADER[2:-1],
        *HEADER,
        *dexterity_names(job),
        *interference_names(job),
        *accuracy_names(job),
        *tolerance_names(job),
    )


JOB_KIND = JobKind(
    name="workspace5r",
    robot_kind="robot5r",
    settings=FiveBarSpec,
    run=run_fivebar,
    summary="five-bar (2-DOF) workspace by certified paving, with its type I and II "
    "singularities and singularity-free circle",
    render=render_workspace,
    extra_outputs=extra_outputs,
    point_figures=point_figures,
    estimate=estimate,
    figure_names=fivebar_figure_names,
    command=Command(
        "workspace5r",
        "Five-bar workspace of every workspace5r job: summary CSV, boxes CSV (--boxes or the "
        "preset's boxes_output) and a map.",
        options=(PRECISION_OPTION,),
        outputs=(BOXES_OPTION,),
        view=MAP_VIEW,
    ),
    tab=Tab("5-bar", 8, "planar_tui.app.widgets.parallel_panes:FiveBarPane"),
    figure="planar_tui.figures.certified:from_fivebar_result",
    warmup=(
        "[[workspace5r]]\nprecision_cm = 8.0\n"
        "geometric_reference = false\nrefine_precision_cm = 4.0\nsingularities = true\n"
        "singularity_free_circle = [0, 60]\n"
        "[[workspace5r]]\nprecision_cm = 8.0\ngeometric_reference = false\ntolerance_cm = 0.1\n"
    ),
)

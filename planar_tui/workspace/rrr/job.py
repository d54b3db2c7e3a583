"""The ``[workspace]`` job: the workspace of a 3-RRR (paper B) at one orientation or over a
range of them (:mod:`planar_tui.workspace.paving.orientation`).

Settings (the preset keys), command-line overrides, the runner, the typed result and the
terminal view (the character-cell map) of one job kind; the computation itself is
:mod:`planar_tui.workspace.paving.levels`.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, ClassVar

from planar_tui.jobkind import (
    Command,
    Job,
    JobKind,
    Option,
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
from planar_tui.workspace.paving.accuracy import accuracy_setting, check_accuracy
from planar_tui.workspace.paving.circle import HEADER as CIRCLE_HEADER
from planar_tui.workspace.paving.dexterity import (
    check_dexterity,
    compute_dexterity,
    kappa_setting,
    length_setting,
)
from planar_tui.workspace.paving.estimate import BUDGET_FACTOR, budget_problem, count_text
from planar_tui.workspace.paving.interference import check_interference, width_setting
from planar_tui.workspace.paving.mechanism import Mechanism
from planar_tui.workspace.paving.orientation import (
    ORIENTATION_HEADER,
    check_orientation,
    orientation_columns,
    summary_text,
)
from planar_tui.workspace.paving.result import (
    BOXES_OPTION,
    MAP_VIEW,
    PRECISION_OPTION,
    WorkspaceResult,
    extra_outputs,
    point_figures,
    render_workspace,
)
from planar_tui.workspace.paving.settings import (
    boxes_setting,
    budget_setting,
    centre_setting,
    check_paving,
    constructor_default,
    modes_setting,
    orientation_mode_setting,
    orientation_setting,
    precision_setting,
    reference_setting,
    refine_setting,
    search_box_setting,
    singularities_setting,
    singularity_precision_setting,
)
from planar_tui.workspace.paving.stages import Stages, SummaryRow, run_stages
from planar_tui.workspace.paving.tolerance import check_tolerance, tolerance_fields
from planar_tui.workspace.rrr.dexterity import length_cm
from planar_tui.workspace.rrr.forms import FORMS
from planar_tui.workspace.rrr.mechanism import MECHANISM
from planar_tui.workspace.rrr.orientation import (
    compute_orientation_workspace,
    default_form,
    reach_box_for,
)
from planar_tui.workspace.rrr.robot import TOLERANCE_KEYS_3RRR, Robot3RRR
from planar_tui.workspace.rrr.singularity import (
    MODED_KEYS,
    Circle,
    check_singularity,
    compute_singularities,
    resolve_circle,
)

#: How the interval forms pave: per (x, y) box a 1-D θ search per leg, or the paper's
#: bisection of (x, y, θ1, θ2, θ3) boxes.
STRATEGIES = ("legwise", "joint")


def _joint_limits(reader: TableReader, name, default, robot, values):
    """Three ``[min, max]`` rows in degrees, each non-empty and at most 360° wide."""
    rows = reader.number_rows("joint_limits_deg", columns=2, row_doc="[min, max] in degrees")
    if len(rows) != 3:
        raise reader.error("joint_limits_deg", f"has {len(rows)} rows", "3 rows [min, max]")
    for leg, (lo, hi) in enumerate(rows, start=1):
        if not lo < hi:
            raise reader.error(
                "joint_limits_deg",
                f"leg {leg} range [{lo:g}, {hi:g}] is empty or reversed",
                "min < max",
            )
        if hi - lo > 360.0:
            raise reader.error(
                "joint_limits_deg", f"leg {leg} range spans {hi - lo:g} deg", "at most 360 deg"
            )
    return rows


def _search_box(reader: TableReader, name, default, robot: Robot3RRR, values):
    """An (x, y) box in cm that contains the robot's reach at the job's orientation."""
    if not reader.has("search_box_cm"):
        return None
    rows = reader.number_rows("search_box_cm", columns=2, row_doc="[min, max] in cm")
    if len(rows) != 2 or any(not lo < hi for lo, hi in rows):
        raise reader.error(
            "search_box_cm", f"is {[list(r) for r in rows]}", "[[x_min, x_max], [y_min, y_max]]"
        )
    (xlo, xhi), (ylo, yhi) = rows
    rxlo, rxhi, rylo, ryhi = reach_box_for(robot, values["orientation_deg"])
    if (
        rxlo <= rxhi
        and rylo <= ryhi
        and not (xlo <= rxlo and rxhi <= xhi and ylo <= rylo and ryhi <= yhi)
    ):
        raise reader.error(
            "search_box_cm",
            "cannot contain the robot's reach "
            f"x in [{rxlo:.4g}, {rxhi:.4g}], y in [{rylo:.4g}, {ryhi:.4g}] cm",
            "a box containing it",
        )
    return rows


@dataclass(frozen=True, kw_only=True)
class WorkspaceSpec:
    """Settings of one workspace computation (angles in degrees, lengths in cm)."""

    joint_limits_deg: tuple[tuple[float, float], ...] = setting(
        _joint_limits, type_doc="3 rows `[min, max]`", doc="active-joint limits θ1, θ2, θ3"
    )
    orientation_deg: float | tuple[float, float] = orientation_setting()
    orientation_mode: str | None = orientation_mode_setting()
    precision_cm: float = precision_setting()
    form: str = constructor_default(
        "mean-value",  # a spec built in code; a preset's default depends on orientation_deg
        string(choices=FORMS),
        default=default_form,
        default_doc='`"mean-value"` (`"arc-distance"` with a range of φ)',
        type_doc=", ".join(f"`{f}`" for f in FORMS),
        doc="interval form of the inclusion test (`geometric`: the exact area only)",
    )
    strategy: str = setting(
        string(choices=STRATEGIES),
        default="legwise",
        type_doc=", ".join(f"`{s}`" for s in STRATEGIES),
        doc="natural, mean-value, slope: pave (x, y) deciding each leg by its own θ search "
        "(`legwise`), or bisect (x, y, θ1, θ2, θ3) boxes as paper B (`joint`)",
    )
    search_box_cm: tuple[tuple[float, float], tuple[float, float]] | None = search_box_setting(
        _search_box
    )
    angle_scale: float = setting(
        number(positive=True),
        default=10.0,
        type_doc="number > 0",
        doc="cm per radian comparing angle and position widths (joint: the bisected "
        "variable; legwise: θ pieces down to the box width / k)",
    )
    expanded: bool = setting(
        boolean(),
        default=False,
        type_doc="boolean",
        doc="natural form only: the paper's expanded eqs. 22-23 (paper layout)",
    )
    refine_precision_cm: float | None = refine_setting()
    box_budget: int = budget_setting(
        "most boxes one job may process (legwise: (x, y, θ_i) boxes a leg's form is "
        "evaluated on; then it fails, writing nothing); the default is lowered to fit the "
        "memory limit"
    )
    geometric_reference: bool = reference_setting()
    boxes_output: str | None = boxes_setting()
    singularities: bool = singularities_setting()
    elbow: tuple[int, int, int] | None = modes_setting()
    circle_centre_cm: tuple[float, float] | None = centre_setting()
    singularity_precision_cm: float | None = singularity_precision_setting()
    kappa_max: float | None = kappa_setting()
    characteristic_length_cm: float | None = length_setting()
    leg_width_cm: float | None = width_setting()
    accuracy: tuple[tuple[str, float], ...] | None = accuracy_setting()
    tolerance_cm: float | None
    tolerances_cm: tuple[tuple[str, float], ...] | None
    tolerance_mode: str | None
    tolerance_cm, tolerances_cm, tolerance_mode = tolerance_fields(TOLERANCE_KEYS_3RRR)
    plot: str | None = plot_setting()

    #: The robot's toleranced quantities (:mod:`planar_tui.workspace.paving.tolerance`).
    tolerance_keys: ClassVar[tuple[str, ...]] = TOLERANCE_KEYS_3RRR
    #: The robot's separator (:mod:`planar_tui.workspace.rrr.mechanism`).
    mechanism: ClassVar[Mechanism] = MECHANISM

    @staticmethod
    def check(values: dict[str, Any], reader: TableReader, robot: Robot3RRR) -> dict[str, Any]:
        """The expanded form needs the natural form and the paper's layout; the refinement
        precision cannot exceed the precision."""
        check_orientation(values, reader)
        check_singularity(values, reader)
        check_dexterity(values, reader, tolerances=True)
        check_interference(values, reader)
        check_accuracy(values, reader, MECHANISM.accuracy_unit)
        lengths = {"proximal_cm": robot.proximal_cm, "distal_cm": robot.distal_cm}
        check_tolerance(values, reader, TOLERANCE_KEYS_3RRR, lengths)
        form = values["form"]
        if values["expanded"] and form != "natural":
            raise reader.error("expanded", f"is true with form = {form!r}", 'form = "natural"')
        if values["expanded"] and not robot.paper_layout:
            raise reader.error(
                "expanded", "needs the paper's layout", "no base_joints_cm / platform_points_cm"
            )
        values = check_paving(values, reader)
        check_budget(WorkspaceSpec(**values), reader, robot)
        return values

    @property
    def limits_rad(self) -> tuple[tuple[float, float], ...]:
        """Joint limits in radians."""
        return tuple((math.radians(lo), math.radians(hi)) for lo, hi in self.joint_limits_deg)

    @property
    def orientation_rad(self) -> float:
        """Platform orientation :math:`\\varphi` in radians (a single orientation only)."""
        if isinstance(self.orientation_deg, tuple):
            raise ValueError("orientation_deg is a range: no single orientation")
        return math.radians(self.orientation_deg)


def check_budget(spec: WorkspaceSpec, reader: TableReader, robot: Robot3RRR) -> None:
    """Refuse a job whose box estimate
    (:func:`~planar_tui.workspace.rrr.compute.estimate_boxes`) exceeds
    :data:`~planar_tui.workspace.paving.estimate.BUDGET_FACTOR` × ``box_budget``: it would
    only stop at its budget, minutes later. Single orientations only (a range of
    orientations is not estimated); one line on ``precision_cm`` (or ``--precision``)."""
    from planar_tui.workspace.rrr.compute import estimate_boxes

    if isinstance(spec.orientation_deg, tuple):
        return
    boxes = estimate_boxes(robot, spec)
    problem = budget_problem(boxes, spec)
    if problem is not None:
        found = f"is {spec.precision_cm:g} cm: about {count_text(boxes)} boxes, {problem}"
        least = count_text(-(-boxes // BUDGET_FACTOR))
        raise reader.error("precision_cm", found, f"a coarser one or box_budget ≥ {least}")


def override_consequences(table: dict[str, Any], given: Mapping[str, Any]) -> dict[str, Any]:
    """The keys that follow a command-line override (the kind's ``overrides`` hook, before
    the table is read again, :func:`planar_tui.batch.override_job`): a form other than
    ``natural`` turns ``expanded`` off; a precision caps the refinement precision."""
    form, precision = given.get("form"), given.get("precision_cm")
    if form is not None and form != "natural":
        table["expanded"] = False
    refine = table.get("refine_precision_cm")
    numbers = (int, float)
    if isinstance(precision, numbers) and isinstance(refine, numbers) and refine > precision:
        table["refine_precision_cm"] = precision
    return table


WorkspaceJob = Job[WorkspaceSpec, Robot3RRR]


@dataclass(frozen=True)
class WorkspacePrepared:
    """What :func:`prepare_workspace` resolves: the singularity-free circle's centre and
    working mode (``None`` without ``singularities`` or a key of ``MODED_KEYS``)."""

    circle: Circle | None


def prepare_workspace(job: WorkspaceJob) -> WorkspacePrepared:
    """Resolve the circle of a job with ``singularities`` or a key of ``MODED_KEYS``
    (its working mode: :func:`resolve_circle`), refusing an unreachable or singular centre
    (:class:`PresetError`, exit code 2)."""
    spec = job.spec
    ranged = isinstance(spec.orientation_deg, tuple)  # its mode is the given elbow
    if ranged or (not spec.singularities and all(getattr(spec, k) is None for k in MODED_KEYS)):
        return WorkspacePrepared(None)
    return WorkspacePrepared(resolve_circle(job))


def rrr_dexterity(ready: PreparedJob[WorkspaceSpec, Robot3RRR, WorkspacePrepared], extent, budget):
    """The dexterous region of a job with ``kappa_max``
    (:func:`~planar_tui.workspace.paving.dexterity.compute_dexterity`) in the prepared mode."""
    job = ready.job
    spec, elbow = job.spec, rrr_elbow(ready)
    evaluate = MECHANISM.dexterity(job, ready.prepared)
    length = length_cm(job.robot, spec)
    assert spec.kappa_max is not None
    return compute_dexterity(
        evaluate, extent, spec.precision_cm, spec.kappa_max, length, elbow, budget
    )


def pave_rrr(job: WorkspaceJob, budget: Any) -> Any:
    """The pave stage: one orientation (:func:`~planar_tui.workspace.rrr.compute.compute_workspace`)
    or a range of them."""
    from planar_tui.workspace.rrr.compute import compute_workspace

    if isinstance(job.spec.orientation_deg, tuple):
        return compute_orientation_workspace(job.robot, job.spec, budget)
    return compute_workspace(job.robot, job.spec, budget)


def compute_rrr(robot: Robot3RRR, spec: WorkspaceSpec, budget: Any) -> Any:
    """One paving at one orientation, what the tolerance stage runs."""
    from planar_tui.workspace.rrr.compute import compute_workspace

    return compute_workspace(robot, spec, budget)


def rrr_head(job: WorkspaceJob, outcome: Any) -> SummaryRow:
    """The summary row of the paving: its columns with the orientation's, the one-line
    summary (a range's own line)."""
    from planar_tui.workspace.paving.levels import SUMMARY_HEADER, summary_line

    base, spec = outcome.summary_row(), job.spec
    ranged = isinstance(spec.orientation_deg, tuple)
    summary = summary_text(spec, outcome) if ranged else summary_line(outcome)
    header = (*SUMMARY_HEADER[:-1], *ORIENTATION_HEADER)
    return SummaryRow(header, [*base[:-1], *orientation_columns(spec)], summary, base[-1])


def rrr_singularities(ready: Any, outcome: Any, budget: Any) -> tuple[tuple[str, ...], Any]:
    """The circle's columns, computed with ``singularities`` at one orientation."""
    job, circle = ready.job, ready.prepared.circle
    if circle is None or not job.spec.singularities or isinstance(job.spec.orientation_deg, tuple):
        return CIRCLE_HEADER, None
    return CIRCLE_HEADER, compute_singularities(job, circle, outcome.extent_cm, budget)


def rrr_elbow(ready: Any) -> str:
    """The prepared working mode (a range's given ``elbow``), ``1 -1 1``."""
    circle = ready.prepared.circle
    mode = ready.job.spec.elbow if circle is None else circle.elbow
    assert mode is not None  # prepared with the mode, or given with a range
    return " ".join(str(s) for s in mode)


#: The stages of a ``[workspace]`` job (:func:`~planar_tui.workspace.paving.stages.run_stages`).
STAGES = Stages(
    pave=pave_rrr,
    compute=compute_rrr,
    head=rrr_head,
    singularities=rrr_singularities,
    dexterity=rrr_dexterity,
    elbow=rrr_elbow,
)


def run_workspace(
    ready: PreparedJob[WorkspaceSpec, Robot3RRR, WorkspacePrepared], progress: Progress
) -> WorkspaceResult:
    """Compute one ``[workspace]`` job (:data:`STAGES`)."""
    return run_stages(STAGES, ready, progress)


#: The warm-up examples by part (:mod:`planar_tui.warmup`): a cold run compiles the
#: kernels of the parts its jobs need (:func:`warmup_parts`), not every part's.
_WARMUP_TABLE = (
    "[[workspace]]\njoint_limits_deg = [[20, 70], [110, 160], [245, 295]]\n"
    "precision_cm = 8.0\ngeometric_reference = false\n"
)
#: A joint bisection long enough to go on in parallel after its serial start
#: (:data:`planar_tui.workspace.rrr.joint.SERIAL_BOXES`): the parallel kernel compiled too.
_PARALLEL_JOINT_TABLE = _WARMUP_TABLE.replace("8.0", "0.05") + 'strategy = "joint"\n'
WARMUP_PARTS = {
    "legwise": _WARMUP_TABLE + 'refine_precision_cm = 4.0\nstrategy = "legwise"\n',
    "joint": _WARMUP_TABLE
    + 'refine_precision_cm = 4.0\nstrategy = "joint"\n'
    + _PARALLEL_JOINT_TABLE,
    "arc-distance": _WARMUP_TABLE + 'form = "arc-distance"\n',
    "singularities": _WARMUP_TABLE + 'form = "arc-distance"\nsingularities = true\n'
    "elbow = [1, -1, 1]\n",
    "orientation": _WARMUP_TABLE + 'orientation_deg = [-1, 1]\norientation_mode = "total"\n',
    "dexterity": _WARMUP_TABLE + 'form = "arc-distance"\nkappa_max = 4\nelbow = [1, -1, 1]\n',
    "interference": _WARMUP_TABLE + 'form = "arc-distance"\nleg_width_cm = 2\nelbow = [1, -1, 1]\n',
    "accuracy": _WARMUP_TABLE
    + 'form = "arc-distance"\naccuracy = { actuator_deg = 0.1 }\nelbow = [1, -1, 1]\n',
}


def warmup_parts(job: Job[WorkspaceSpec, Robot3RRR]) -> tuple[str, ...]:
    """The parts of :data:`WARMUP_PARTS` whose kernels a run of ``job`` calls: a range of
    orientations, the arc-distance form or an interval form's strategy (none for the
    exact geometric area alone), and the singularities and dexterity where asked."""
    spec = job.spec
    if isinstance(spec.orientation_deg, tuple):
        parts = ["orientation"]
    elif spec.form == "geometric":
        parts = []
    elif spec.form == "arc-distance":
        parts = ["arc-distance"]
    else:
        parts = [spec.strategy]
    if spec.singularities:
        parts.append("singularities")
    parts += ["dexterity"] if spec.kappa_max is not None else []
    parts += ["interference"] if spec.leg_width_cm is not None else []
    return (*parts, "accuracy") if spec.accuracy is not None else tuple(parts)


JOB_KIND = JobKind(
    name="workspace",
    robot_kind="robot3rrr",
    settings=WorkspaceSpec,
    run=run_workspace,
    summary="3-RRR workspace by interval analysis: one orientation or a range of them, "
    "with its type II singularities and singularity-free circle",
    render=render_workspace,
    extra_outputs=extra_outputs,
    overrides=override_consequences,
    point_figures=point_figures,
    prepare=prepare_workspace,
    command=Command(
        "workspace",
        "3-RRR workspace of every workspace job: summary CSV, boxes CSV (--boxes or the "
        "preset's boxes_output) and a map titled with the job, form and precision.\n\n"
        "--form and --precision apply to every selected job; each one that changes a job's "
        "setting is appended to the stem of the files the preset names (table3-natural.csv "
        "run with --form mean-value writes table3-natural--form-mean-value.csv); names given "
        "with --out and --boxes are kept.",
        options=(
            Option(
                "--form",
                "form",
                "natural, mean-value, slope, arc-distance or geometric; overrides `form`.",
            ),
            PRECISION_OPTION,
            Option(
                "--tolerance",
                "tolerance_cm",
                "Manufacturing tolerance +- in cm on every length and joint coordinate; "
                "overrides `tolerance_cm`.",
                float,
            ),
            Option(
                "--tolerance-mode",
                "tolerance_mode",
                "all (the robust workspace) or some; overrides `tolerance_mode`.",
            ),
        ),
        outputs=(BOXES_OPTION,),
        view=MAP_VIEW,
    ),
    tab=Tab("Workspace", 2, "planar_tui.app.widgets.workspace_pane:WorkspacePane"),
    figure="planar_tui.figures.certified:from_result",
    warmup=WARMUP_PARTS,
    warmup_parts=warmup_parts,
    app_default={
        "joint_limits_deg": [[20.0, 70.0], [110.0, 160.0], [245.0, 295.0]],
        "orientation_deg": 0.0,
        "precision_cm": 0.9375,
        "form": "arc-distance",
        "output": "app-workspace.csv",
    },
)

"""The generic runner of a parallel robot's workspace job: the settings every such job
has (:class:`PlanarSpec`), the 2-D paving with the robot's exact per-leg test, the runner,
the job kind and the result.

A robot supplies a :class:`~planar_tui.workspace.paving.mechanism.Mechanism`: its kernel
parameters, the box holding its reach, its exact polygons (inner and outer,
:func:`~planar_tui.workspace.paving.geometry.polygon_bracket`) and its level kernel (one per
robot in ``kernels/``, with the signature of
:func:`~planar_tui.kernels.workspace3rpr.rpr_level`). The paving
(:func:`~planar_tui.workspace.paving.levels.pave_in_levels`, then
:func:`~planar_tui.workspace.paving.levels.finished_outcome`) never splits a box proved
inside; boundary boxes are kept at ``precision_cm`` and, with ``refine_precision_cm``, paved
again at that precision; the certified bracket is ``|inside| <= exact <= |kept|``. The
result is :class:`~planar_tui.workspace.paving.result.WorkspaceResult` (the same summary and
boxes CSVs for every robot), so the map, the figure and the app's workspace pane show every
kind.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, ClassVar

from planar_tui.jobkind import Command, Job, JobKind, Option, OutputOption, PreparedJob, Tab
from planar_tui.progress import Progress
from planar_tui.schema import TableReader, number, plot_setting, setting, string
from planar_tui.workspace.paving.accuracy import accuracy_setting, check_accuracy
from planar_tui.workspace.paving.circle import HEADER
from planar_tui.workspace.paving.columns import planar_figure_names
from planar_tui.workspace.paving.dexterity import (
    check_dexterity,
    kappa_setting,
    length_setting,
    planar_dexterity,
)
from planar_tui.workspace.paving.estimate import check_needs, estimate, report_box_estimate
from planar_tui.workspace.paving.interference import check_interference, width_setting
from planar_tui.workspace.paving.mechanism import Mechanism
from planar_tui.workspace.paving.orientation import (
    ORIENTATION_HEADER,
    check_orientation,
    orientation_columns,
    paved_range,
    range_stage,
)
from planar_tui.workspace.paving.orientation import describe as describe_range
from planar_tui.workspace.paving.result import (
    WorkspaceResult,
    extra_outputs,
    point_figures,
    render_workspace,
)
from planar_tui.workspace.paving.settings import (
    boxes_setting,
    budget_setting,
    centre_setting,
    checked_box_budget,
    precision_setting,
    read_search_box,
    reference_setting,
    refine_setting,
    search_box_setting,
    singularities_setting,
    singularity_precision_setting,
)
from planar_tui.workspace.paving.stages import Stages, SummaryRow, run_stages
from planar_tui.workspace.paving.tolerance import grown, reach_margin_cm


@dataclass(frozen=True, kw_only=True)
class PlanarSpec:
    """The settings every fixed-orientation parallel workspace job has (angles in degrees,
    lengths in cm); a kind adds its own keys (``leg_limits_cm``) in a subclass."""

    orientation_deg: float | tuple[float, float] = setting(
        number(), default=0.0, type_doc="number", doc="platform orientation φ"
    )
    precision_cm: float = precision_setting()
    form: str = setting(
        string(choices=("natural", "geometric")),
        default="natural",
        type_doc="`natural`, `geometric`",
        doc="exact per-leg test of each box (see docs/workspace.md), or the exact area only",
    )
    refine_precision_cm: float | None = refine_setting(
        doc="boundary-only refinement to this precision"
    )
    search_box_cm: tuple[tuple[float, float], tuple[float, float]] | None = search_box_setting(
        read_search_box
    )
    box_budget: int = budget_setting(
        doc="most (x, y) boxes one job may decide (then it fails, writing nothing)",
    )
    geometric_reference: bool = reference_setting()
    boxes_output: str | None = boxes_setting()
    plot: str | None = plot_setting()
    singularities: bool = singularities_setting(
        doc="also map the type II singularities and certify the singularity-free circle",
    )
    circle_centre_cm: tuple[float, float] | None = centre_setting()
    singularity_precision_cm: float | None = singularity_precision_setting()
    kappa_max: float | None = kappa_setting()
    characteristic_length_cm: float | None = length_setting()
    leg_width_cm: float | None = width_setting()
    accuracy: tuple[tuple[str, float], ...] | None = accuracy_setting()

    #: The kind's :class:`Mechanism` and job kind's name (set by each subclass; not keys).
    mechanism: ClassVar[Mechanism]
    kind: ClassVar[str] = ""
    #: The robot's toleranced quantities, for a kind with tolerance keys
    #: (:mod:`planar_tui.workspace.paving.tolerance`; ``()``: none).
    tolerance_keys: ClassVar[tuple[str, ...]] = ()
    #: The keys that go with ``singularities = true`` (:func:`check_circle_keys`).
    circle_keys: ClassVar[tuple[str, ...]] = ("circle_centre_cm", "singularity_precision_cm")
    #: The circle keys that ``kappa_max`` and ``leg_width_cm`` take too (their working
    #: mode; ``()``: none).
    mode_keys: ClassVar[tuple[str, ...]] = ()

    @property
    def orientation_rad(self) -> float:
        """The single orientation in radians (a kind taking ranges has none then)."""
        if isinstance(self.orientation_deg, tuple):
            raise ValueError("orientation_deg is a range: no single orientation")
        return math.radians(self.orientation_deg)

    @classmethod
    def check(cls, values: dict[str, Any], reader: TableReader, robot: Any) -> dict[str, Any]:
        """The refinement precision cannot exceed the precision; an explicit search box
        must hold the legs' reach (a "some" job's: grown by the tolerances); the box budget
        must fit the memory limit; the circle's keys go with ``singularities``
        (:func:`check_circle_keys`); the job's estimated memory and time must fit the limits
        (:func:`~planar_tui.workspace.paving.estimate.check_needs`)."""
        moded = any(values[k] is not None for k in ("kappa_max", "leg_width_cm", "accuracy"))
        names = tuple(n for n in cls.circle_keys if not (moded and n in cls.mode_keys))
        if values["kappa_max"] is not None:  # the dexterous disc's centre
            names = tuple(n for n in names if n != "circle_centre_cm")
        check_circle_keys(values, reader, names)
        check_dexterity(values, reader, cls.mechanism.has_tolerant_dexterity)
        if values["leg_width_cm"] is not None and not cls.mechanism.has_interference:
            found = f"is set: the {cls.mechanism.name}'s leg interference is not certified yet"
            raise reader.error("leg_width_cm", found, "no leg_width_cm")
        check_interference(values, reader)
        if values["accuracy"] is not None and not cls.mechanism.accuracy_unit:
            found = f"is set: the {cls.mechanism.name}'s accuracy is not certified yet"
            raise reader.error("accuracy", found, "no accuracy")
        if values["accuracy"] is not None:
            check_accuracy(values, reader, cls.mechanism.accuracy_unit)
        refine = values["refine_precision_cm"]
        if refine is not None and refine > values["precision_cm"]:
            raise reader.error(
                "refine_precision_cm", f"is {refine:g} > precision_cm", "<= precision_cm"
            )
        box = values["search_box_cm"]
        if box is not None:
            spec = cls(**values)

            reach = grown(spec.mechanism.reach_box(robot, spec), reach_margin_cm(spec))
            rxlo, rxhi, rylo, ryhi = reach  # a "some" job's robots reach farther
            (xlo, xhi), (ylo, yhi) = box
            holds = xlo <= rxlo and rxhi <= xhi and ylo <= rylo and ryhi <= yhi
            if rxlo <= rxhi and rylo <= ryhi and not holds:
                raise reader.error(
                    "search_box_cm",
                    "cannot contain the legs' reach "
                    f"x in [{rxlo:.4g}, {rxhi:.4g}], y in [{rylo:.4g}, {ryhi:.4g}] cm",
                    "a box containing it",
                )
        values["box_budget"] = checked_box_budget(values["box_budget"], reader)
        check_needs(cls.kind, cls(**values), reader, robot)
        return values


def single_orientation_rad(spec: Any) -> float | None:
    """The spec's one orientation in radians (a degenerate range ``[φ, φ]`` built in code
    counts as one), or ``None`` over a range."""
    phi = spec.orientation_deg
    if not isinstance(phi, tuple):
        return math.radians(phi)
    return math.radians(phi[0]) if phi[0] == phi[1] else None


def check_range_and_reference(values: dict[str, Any], reader: TableReader, form: str) -> None:
    """An orientation range takes the 3-RRR's ``orientation_mode`` checks
    (:func:`~planar_tui.workspace.paving.orientation.check_orientation`) with the kind's box form
    ``form`` only, and no singularities; with a range or a tolerance the job has no geometric
    reference (one orientation's nominal area is not the job's: off by default, refused if
    asked for)."""
    check_orientation(values, reader, form)
    ranged = isinstance(values["orientation_deg"], tuple)
    if ranged and values["singularities"]:
        raise reader.error(
            "singularities", "is true with orientation_deg = [lo, hi]", "one orientation"
        )
    if (values["tolerance_mode"] is not None or ranged) and values["geometric_reference"]:
        if reader.has("geometric_reference"):
            found = "a tolerance" if values["tolerance_mode"] else "orientation_deg = [lo, hi]"
            raise reader.error("geometric_reference", f"is true with {found}", "false")
        values["geometric_reference"] = False  # its default is one orientation's exact area


def compute_range(robot: Any, spec: Any, budget: Any, g: Any, limits: Any, mechanism: int) -> Any:
    """The maximal or total orientation workspace of a parallel kind's spec with
    ``orientation_deg = (lo, hi)``: the 3-RRR's range paving
    (:func:`~planar_tui.workspace.paving.orientation.range_stage`) of the kernels' ``mechanism``
    with its arrays ``g`` (the platform points at ``g[2:8]``) and ``limits``."""
    from planar_tui.workspace.paving.levels import square_about

    started = time.perf_counter()
    box = spec.search_box_cm or square_about(
        spec.mechanism.reach_box(robot, spec), spec.precision_cm
    )
    extent = (box[0][0], box[0][1], box[1][0], box[1][1])
    points = robot.platform_points_cm

    def stage(seeds, precision, inside_cm2):
        return range_stage(g, limits, mechanism, points, spec, seeds, precision, budget, inside_cm2)

    return paved_range(stage, spec, budget, extent, None, started, disjoint=True)


def platform_and_base_vector(platform: Any, base: Any) -> Any:
    """``[0, 0, q1, q2, q3, B1, B2, B3]`` flattened (cm): the 3-RRR's layout of the range
    kernels' ``g`` (:mod:`planar_tui.kernels.workspace_orientation`)."""
    import numpy as np

    values = [0.0, 0.0]
    for point in (*platform, *base):
        values += [float(point[0]), float(point[1])]
    return np.array(values)


def check_circle_keys(values: dict[str, Any], reader: TableReader, names: tuple[str, ...]) -> None:
    """The circle's keys ``names`` go with ``singularities = true``, which needs a form
    with boxes."""
    if not values["singularities"]:
        for name in names:
            if values[name] is not None:
                raise reader.error(
                    name, "is set without singularities = true", "singularities = true"
                )
    elif values["form"] == "geometric":
        raise reader.error("singularities", 'is true with form = "geometric"', "a form with boxes")


def compute_workspace(
    mechanism: Mechanism, robot: Any, spec: Any, budget: Any, label: str | None = None
) -> Any:
    """The paving of the module docstring for one robot, its ``mechanism`` and a spec
    (:class:`~planar_tui.workspace.paving.levels.WorkspaceOutcome`): the search box (the
    spec's, else a square about the reach box grown by
    :func:`~planar_tui.workspace.paving.tolerance.reach_margin_cm`), the levels decided by
    :meth:`Mechanism.decider`, the boundary refined, ``|inside| <= exact <= |kept|``; an
    orientation range goes to :meth:`Mechanism.compute_range`. ``label`` names the stage in
    the progress (default: the form's)."""
    import numpy as np

    from planar_tui.workspace.paving.levels import (
        WorkspaceOutcome,
        finished_outcome,
        pave_in_levels,
        square_about,
    )

    if mechanism.has_orientation_ranges and isinstance(spec.orientation_deg, tuple):
        return mechanism.compute_range(robot, spec, budget)  # the kind's check allowed it
    started = time.perf_counter()
    reach = grown(mechanism.reach_box(robot, spec), reach_margin_cm(spec))  # "some": farther
    box = spec.search_box_cm or square_about(reach, spec.precision_cm)
    extent = (box[0][0], box[0][1], box[1][0], box[1][1])
    geometric = None
    if spec.geometric_reference or spec.form == "geometric":
        geometric = mechanism.geometric_area(robot, spec)
    if spec.form == "geometric":
        assert geometric is not None
        nothing = np.zeros((0, 4))
        return WorkspaceOutcome(
            form="geometric",
            precision_cm=spec.precision_cm,
            refine_precision_cm=None,
            boxes=nothing,
            status=np.zeros(0, np.int64),
            boxes_processed=0,
            area_kept_cm2=geometric.outer_cm2,
            area_inside_cm2=geometric.inner_cm2,
            geometric=geometric,
            seconds=time.perf_counter() - started,
            extent_cm=extent,
        )

    def decider(precision: float) -> Callable[..., None]:
        return mechanism.decider(robot, spec, precision)

    budget.progress.start(1.0, label or f"{spec.form} paving")
    boxes, status = pave_in_levels(np.array([extent]), budget, decider(spec.precision_cm))

    def refine(seeds, inside_cm2):
        assert spec.refine_precision_cm is not None
        return pave_in_levels(seeds, budget, decider(spec.refine_precision_cm), inside_cm2)

    return finished_outcome(
        spec,
        boxes,
        status,
        refine,
        budget,
        geometric,
        started,
        extent,
        form=spec.form,
        disjoint=True,
    )


def compute_planar(robot: Any, spec: PlanarSpec, budget: Any) -> Any:
    """:func:`compute_workspace` with the spec's kind's Mechanism (a 3-RPR or 3-PRR)."""
    return compute_workspace(spec.mechanism, robot, spec, budget)


def pave_planar(job: Any, budget: Any) -> Any:
    """The pave stage of a parallel kind: its box estimate reported (warned of over the box
    budget), then :func:`compute_planar`."""
    report_box_estimate(job, budget.progress)
    return compute_planar(job.robot, job.spec, budget)


def planar_head(job: Any, outcome: Any) -> SummaryRow:
    """The summary row of the paving: the 3-RRR's columns, its orientation's among them,
    and the range described where the orientation is one."""
    from planar_tui.workspace.paving.levels import SUMMARY_HEADER, summary_line  # numpy

    base, summary = outcome.summary_row(), summary_line(outcome)
    if isinstance(job.spec.orientation_deg, tuple):
        summary += f"; {describe_range(job.spec)}"
    header = (*SUMMARY_HEADER[:-1], *ORIENTATION_HEADER)
    return SummaryRow(header, [*base[:-1], *orientation_columns(job.spec)], summary, base[-1])


def planar_singularities(ready: Any, outcome: Any, budget: Any) -> Any:
    """The circle's columns where the Mechanism certifies singularities (computed where
    ``prepare`` resolved a centre); none where it does not."""
    mechanism: Mechanism = ready.job.spec.mechanism
    if not mechanism.has_singularities:
        return None
    if ready.prepared is None:
        return HEADER, None
    return HEADER, mechanism.compute_singularities(
        ready.job, ready.prepared, outcome.extent_cm, budget
    )


def planar_dexterity_stage(ready: Any, extent: Any, budget: Any) -> Any:
    """:func:`~planar_tui.workspace.paving.dexterity.planar_dexterity` of the prepared job."""
    return planar_dexterity(ready.job, ready.prepared, extent, budget)


#: The stages of a 3-RPR or 3-PRR job (:func:`~planar_tui.workspace.paving.stages.run_stages`).
PLANAR_STAGES = Stages(
    pave=pave_planar,
    compute=compute_planar,
    head=planar_head,
    singularities=planar_singularities,
    dexterity=planar_dexterity_stage,
    elbow=lambda ready: "",
)


def run_planar(ready: PreparedJob[PlanarSpec, Any, Any], progress: Progress) -> WorkspaceResult:
    """Run one workspace job of a parallel kind (:data:`PLANAR_STAGES`): the summary CSV
    (the 3-RRR's columns, its orientation's among them), the boxes and the one-line
    summary."""
    return run_stages(PLANAR_STAGES, ready, progress)


def prepare_planar(job: Job[PlanarSpec, Any]) -> object:
    """The kind's ``prepare``: the singularity-free circle's centre, checked (``None``
    without singularities); with ``kappa_max`` (``leg_width_cm``, ``accuracy``) the κ
    (clearance, pose error) evaluator is built once here, so a working mode it cannot resolve is refused before
    anything runs."""
    mechanism: Mechanism = job.spec.mechanism
    prepared = mechanism.resolve_centre(job) if mechanism.has_singularities else None
    if job.spec.kappa_max is not None:
        mechanism.dexterity(job, prepared)
    if job.spec.leg_width_cm is not None:
        mechanism.interference(job, prepared)
    if job.spec.accuracy is not None:
        mechanism.accuracy(job, prepared)
    return prepared


def planar_job_kind(
    name: str, mechanism_name: str, settings: type, summary: str, tab: Tab, warmup: str
) -> JobKind:
    """The :class:`JobKind` of a fixed-orientation parallel kind ``name`` (its robot table
    ``robot`` + the name's suffix): the shared runner, terminal map, figure, command
    (``--precision``, ``--boxes``, ``--map/--no-map``), its estimate
    (:mod:`planar_tui.workspace.paving.estimate`) and sweep columns
    (:mod:`planar_tui.workspace.paving.columns`)."""
    declared = getattr(settings, "kind", None)
    assert declared == name, f"{settings.__name__}.kind is {declared!r}, not {name!r}"
    return JobKind(
        name=name,
        robot_kind="robot" + name.removeprefix("workspace"),
        settings=settings,
        run=run_planar,
        prepare=prepare_planar,
        point_figures=point_figures,
        summary=summary,
        render=render_workspace,
        extra_outputs=extra_outputs,
        command=Command(
            name,
            f"{mechanism_name} workspace of every {name} job: summary CSV, boxes CSV (--boxes "
            "or the preset's boxes_output) and a map titled with the job and precision.",
            options=(
                Option(
                    "--precision",
                    "precision_cm",
                    "Precision epsilon in cm; overrides `precision_cm`.",
                    float,
                ),
            ),
            outputs=(
                OutputOption(
                    "--boxes", "boxes", "CSV of the kept boxes (with several jobs: FILE-1.csv ...)."
                ),
            ),
            view=("--map/--no-map", "Print the character-cell map."),
        ),
        tab=tab,
        figure="planar_tui.figures.certified:from_planar_result",
        warmup=warmup,
        estimate=estimate,
        figure_names=planar_figure_names,
    )


__all__ = [
    "PlanarSpec",
    "compute_planar",
    "compute_workspace",
    "extra_outputs",
    "planar_job_kind",
    "render_workspace",
    "run_planar",
]

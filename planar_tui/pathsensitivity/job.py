"""The path-sensitivity job kinds' shared part: their sampling keys, checks, runner,
result, terminal view and the :class:`~planar_tui.jobkind.JobKind` a robot's module
declares with :func:`path_sensitivity_kind`.

A robot's settings are its path job's (``from_pose``, ``to_pose``, ``duration_s``,
``steps``, its working mode and limits: the same keys, read and checked by the same code)
plus :class:`SensitivityKeys`. Why one kind per robot rather than one kind naming a path
job: a job kind runs on one robot table (``robot_kind``) and a preset's job tables are
read one by one (the app validates one job alone), so a job cannot name another job's
table; the per-robot kinds share everything here and differ by one module of a few lines.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, ClassVar

from planar_tui import uq
from planar_tui.errors import PresetError
from planar_tui.jobkind import Command, Job, JobKind
from planar_tui.limits import memory_problem, time_problem
from planar_tui.pathsensitivity.analysis import PathSensitivityResult, analyse_path
from planar_tui.pathsensitivity.inputs import INERTIA, LENGTH, MASS
from planar_tui.pathsensitivity.sizes import inputs_of, sample_sizes
from planar_tui.schema import TableReader, boolean, integer, number, setting

METHODS = ("sobol", "efast", "pce")
#: Seconds per sampled pose of one design row (kernel and Python wrapper, per row), as the
#: path jobs' estimate; memory per effort value (efforts, outputs, indices).
POSE_SECONDS = 2e-6
BYTES_PER_EFFORT = 48


@dataclass(frozen=True, kw_only=True)
class SensitivityKeys:
    """The sampling keys of a path-sensitivity job (``docs/path-sensitivity.md``); and the
    path job's ``feed_forward``, kept false."""

    feed_forward: bool = setting(
        boolean(),
        default=False,
        type_doc="boolean",
        doc="the path job's key, refused here when true (a sensitivity runs no forward dynamics)",
    )

    tolerance_length_mm: float = uq.tolerance_setting(
        "mm", "half-width of every length's range (link lengths, platform and base geometry)"
    )
    tolerance_mass_g: float = uq.tolerance_setting(
        "g", "half-width of every mass's range (each body with a positive mass)"
    )
    tolerance_inertia_kgm2: float | None = setting(
        number(positive=True),
        default=None,
        default_doc="(none: inertias fixed)",
        type_doc="0 < number < smallest positive inertia",
        doc="half-width of every positive inertia's range; makes the inertias inputs",
    )
    methods: tuple[str, ...] = uq.methods_setting(
        METHODS,
        default=("sobol", "pce"),
        default_doc='`["sobol", "pce"]`',
        doc="estimators, as the serial arm's path study: Sobol' (Saltelli design), eFAST "
        "(M = 4), pce (polynomial chaos, indices from its coefficients)",
    )
    samples: int = setting(
        integer(minimum=1),
        default=256,
        type_doc="power of two ≥ 8",
        doc="Sobol' base N (N·(D+2) robots along the path, D inputs)",
    )
    efast_samples: int | None = setting(
        integer(minimum=1),
        default=None,
        default_doc="same cost as Sobol', at least 4 M² (D − 1) + 1",
        type_doc="integer > 64",
        doc="eFAST N per input (M = 4); below 4 M² (D − 1) + 1 its search frequencies repeat "
        "and small indices come out too large",
    )
    pce_samples: int | None = uq.pce_samples_setting("robots")
    pce_max_loo_error: float = uq.pce_max_loo_setting(
        "largest accepted PCE leave-one-out error of any output; above it the job fails",
    )
    allow_failed_runs: float = uq.allow_failed_runs_setting(
        "fraction of PCE robots that may fail the path (a leg that cannot close, a limit, a "
        "singularity) and be dropped from the fit; any failure fails Sobol' and eFAST",
    )
    seed: int = uq.seed_setting("seed of sampling and bootstrap")

    #: The robot fields named otherwise in the preset (field -> key), for the inputs' names.
    key_names: ClassVar[dict[str, str]] = {}

    @staticmethod
    def length_fields(robot: Any) -> tuple[str, ...]:
        """The robot's length fields that are inputs (a robot's spec says which)."""
        raise NotImplementedError


def robot_count(spec: Any, num_vars: int) -> int:
    """Robots run along the path: every method's design, and N Monte-Carlo robots for
    eFAST's per-step variances (its search curves are not independent draws)."""
    sizes = sample_sizes(spec, num_vars)
    rows = sum(uq.design_rows(m, num_vars, sizes[m]) for m in spec.methods)
    return rows + (sizes["efast"] if "efast" in spec.methods else 0)


def resource_estimate(spec: Any, robot: Any) -> tuple[float, float]:
    """``(memory_bytes, seconds)``: robots × poses of the inverse dynamics, their efforts
    and per-step outputs."""
    robots = robot_count(spec, len(inputs_of(spec, robot)))
    poses = robots * (spec.steps + 1)
    actuators = spec.mechanism.path_model(robot).actuators
    return poses * actuators * BYTES_PER_EFFORT, poses * POSE_SECONDS


def check_sensitivity(
    values: dict[str, Any], reader: TableReader, robot: Any, settings: type
) -> dict[str, Any]:
    """No feed-forward; every tolerance below the smallest nominal value it spreads; a robot
    with a mass (else every effort is 0); sample sizes the methods accept; the run within
    the time and memory limits."""
    if values.get("feed_forward"):
        raise reader.error(
            "feed_forward", "is true: a sensitivity job integrates no forward dynamics", "false"
        )
    spec = settings(**values)
    inputs = inputs_of(spec, robot)
    if not any(i.kind == MASS for i in inputs):
        raise reader.error(
            "tolerance_mass_g",
            "spreads no mass: the robot's bodies are massless, every effort is 0",
            "positive masses in the robot table",
        )
    for key, kind, unit, scale in (
        ("tolerance_length_mm", LENGTH, "mm", 10.0),
        ("tolerance_mass_g", MASS, "g", 1000.0),
        ("tolerance_inertia_kgm2", INERTIA, "kg m²", 1.0),
    ):
        # a length field's entries (not a point's coordinates, which may be 0 or negative)
        nominal = [i.nominal * scale for i in inputs if i.kind == kind and len(i.position) < 2]
        value = values.get(key)
        if nominal and value is not None and value >= min(nominal):
            raise reader.error(
                key,
                f"is {value:g} {unit}, not below the smallest nominal value "
                f"{min(nominal):g} {unit}",
                f"0 < tolerance < {min(nominal):g}",
            )
    sizes = sample_sizes(spec, len(inputs))
    keys = {"sobol": "samples", "efast": "efast_samples", "pce": "pce_samples"}
    uq.check_samples(reader.error, spec.methods, {m: (keys[m], sizes[m]) for m in METHODS})
    memory, seconds = resource_estimate(spec, robot)
    problem = time_problem(seconds) or memory_problem(memory)
    if problem is not None:
        robots = robot_count(spec, len(inputs))
        raise reader.error(
            "samples",
            f"{robots} robots × {spec.steps + 1} poses: {problem}",
            "fewer samples or fewer steps",
        )
    return values


def extra_outputs(job: Job[Any, Any]) -> dict[str, str]:
    """The per-step indices beside the job's CSV (``-path.csv``) and the aggregated
    indices (``-path-aggregated.csv``), as the serial arm's path study."""
    stem = job.output[:-4] if job.output.lower().endswith(".csv") else job.output
    return {"path": f"{stem}-path.csv", "path_aggregated": f"{stem}-path-aggregated.csv"}


def render(job: Job[Any, Any], result: PathSensitivityResult, console: Any) -> None:
    """The CLI view: the peak and RMS indices' table, fitted to the terminal width."""
    from planar_tui.sensitivity.tables import VIEWS, fit_tables

    console.print(f"{result.robot_label}: {job.label}", style="bold", markup=False)
    console.print(fit_tables(result.analyses, VIEWS[0], console.width, "ST").renderable)


def _outputs(job: Job[Any, Any]) -> list[str]:
    model = job.spec.mechanism.path_model(job.robot)
    actuators = range(1, model.actuators + 1)
    return [f"{model.effort}{i}_{what}" for what in ("peak", "rms") for i in actuators]


def figure_names(job: Job[Any, Any]) -> tuple[str, ...]:
    """The columns :func:`point_figures` reports, without running the job."""
    return tuple(
        f"{out}_{figure}" for out in _outputs(job) for figure in ("dominant", "dominant_percent")
    )


def point_figures(job: Job[Any, Any], result: PathSensitivityResult) -> dict[str, Any]:
    """A sweep row's figures: per actuator's peak and RMS effort, the input of largest
    share (the first method's ``percent``) and that share."""
    chosen = result.analyses[0]
    figures: dict[str, Any] = {}
    for out, percent in zip(_outputs(job), chosen.percent, strict=True):
        top = int(percent.argmax())
        figures[f"{out}_dominant"] = chosen.names[top]
        figures[f"{out}_dominant_percent"] = float(percent[top])
    return figures


def prepared_spec(prepare: Callable[[Job[Any, Any]], Any]) -> Callable[[Job[Any, Any]], Any]:
    """The robot path job's ``prepare`` (its working mode resolved) with the resources
    checked again (command-line overrides change them)."""

    def prepare_job(job: Job[Any, Any]) -> Any:
        spec = prepare(job)
        memory, seconds = resource_estimate(spec, job.robot)

        problem = time_problem(seconds) or memory_problem(memory)
        if problem is not None:
            raise PresetError(
                job.preset_path, f"{job.key}.samples", problem, "fewer samples or fewer steps"
            )
        return spec

    return prepare_job


def path_sensitivity_kind(
    name: str,
    robot_kind: str,
    settings: type,
    robot_words: str,
    prepare: Callable[[Job[Any, Any]], Any],
    warmup: str,
) -> JobKind:
    """The :class:`JobKind` of a robot's path sensitivity (``prepare``: its path job's)."""
    return JobKind(
        name=name,
        robot_kind=robot_kind,
        settings=settings,
        run=analyse_path,
        summary=f"Sobol'/eFAST/PCE sensitivity of the {robot_words}'s actuator efforts "
        "along a path",
        render=render,
        prepare=prepared_spec(prepare),
        extra_outputs=extra_outputs,
        point_figures=point_figures,
        figure_names=figure_names,
        estimate=lambda job: resource_estimate(job.spec, job.robot),
        command=Command(
            name,
            f"Sobol'/eFAST/PCE sensitivity of the {robot_words}'s actuator efforts along the "
            f"quintic path of every {name} job to its lengths and masses under tolerances: "
            "indices of each actuator's peak and RMS effort (one CSV per job), of every "
            "effort at every step (OUTPUT-path.csv) and aggregated over the path "
            "(OUTPUT-path-aggregated.csv).",
            options=uq.sampling_options(METHODS, "Sobol' base N (a power of two)"),
        ),
        figure="planar_tui.figures.dispatch:from_main_table",
        warmup=warmup,
    )

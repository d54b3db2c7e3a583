"""The ``[sensitivity]`` job: Sobol'/eFAST sensitivity of the joint torques (paper A, §3).

Settings (the preset keys), command-line overrides, the runner (sampling, evaluation,
analysis), the typed result and the terminal view of one job kind.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from planar_tui import uq
from planar_tui.dynamics.robot import SerialRobot
from planar_tui.errors import PresetError
from planar_tui.jobkind import Command, Job, JobKind, JobResult, PreparedJob, Tab, option_or_key
from planar_tui.progress import Progress
from planar_tui.schema import (
    TableReader,
    boolean,
    integer,
    number,
    per_link,
    plot_setting,
    setting,
    shown,
    string,
)
from planar_tui.sensitivity.figure_names import figure_names
from planar_tui.sensitivity.path import PathSpec

if TYPE_CHECKING:
    from planar_tui.sensitivity.postures import Posture
    from planar_tui.sensitivity.results import Analysis

METHODS = ("sobol", "efast", "pce")
#: The methods a job runs unless its preset says otherwise (paper A's two).
DEFAULT_METHODS = ("sobol", "efast")
PERCENT_OF = ("ST", "S1")
#: Rough cost of one model run (an inverse dynamics, batched): 0.3 µs + 20 ns per link.
MODEL_RUN_SECONDS = (3e-7, 2e-8)


def _read_speeds(reader: TableReader, name, default, robot, values) -> tuple[float, ...]:
    """One speed (a number) or a sweep (a list of numbers)."""
    if isinstance(reader.raw(name, 1.0), list):
        return reader.numbers(name)
    return (reader.number(name, 1.0),)


def _dump_speeds(speeds: tuple[float, ...]) -> Any:
    return speeds[0] if len(speeds) == 1 else list(speeds)


def _read_posture_request(reader: TableReader, name, default, robot, values) -> Any:
    """``"singular"``, ``"isotropic"`` or n joint angles in degrees."""
    if isinstance(reader.raw(name, default), list):
        return reader.numbers(name, length=robot.n_links)
    return reader.string(name, default, choices=("singular", "isotropic"))


per_link(_read_posture_request, "list")  # when it lists angles


#: Most path steps (each is one batched inverse dynamics of every design row).
MAX_PATH_STEPS = 1000


def _read_path(reader: TableReader, name, default, robot, values) -> PathSpec | None:
    """``{ to_deg = [n angles], duration_s = T, steps = K }`` or absent."""
    table = reader.raw(name, None)
    if table is None:
        return None
    expected = "{ to_deg = [n angles in degrees], duration_s = T > 0, steps = K >= 1 }"
    if not isinstance(table, dict):
        raise reader.error(name, f"is {shown(table)}", expected)
    inner = TableReader(reader.path, table, reader.key(name), ("to_deg", "duration_s", "steps"))
    return PathSpec(
        inner.numbers("to_deg", length=robot.n_links),
        inner.number("duration_s", positive=True),
        inner.integer("steps", minimum=1, maximum=MAX_PATH_STEPS),
    )


def _dump_path(path: PathSpec | None) -> Any:
    if path is None:
        return None
    return {"to_deg": list(path.to_deg), "duration_s": path.duration_s, "steps": path.steps}


@dataclass(frozen=True, kw_only=True)
class SensitivitySpec:
    """Settings of one sensitivity job (see ``docs/sensitivity.md``).

    ``posture_request`` is what the preset asked for (key ``posture``);
    :func:`prepare_sensitivity` solves it (:class:`SensitivityPrepared`).
    ``efast_samples`` None means "match the Sobol' cost".
    """

    posture_request: Any = setting(
        _read_posture_request,
        name="posture",
        default="singular",
        type_doc='`"singular"`, `"isotropic"` or n angles in degrees',
        doc="singular = all joint angles 0; isotropic = the posture minimising the Jacobian "
        "condition number (2R closed form; 3R with orientation row and characteristic "
        "length); a robot without one is refused, naming the minimum reached",
    )
    speeds_rad_s: tuple[float, ...] = setting(
        _read_speeds,
        name="speed_rad_s",
        default=(1.0,),
        default_doc="`1.0`",
        dump=_dump_speeds,
        type_doc="number or list",
        doc="the joint speed of every joint; a list is a sweep (Figs 5-6)",
    )
    alpha_rad_s2: float = setting(
        number(), default=0.0, type_doc="number", doc="the joint acceleration of every joint"
    )
    path: PathSpec | None = setting(
        _read_path,
        default=None,
        default_doc="(none)",
        dump=_dump_path,
        type_doc="`{ to_deg = [...], duration_s = T, steps = K }`",
        doc="torques along a quintic rest-to-rest path from the posture to `to_deg` instead "
        "of one state (speed and acceleration then come from the path): indices of the peak "
        "absolute torque and the RMS torque of each joint (the table) and of each torque at "
        "every step "
        f"(`-path.csv`); at most {MAX_PATH_STEPS} steps",
    )
    tolerance_length_mm: float = uq.tolerance_setting("mm", "half-width of every length's range")
    tolerance_mass_g: float = uq.tolerance_setting("g", "half-width of every mass's range")
    vary_inertias: bool = setting(
        boolean(), default=False, type_doc="boolean", doc="add the inertias as inputs"
    )
    tolerance_inertia_kgm2: float | None = setting(
        number(positive=True),
        default=None,
        default_doc="(needs `vary_inertias`)",
        type_doc="number > 0",
        doc="half-width of every inertia's range",
    )
    methods: tuple[str, ...] = uq.methods_setting(
        METHODS,
        default=DEFAULT_METHODS,
        default_doc='`["sobol", "efast"]`',
        doc="estimators (Sobol', eFAST: SALib samples, jitted analysis equal to SALib's; "
        "pce: polynomial chaos, indices from its coefficients)",
    )
    samples: int = setting(
        integer(minimum=1),
        default=8192,
        type_doc="power of two ≥ 8",
        doc="Sobol' base N (N·(D+2) model runs, D inputs)",
    )
    efast_samples: int | None = setting(
        integer(minimum=1),
        default=None,
        default_doc="same cost as Sobol'",
        type_doc="integer > 64",
        doc="eFAST N per input (M = 4)",
    )
    pce_samples: int | None = uq.pce_samples_setting("model runs")
    pce_max_loo_error: float = uq.pce_max_loo_setting(
        "largest accepted PCE leave-one-out error (relative); above it the job fails",
    )
    allow_failed_runs: float = uq.allow_failed_runs_setting(
        "fraction of model runs that may fail (non-finite torques) and be dropped from "
        "a PCE fit; any failure fails Sobol' and eFAST",
    )
    seed: int = uq.seed_setting("seed of sampling and bootstrap (SALib treats 0 as no seed)")
    percent_of: str = setting(
        string(choices=PERCENT_OF),
        default="ST",
        type_doc='`"ST"` or `"S1"`',
        doc="index normalised to the `percent` column (the paper's: total)",
    )
    isotropy_tolerance: float = setting(
        number(positive=True),
        default=0.01,
        type_doc="number > 0",
        doc='largest accepted `κ − 1` for `"isotropic"`',
    )
    plot: str | None = plot_setting()

    @staticmethod
    def check(values: dict[str, Any], reader: TableReader, robot: SerialRobot) -> dict[str, Any]:
        """Tolerances below the nominal values and sample sizes (cheap: the posture is
        solved by :func:`prepare_sensitivity`, before the job runs)."""
        tolerance_inertia = values["tolerance_inertia_kgm2"]
        if values["vary_inertias"] and tolerance_inertia is None:
            raise reader.error("tolerance_inertia_kgm2", "missing key", "a positive number")
        if not values["vary_inertias"] and tolerance_inertia is not None:
            raise reader.error(
                "tolerance_inertia_kgm2",
                "is set but vary_inertias is false",
                "vary_inertias = true",
            )
        uq.check_tolerances(values, reader, robot)
        spec = SensitivitySpec(**values)
        uq.check_samples(reader.error, spec.methods, spec.sample_keys())
        check_resources(reader.error, spec, robot)
        return values

    def sample_keys(self) -> uq.SampleSizes:
        """Each method's sample-count key and value (eFAST's ``None``: matching Sobol')."""
        return {
            "sobol": ("samples", self.samples),
            "efast": ("efast_samples", self.efast_samples),
            "pce": ("pce_samples", self.pce_samples),
        }

    @property
    def tolerance_length_m(self) -> float:
        """Half-width of every length's uniform range, in metres."""
        return self.tolerance_length_mm * 1e-3

    @property
    def tolerance_mass_kg(self) -> float:
        """Half-width of every mass's uniform range, in kilograms."""
        return self.tolerance_mass_g * 1e-3

    @property
    def inertia_tolerance_kgm2(self) -> float | None:
        """Half-width of every inertia's range when the inertias vary, else ``None``."""
        return self.tolerance_inertia_kgm2 if self.vary_inertias else None


def resource_estimate(spec: SensitivitySpec, robot: SerialRobot) -> tuple[float, float]:
    """Rough peak memory (bytes) and computing time (s) of a job: the unit designs (drawn
    and cached), one output matrix per method and speed, the Sobol' bootstrap's
    resample indices and counts (N × 1000 each), and one model run per design row and
    speed."""
    from planar_tui.sensitivity.estimators import NUM_RESAMPLES

    n = robot.n_links
    num_vars = (3 if spec.vary_inertias else 2) * n
    sizes = sample_sizes(spec, num_vars)
    rows = {method: uq.design_rows(method, num_vars, sizes[method]) for method in spec.methods}
    speeds = len(spec.speeds_rad_s)
    memory = sum(r * (2 * num_vars + speeds * n + 2 * n) * 8.0 for r in rows.values())
    if "sobol" in spec.methods:
        memory += 2.0 * spec.samples * NUM_RESAMPLES * 8
    per_run = MODEL_RUN_SECONDS[0] + MODEL_RUN_SECONDS[1] * n
    return memory, sum(rows.values()) * speeds * per_run


def check_resources(error: uq.ErrorFactory, spec: SensitivitySpec, robot: SerialRobot) -> None:
    """Refuse a job whose estimated memory or time exceeds :mod:`planar_tui.limits`."""
    from planar_tui.limits import memory_problem, time_problem

    memory, seconds = resource_estimate(spec, robot)
    problem = memory_problem(memory) or time_problem(seconds)
    if problem is not None:
        raise error(
            "samples",
            f"{robot.n_links} links, {len(spec.speeds_rad_s)} speed(s), samples = "
            f"{shown(spec.samples)}: {problem}",
            "fewer samples, links or speeds",
        )


def solve_posture(job: Job[SensitivitySpec, SerialRobot]) -> Posture:
    """The job's posture: singular, explicit, or the isotropic one solved now (seconds for
    a robot of hundreds of links); a robot without one is a :class:`PresetError` on the
    job's ``posture`` key."""
    from planar_tui.sensitivity.postures import (
        NoIsotropicPosture,
        explicit_posture,
        isotropic_posture,
        singular_posture,
    )

    spec, robot = job.spec, job.robot
    request = spec.posture_request
    if isinstance(request, tuple):
        return explicit_posture(request, robot.lengths_m)
    if request == "singular":
        return singular_posture(robot.n_links)
    try:
        import numpy as np

        with np.errstate(over="ignore", invalid="ignore"):  # a 1e30 m link: κ ~ 1e30, said below
            return isotropic_posture(robot.lengths_m, spec.isotropy_tolerance)
    except NoIsotropicPosture as error:
        raise PresetError(
            job.preset_path,
            f"{job.key}.posture",
            f"robot has {error}",
            "a robot with an isotropic posture",
        ) from None


@dataclass(frozen=True)
class SensitivityPrepared:
    """What :func:`prepare_sensitivity` resolves: the job's solved posture."""

    posture: Posture


def prepare_sensitivity(job: Job[SensitivitySpec, SerialRobot]) -> SensitivityPrepared:
    """Check the job's resources again (command-line overrides change them: a problem they
    cause names the option) and solve its posture."""

    def error(name: str, problem: str, expected: str) -> PresetError:
        return PresetError(*option_or_key(job, name, "methods"), problem, expected)

    check_resources(error, job.spec, job.robot)
    return SensitivityPrepared(solve_posture(job))


@dataclass(frozen=True, kw_only=True)
class SensitivityResult(JobResult):
    """Indices of one job: one :class:`~planar_tui.sensitivity.results.Analysis` per method
    and speed, the robot's label, the solved posture and N per method; ``variances_Nm2``:
    per speed, each torque's variance over the first method's design (rows: uniform draws)."""

    robot_label: str
    posture: Posture
    analyses: list[Analysis]
    samples: Mapping[str, int]
    variances_Nm2: Mapping[float, tuple[float, ...]] = field(default_factory=dict)


def sample_sizes(spec: SensitivitySpec, num_vars: int) -> dict[str, int]:
    """N per method: the Sobol' base N, eFAST's (given, or matching the Sobol' cost), the
    PCE's model runs (given, or :func:`~planar_tui.sensitivity.pce.default_pce_samples`)."""
    from planar_tui.sensitivity.engine import default_efast_samples
    from planar_tui.sensitivity.pce import default_pce_samples

    efast = spec.efast_samples or default_efast_samples(spec.samples, num_vars)
    return {
        "sobol": spec.samples,
        "efast": efast,
        "pce": spec.pce_samples or default_pce_samples(num_vars),
    }


SensitivityJob = PreparedJob[SensitivitySpec, SerialRobot, SensitivityPrepared]


def run_sensitivity(job: SensitivityJob, progress: Progress) -> SensitivityResult:
    """Indices of every torque for every method and speed of one job (one posture), the job
    prepared (:func:`prepare_sensitivity`, done by the batch service).

    Progress goes through three stages (sampling, evaluation, analysis), each in chunks of
    well under :data:`~planar_tui.progress.CHECK_INTERVAL_S` (design chunks, row chunks of
    the design, one output column or one curve per worker), so a cancel raises
    :class:`~planar_tui.errors.Cancelled` within a fraction of a second.
    """
    import numpy as np

    from planar_tui.sensitivity.engine import (
        build_problem,
        evaluate,
        montecarlo_design,
        unit_design,
    )
    from planar_tui.sensitivity.path import (
        path_context,
        path_labels,
        path_outputs,
        path_tables,
        path_variances,
    )
    from planar_tui.sensitivity.pce import pce_unit_design
    from planar_tui.sensitivity.results import Analysis, csv_table, sensitivity_percent

    spec, robot, posture = job.spec, job.robot, job.prepared.posture
    problem = build_problem(
        robot, spec.tolerance_length_m, spec.tolerance_mass_kg, spec.inertia_tolerance_kgm2
    )
    sizes = sample_sizes(spec, problem.num_vars)
    progress.start(len(spec.methods), "sampling")
    designs = {}
    for method in spec.methods:
        if method == "pce":
            designs[method] = pce_unit_design(problem.num_vars, sizes[method], spec.seed)
            progress.advance(1.0, method)
        else:
            designs[method] = unit_design(
                method, problem.num_vars, sizes[method], spec.seed, progress
            )
    speeds = (0.0,) if spec.path is not None else spec.speeds_rad_s
    states = [(method, speed) for speed in speeds for method in spec.methods]
    n = robot.n_links
    alpha = np.full(n, spec.alpha_rad_s2)
    theta = np.array(posture.theta_rad)
    # eFAST's search curves are not independent robots: a path's torque variances (the
    # aggregation's weights) come from N Monte-Carlo rows of their own
    variance_outputs = {}
    if spec.path is not None and "efast" in spec.methods:
        progress.start(len(states) + 1, "evaluation")
        unit = montecarlo_design(problem.num_vars, sizes["efast"], spec.seed)
        variance_outputs["efast"] = path_outputs(problem, unit, robot, theta, spec.path, progress)
    else:
        progress.start(len(states), "evaluation")
    outputs = {}
    for method, speed in states:
        if spec.path is not None:
            outputs[method, speed] = path_outputs(
                problem, designs[method], robot, theta, spec.path, progress
            )
            continue
        omega = np.full(n, speed)
        outputs[method, speed] = evaluate(
            problem,
            designs[method],
            robot,
            theta,
            omega,
            alpha,
            progress,
            f"{method} {speed:g} rad/s",
        )
    speed_variances = (
        {}
        if spec.path is not None
        else {
            speed: tuple(float(v) for v in outputs[spec.methods[0], speed].var(axis=0, ddof=1))
            for speed in spec.speeds_rad_s
        }
    )
    progress.start(len(states), "analysis")
    analyses = []
    notes = []
    along: list[Analysis] = []
    variances = {}  # a path's torque variances over independent uniform runs, and their count
    for method, speed in states:
        values = outputs.pop((method, speed))
        if spec.path is not None:
            extra = variance_outputs.get(method)
            variances[method] = path_variances(method, values, extra, designs[method], n)
        indices, loo, note = analyse_outputs(
            job,
            problem,
            method,
            designs[method],
            values,
            progress,
            f"{method} {speed:g} rad/s",
        )
        notes += [f"{method} {speed:g} rad/s: {note}"] if note else []
        runs = len(designs[method])
        if spec.path is not None:
            along.append(
                Analysis(
                    method,
                    posture.label,
                    0.0,
                    problem.names,
                    indices,
                    sensitivity_percent(indices, "ST"),
                    runs=runs,
                    loo_error=loo,
                )
            )
            indices, loo = indices[:, : 2 * n], None if loo is None else loo[: 2 * n]
        percent = sensitivity_percent(indices, spec.percent_of)
        labels = path_labels(n) if spec.path is not None else ()
        context = "" if spec.path is None else path_context(posture.label, spec.path)
        analyses.append(
            Analysis(
                method,
                posture.label,
                speed,
                problem.names,
                indices,
                percent,
                labels,
                context,
                runs=runs,
                loo_error=loo,
            )
        )
    label = robot.label
    kappa = posture.condition_number
    sobol_conf = [float(a.indices[[1, 3]].max()) for a in analyses if a.method == "sobol"]
    loo = [float(a.loo_error.max()) for a in analyses if a.loo_error is not None]
    summary = (
        f"{label} {posture.label}"
        + (f" (κ = {kappa:.6g})" if math.isfinite(kappa) else "")
        + (
            f", {len(spec.speeds_rad_s)} speed(s), "
            if spec.path is None
            else f", {path_context(posture.label, spec.path)}, "
        )
        + ", ".join(f"{m} N={sizes[m]}" for m in spec.methods)
        + (f", max Sobol' CI ±{max(sobol_conf):.4f}" if sobol_conf else "")
        + (f", max PCE LOO error {max(loo):.2g}" if loo else "")
        + "".join(f"; {note}" for note in notes)
    )
    return SensitivityResult(
        table=csv_table(label, analyses),
        extra_tables={} if spec.path is None else path_tables(along, spec.path, n, variances),
        summary=summary,
        robot_label=label,
        posture=posture,
        analyses=analyses,
        samples=sizes,
        variances_Nm2=speed_variances,
    )


def path_outputs_files(job: Job[SensitivitySpec, SerialRobot]) -> dict[str, str]:
    """With a ``path``: its per-step indices beside the job's CSV (``-path.csv``) and the
    aggregated indices (``-path-aggregated.csv``)."""
    if job.spec.path is None:
        return {}
    stem = job.output[:-4] if job.output.lower().endswith(".csv") else job.output
    return {"path": f"{stem}-path.csv", "path_aggregated": f"{stem}-path-aggregated.csv"}


def analyse_outputs(
    job: SensitivityJob,
    problem: Any,
    method: str,
    unit: Any,
    outputs: Any,
    progress: Progress,
    detail: str,
) -> tuple[Any, Any, str]:
    """(4, n, D) indices of the torques ``outputs`` of the design ``unit``, the PCE's LOO
    error per torque (``None`` for Sobol', eFAST) and a note on dropped runs (``""``).
    Failed runs (non-finite torques) and a PCE whose LOO error exceeds
    ``pce_max_loo_error`` are a :class:`PresetError` naming the key to change."""
    from planar_tui.sensitivity.engine import analyse
    from planar_tui.sensitivity.failed_runs import FailedRuns, check_failed_runs
    from planar_tui.sensitivity.pce import PceError, job_indices

    spec = job.spec
    torques = [f"tau{i + 1}" for i in range(outputs.shape[1])]
    try:
        if method != "pce":
            check_failed_runs(outputs, unit, problem.names, 0.0, can_drop=False)
            indices = analyse(method, outputs, problem.num_vars, spec.seed, progress, detail)
            return indices, None, ""
        indices, loo, note = progress.wait_for(
            job_indices,
            unit,
            outputs,
            spec.seed,
            problem.names,
            torques,
            spec.pce_max_loo_error,
            spec.allow_failed_runs,
        )
        progress.advance(1.0, detail)
        return indices, loo, note
    except (PceError, FailedRuns) as error:
        raise PresetError(
            job.preset_path, f"{job.key}.{error.key}", error.problem, error.expected
        ) from None


def render_sensitivity(
    job: Job[SensitivitySpec, SerialRobot], result: SensitivityResult, console: Any
) -> None:
    """The CLI view of one job: its index tables fitted to the terminal width (percent
    view), and the stacked bars (Figs 5/6) when speeds are swept."""
    from planar_tui.sensitivity.bars import sensitivity_bars
    from planar_tui.sensitivity.tables import VIEWS, fit_tables

    analyses = result.analyses
    console.print(f"{result.robot_label}: {job.label}", style="bold", markup=False)
    console.print(fit_tables(analyses, VIEWS[0], console.width, job.spec.percent_of).renderable)
    if len({a.speed_rad_s for a in analyses}) > 1:
        console.print(sensitivity_bars(analyses, analyses[0].method))


def point_figures(
    job: Job[SensitivitySpec, SerialRobot], result: SensitivityResult
) -> dict[str, str | float]:
    """A sweep row's figures, per torque ``i`` (at each speed, suffixed ``_w2``, ``_w3`` …
    from the second on): the dominant parameter by the percent of the job's first method,
    its percent, the lengths' and the masses' shares (sums of their percents), the
    largest Sobol' 95 % half-width of ``S1`` and ``ST`` over the parameters (empty without
    Sobol') and its variance (N² m², without a ``path``); then the largest variance over
    the torques. With a ``path`` the outputs are ``tau{j}_peak`` and ``tau{j}_rms``
    instead."""
    method = job.spec.methods[0]
    figures: dict[str, str | float] = {}
    path = job.spec.path is not None
    n = job.robot.n_links
    for k, speed in enumerate((0.0,) if path else job.spec.speeds_rad_s, start=1):
        at = {a.method: a for a in result.analyses if a.speed_rad_s == speed}
        chosen, sobol = at[method], at.get("sobol")
        suffix = "" if k == 1 else f"_w{k}"
        names = chosen.names
        for i, percent in enumerate(chosen.percent, start=1):
            top = int(percent.argmax())
            out = f"tau{(i - 1) % n + 1}_{'peak' if i <= n else 'rms'}" if path else f"tau{i}"
            figures[f"{out}_dominant{suffix}"] = names[top]
            figures[f"{out}_dominant_percent{suffix}"] = float(percent[top])
            for group, prefix in (("lengths", "l"), ("masses", "m")):
                share = sum(
                    float(p)
                    for p, name in zip(percent, names, strict=True)
                    if name.startswith(prefix)
                )
                figures[f"{out}_{group}_percent{suffix}"] = share
            halfwidth = "" if sobol is None else float(sobol.indices[[1, 3], i - 1].max())
            figures[f"{out}_sobol_halfwidth_max{suffix}"] = halfwidth
            if not path:
                figures[f"{out}_variance_Nm2{suffix}"] = result.variances_Nm2[speed][i - 1]
        if not path:
            figures[f"tau_variance_max_Nm2{suffix}"] = max(result.variances_Nm2[speed])
    return figures


JOB_KIND = JobKind(
    name="sensitivity",
    robot_kind="robot",
    settings=SensitivitySpec,
    run=run_sensitivity,
    summary="Sobol'/eFAST/PCE sensitivity of the joint torques to lengths and masses",
    render=render_sensitivity,
    prepare=prepare_sensitivity,
    extra_outputs=path_outputs_files,
    point_figures=point_figures,
    command=Command(
        "sensitivity",
        "Sobol'/eFAST sensitivity of the joint torques of every sensitivity job; one CSV "
        "each.\n\nAn option that changes a job's setting is appended to the stem of the file "
        "the preset names (tiny-sensitivity--samples-512.csv); a name given with --out is kept.",
        options=uq.sampling_options(METHODS, "Sobol' base N (a power of two)"),
    ),
    tab=Tab(
        "Sensitivity",
        1,
        "planar_tui.app.widgets.sensitivity_pane:SensitivityPane",
        view="S1/ST/%",
        view_help="percent / S1 / ST / ± half-width",
    ),
    figure="planar_tui.figures.sensitivity:from_result",
    warmup="[sensitivity]\nsamples = 8\nefast_samples = 65\n",
    figure_names=figure_names,
    estimate=lambda job: resource_estimate(job.spec, job.robot),
    app_default={
        "posture": "singular",
        "speed_rad_s": 1.0,
        "tolerance_length_mm": 1.0,
        "tolerance_mass_g": 1.0,
        "methods": ["sobol", "efast"],
        "samples": 1024,
        "seed": 42,
        "output": "app-sensitivity.csv",
    },
)

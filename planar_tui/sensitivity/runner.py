"""The ``[sensitivity]`` job's runner, in stages as SALib separates them: the design
(the unit samples of every method), the evaluation (the torques of every design row at
every speed, or along the path) and the analysis (the indices, the tables, the summary);
:func:`run_sensitivity` composes them. Before it, :func:`prepare_sensitivity` checks the
job's resources again and solves its posture."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from planar_tui.dynamics.robot import SerialRobot
from planar_tui.errors import PresetError
from planar_tui.jobkind import Job, JobResult, PreparedJob, option_or_key
from planar_tui.progress import Progress
from planar_tui.sensitivity.path import (
    path_context,
    path_labels,
    path_outputs,
    path_tables,
    path_variances,
)
from planar_tui.sensitivity.spec import SensitivitySpec, check_resources, sample_sizes

if TYPE_CHECKING:
    import numpy as np

    from planar_tui.sensitivity.postures import Posture
    from planar_tui.sensitivity.results import Analysis


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


SensitivityJob = PreparedJob[SensitivitySpec, SerialRobot, SensitivityPrepared]


@dataclass(frozen=True)
class SensitivityDesign:
    """What :func:`design_sensitivity` draws: the SALib ``problem``, N per method
    (``sizes``), each method's unit design (``units``: rows in [0, 1)^D) and the
    (method, speed) states to evaluate, speed by speed (one speed, 0, along a path)."""

    problem: Any
    sizes: dict[str, int]
    units: dict[str, np.ndarray]
    states: list[tuple[str, float]]


@dataclass(frozen=True)
class SensitivityOutputs:
    """What :func:`evaluate_sensitivity` computes: the torques of every state's design
    rows (``outputs``, by (method, speed); the analysis pops them as it goes) and, along a
    path with eFAST, the torques of N Monte-Carlo rows of their own (``variance_outputs``:
    eFAST's search curves are not independent robots)."""

    outputs: dict[tuple[str, float], np.ndarray]
    variance_outputs: dict[str, np.ndarray]


def design_sensitivity(job: SensitivityJob, progress: Progress) -> SensitivityDesign:
    """Sampling: the unit design of every method (SALib's Sobol'/eFAST samples, cached; the
    PCE's own), in chunks the progress can cancel between."""
    from planar_tui.sensitivity.engine import build_problem, unit_design
    from planar_tui.sensitivity.pce import pce_unit_design

    spec, robot = job.spec, job.robot
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
    return SensitivityDesign(problem, sizes, designs, states)


def evaluate_sensitivity(
    job: SensitivityJob, design: SensitivityDesign, progress: Progress
) -> SensitivityOutputs:
    """Evaluation: the joint torques of every design row, by batched inverse dynamics at the
    job's posture and each speed, or at every step of its path."""
    import numpy as np

    from planar_tui.sensitivity.engine import evaluate, montecarlo_design

    spec, robot, posture = job.spec, job.robot, job.prepared.posture
    problem, designs, states = design.problem, design.units, design.states
    n = robot.n_links
    alpha = np.full(n, spec.alpha_rad_s2)
    theta = np.array(posture.theta_rad)
    # eFAST's search curves are not independent robots: a path's torque variances (the
    # aggregation's weights) come from N Monte-Carlo rows of their own
    variance_outputs = {}
    if spec.path is not None and "efast" in spec.methods:
        progress.start(len(states) + 1, "evaluation")
        unit = montecarlo_design(problem.num_vars, design.sizes["efast"], spec.seed)
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
    return SensitivityOutputs(outputs, variance_outputs)


def analyse_sensitivity(
    job: SensitivityJob,
    design: SensitivityDesign,
    evaluated: SensitivityOutputs,
    progress: Progress,
) -> SensitivityResult:
    """Analysis: the indices of every state (:func:`analyse_outputs`), the torques'
    variances per speed, a path's per-step and aggregated tables, and the summary."""
    from planar_tui.sensitivity.results import Analysis, csv_table, sensitivity_percent

    spec, robot, posture = job.spec, job.robot, job.prepared.posture
    problem, designs, states, outputs = (
        design.problem,
        design.units,
        design.states,
        evaluated.outputs,
    )
    n = robot.n_links
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
            extra = evaluated.variance_outputs.get(method)
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
    return SensitivityResult(
        table=csv_table(robot.label, analyses),
        extra_tables={} if spec.path is None else path_tables(along, spec.path, n, variances),
        summary=_summary(job, analyses, design.sizes, notes),
        robot_label=robot.label,
        posture=posture,
        analyses=analyses,
        samples=design.sizes,
        variances_Nm2=speed_variances,
    )


def _summary(
    job: SensitivityJob, analyses: list[Analysis], sizes: Mapping[str, int], notes: list[str]
) -> str:
    """The job's one line: robot, posture (κ), speeds or path, N per method, the largest
    Sobol' confidence half-width and PCE LOO error, and the analyses' notes."""
    spec, posture = job.spec, job.prepared.posture
    kappa = posture.condition_number
    sobol_conf = [float(a.indices[[1, 3]].max()) for a in analyses if a.method == "sobol"]
    loo = [float(a.loo_error.max()) for a in analyses if a.loo_error is not None]
    return (
        f"{job.robot.label} {posture.label}"
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


def run_sensitivity(job: SensitivityJob, progress: Progress) -> SensitivityResult:
    """Indices of every torque for every method and speed of one job (one posture), the job
    prepared (:func:`prepare_sensitivity`, done by the batch service): design, evaluate,
    analyse.

    Progress goes through the three stages (sampling, evaluation, analysis), each in chunks
    of well under :data:`~planar_tui.progress.CHECK_INTERVAL_S` (design chunks, row chunks
    of the design, one output column or one curve per worker), so a cancel raises
    :class:`~planar_tui.errors.Cancelled` within a fraction of a second.
    """
    design = design_sensitivity(job, progress)
    evaluated = evaluate_sensitivity(job, design, progress)
    return analyse_sensitivity(job, design, evaluated, progress)


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
    from planar_tui.sensitivity.pce import PceError
    from planar_tui.sensitivity.pce_analysis import job_indices

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

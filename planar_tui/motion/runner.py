"""The ``[motion_uncertainty]`` job's runner, in stages as SALib separates them: the
design (the sampled robots, on the job's device), the evaluation (every robot integrated,
its outputs kept at the recorded and analysed steps) and the analysis (the band, the
indices at the times of ``at_s`` and along the trajectory, the summary);
:func:`run_motion` composes them. Before it, :func:`prepare_motion` checks the job's
resources again and chooses its device."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from planar_tui.csvio import CsvTable
from planar_tui.dynamics.robot import SerialRobot
from planar_tui.errors import PresetError
from planar_tui.jobkind import JobResult, PreparedJob, option_or_key
from planar_tui.motion.device import resolve
from planar_tui.motion.spec import MotionJob, MotionSpec, check_resources, extra_band_note
from planar_tui.progress import Progress

if TYPE_CHECKING:
    import numpy as np

    from planar_tui.sensitivity.results import Analysis


@dataclass(frozen=True)
class MotionPrepared:
    """What :func:`prepare_motion` resolves: the device the robots are integrated on
    (``cpu`` or ``cuda``) and what the summary says about it (``device_note``)."""

    device: str
    device_note: str


def _checked_device(job: MotionJob) -> MotionPrepared:
    """The job's resources checked again (overrides change them) and its device chosen
    (:func:`~planar_tui.motion.device.resolve`); ``cuda`` without a usable GPU is a
    :class:`PresetError` on ``device``.

    A problem with a value a command-line option set names the option (``command line:
    --device``), not the preset's key: the device when ``--device`` set it, the resources
    (checked on the preset's values when it was read) when ``--samples`` or ``--method``
    changed them."""

    def error(name: str, problem: str, expected: str) -> PresetError:
        causes = ("methods",) if name == "samples" else ()
        return PresetError(*option_or_key(job, name, *causes), problem, expected)

    check_resources(error, job.spec, job.robot)
    used, note = resolve(job.spec.device)
    if used is None:
        raise error("device", note, '"cpu" or "auto", or a machine with a usable CUDA GPU')
    return MotionPrepared(used, note)


def check_motion(job: MotionJob) -> None:
    """Refuse a job that cannot run here (resources, an unusable ``cuda`` device) without
    computing anything: the job kind's ``check``, run on every sweep point."""
    _checked_device(job)


def prepare_motion(job: MotionJob) -> MotionPrepared:
    """Check the job's resources again (overrides change them: a problem they cause names
    the option) and choose its device: ``cuda`` without a usable GPU is a
    :class:`PresetError` on ``device`` (or ``--device``)."""
    return _checked_device(job)


@dataclass(frozen=True, kw_only=True)
class MotionResult(JobResult):
    """The band and the indices of one job.

    ``t_s`` (R,) recorded times; ``band`` (R, 5, n_out): mean, std, p5, p50, p95;
    ``names`` the outputs' column stems; ``analyses``: one
    :class:`~planar_tui.sensitivity.results.Analysis` per time and index method;
    ``notes``: where the band's extra Monte-Carlo robots come from (eFAST alone), outputs
    without variance (indices 0); ``device`` what ran (and why,
    when ``auto`` fell back to the CPU); ``design`` (:class:`~planar_tui.motion.engine.
    Design`) and ``at_outputs`` ({step: (S, n_out)}, every robot's outputs at the times of
    ``at_s``): the model runs, for the SALib hand-off (``--export-problem``)."""

    robot_label: str
    t_s: np.ndarray
    band: np.ndarray
    names: tuple[str, ...]
    analyses: list[Analysis]
    notes: tuple[str, ...]
    device: str
    robots: int
    design: Any = None
    at_outputs: Any = None


MotionRun = PreparedJob[MotionSpec, SerialRobot, MotionPrepared]


@dataclass(frozen=True)
class MotionDesign:
    """What :func:`design_motion` samples: the SALib ``problem``, the robots' unit
    ``design`` (:class:`~planar_tui.motion.engine.Design`), the sampled robots ready to
    integrate on the job's device (``robots``) and their lengths (``lengths_s``, (S, n))."""

    problem: Any
    design: Any
    robots: Any
    lengths_s: np.ndarray


@dataclass(frozen=True)
class MotionOutputs:
    """What :func:`evaluate_motion` keeps of the integration: the output ``names``, the
    ``band`` (R, 5, n_out) at the recorded steps, every robot's outputs at the steps of
    ``at_s`` (``at_outputs``), the PCE robots' outputs at every stop (``trajectory``),
    Sobol'/eFAST point indices (``every``) and the variances that weight them
    (``variances``) at every stop, by method, and all robots' outputs at a stop where a
    Sobol'/eFAST robot failed (``failed``)."""

    names: tuple[str, ...]
    band: np.ndarray
    at_outputs: dict[int, np.ndarray]
    trajectory: dict[int, np.ndarray]
    every: dict[str, dict[int, np.ndarray]]
    variances: dict[str, dict[int, np.ndarray]]
    failed: dict[int, np.ndarray]


def index_methods(spec: MotionSpec) -> list[str]:
    """The methods whose indices come at every stop (Sobol', eFAST), in the job's order."""
    return [m for m in spec.methods if m not in ("montecarlo", "pce")]


def design_motion(job: MotionRun, progress: Progress) -> MotionDesign:
    """Sampling: the robots of every method's design (eFAST alone: N Monte-Carlo robots
    more for the band), their parameters and initial states on the job's device."""
    import numpy as np

    from planar_tui.motion import engine
    from planar_tui.sensitivity.engine import build_problem

    spec, robot, device = job.spec, job.robot, job.prepared
    inertia_tol = spec.tolerance_inertia_kgm2
    problem = build_problem(
        robot, spec.tolerance_length_mm * 1e-3, spec.tolerance_mass_g * 1e-3, inertia_tol
    )
    lengths, masses, inertias = robot.arrays()
    rod = inertias == masses * lengths * lengths / 12.0
    progress.start(len(engine.design_methods(spec.methods)), "sampling")
    design = engine.build_design(
        spec.methods,
        problem.num_vars,
        spec.samples,
        spec.seed,
        progress,
        spec.pce_robots(problem.num_vars),
    )
    robots, params = engine.make_robots(
        device.device,
        problem,
        design,
        rod,
        robot,
        np.radians(np.array(spec.theta0_deg, dtype=np.float64)),
        np.radians(np.array(spec.omega0_deg_s, dtype=np.float64)),
        np.array(spec.torques_Nm, dtype=np.float64),
    )
    return MotionDesign(problem, design, robots, params[:, 0, :])


def evaluate_motion(job: MotionRun, sampled: MotionDesign, progress: Progress) -> MotionOutputs:
    """Integrating: every robot by RK4 under the job's torques; at each stop (a recorded
    step, a step of ``at_s``) the outputs of every robot give the band's statistics, the
    outputs kept for the analysis, and Sobol'/eFAST's point indices and variances."""
    import numpy as np

    from planar_tui.motion import engine
    from planar_tui.sensitivity.engine import point_indices

    spec, robot, device = job.spec, job.robot, job.prepared
    problem, design, lengths_s = sampled.problem, sampled.design, sampled.lengths_s
    band_rows = design.band_rows()
    record_steps = spec.record_steps()
    at_steps = spec.at_steps()
    stops = sorted(set(record_steps) | set(at_steps))
    records = {step: i for i, step in enumerate(record_steps)}
    names = engine.output_names(robot.n_links, spec.outputs)
    band = np.empty((len(record_steps), 5, len(names)))
    at_outputs = {}
    pce_rows = design.rows.get("pce")
    trajectory = {}  # the PCE robots' outputs at every stop
    methods = index_methods(spec)
    # Sobol'/eFAST at every stop: point indices, and the variances (aggregation weights)
    # over independent robots: Sobol's A and B rows, the band's robots for eFAST
    every: dict[str, dict[int, np.ndarray]] = {m: {} for m in methods}
    variances: dict[str, dict[int, np.ndarray]] = {m: {} for m in methods}
    weight_rows = {m: design.independent_rows(m) if m == "sobol" else band_rows for m in methods}
    failed = {}  # all robots' outputs at a stop where a Sobol'/eFAST robot failed

    def on_stop(step: int, angles) -> None:
        values = engine.take_outputs(lengths_s, angles, spec.outputs)  # every robot's, (S, M)
        if step in records:
            band[records[step]] = engine.band_statistics(values[band_rows])
        if step in at_steps:
            at_outputs[step] = values
        if pce_rows is not None:
            trajectory[step] = values[pce_rows]
        for method in methods:
            if not np.isfinite(values[design.rows[method]]).all():
                failed[step] = values
            every[method][step] = point_indices(
                method, values[design.rows[method]], problem.num_vars
            )
            variances[method][step] = values[weight_rows[method]].var(axis=0)

    total = design.samples * spec.n_steps
    progress.start(total, "integrating", f"{design.samples} robots on {device.device_note}")
    engine.integrate(sampled.robots, spec.step_s, stops, on_stop, progress)
    return MotionOutputs(names, band, at_outputs, trajectory, every, variances, failed)


def analyse_motion(
    job: MotionRun, sampled: MotionDesign, evaluated: MotionOutputs, progress: Progress
) -> MotionResult:
    """Analysis: failed Sobol'/eFAST robots refused, the indices at the times of ``at_s``
    and along the trajectory (Sobol'/eFAST from their point indices, the PCE's one
    expansion per output), the band's and the indices' tables and the summary."""
    import numpy as np

    from planar_tui.motion import engine
    from planar_tui.motion.results import (
        analyse_times,
        band_table,
        index_trajectories,
        indices_table,
    )
    from planar_tui.sensitivity.results import AGGREGATED_HEADER

    spec, robot, device = job.spec, job.robot, job.prepared
    problem, design = sampled.problem, sampled.design
    names, band, at_outputs = evaluated.names, evaluated.band, evaluated.at_outputs
    at_steps = spec.at_steps()
    pce_rows = design.rows.get("pce")
    methods = index_methods(spec)
    progress.start(max(1, len(methods) * len(at_steps) + (pce_rows is not None)), "analysis")
    labels = engine.output_labels(names)
    for method in methods:
        check_failed(job, {**evaluated.failed, **at_outputs}, design, method, problem)
    analyses, notes = analyse_times(design, at_outputs, spec, problem, labels, methods, progress)
    time_analyses, aggregated = index_trajectories(
        design, evaluated.every, evaluated.variances, analyses, spec, problem, labels
    )
    if pce_rows is not None:
        pce_analyses, pce_aggregated, pce_notes = analyse_trajectory(
            job, design.unit[pce_rows], evaluated.trajectory, problem, labels, progress
        )
        at_times = {step * spec.step_s for step in at_steps}
        analyses += [a for a in pce_analyses if a.speed_rad_s in at_times]
        analyses.sort(key=lambda a: a.speed_rad_s)  # stable: method order within a time
        time_analyses += pce_analyses
        aggregated += pce_aggregated
        notes = (*notes, *pce_notes)
    band_note = extra_band_note(spec)
    if band_note:
        notes = (band_note, *notes)
    t_s = np.array(spec.record_steps()) * spec.step_s
    last = band[-1]
    summary = (
        f"{robot.label}: {design.samples} robots × {spec.n_steps} steps on {device.device_note}; "
        + ", ".join(
            f"{label} {m:.4g}±{s:.2g}" for label, m, s in zip(labels, last[0], last[1], strict=True)
        )
        + f" at t = {t_s[-1]:g} s"
        + (f"; band from {spec.samples} extra Monte-Carlo robots" if band_note else "")
    )
    extra_tables = {}
    if analyses:
        order = {m: i for i, m in enumerate([*methods, "pce"])}  # within a time
        by_time = sorted(time_analyses, key=lambda a: (a.speed_rad_s, order[a.method]))
        extra_tables["indices"] = indices_table(by_time, names)
        named = dict(zip(labels, names, strict=True))  # the CSVs' ASCII names, as the indices'
        ascii_rows = [(named.get(row[0], row[0]), *row[1:]) for row in aggregated]
        extra_tables["aggregated"] = CsvTable(AGGREGATED_HEADER, ascii_rows)
    return MotionResult(
        table=band_table(t_s, band, names),
        extra_tables=extra_tables,
        summary=summary,
        robot_label=robot.label,
        t_s=t_s,
        band=band,
        names=names,
        analyses=analyses,
        notes=notes,
        device=device.device_note,
        robots=design.samples,
        design=design,
        at_outputs=at_outputs,
    )


def run_motion(job: MotionRun, progress: Progress) -> MotionResult:
    """Design, evaluate, analyse (three stages of progress: sampling, integrating,
    analysis): the band and the indices of one job (see :mod:`planar_tui.motion.engine`)."""
    sampled = design_motion(job, progress)
    evaluated = evaluate_motion(job, sampled, progress)
    return analyse_motion(job, sampled, evaluated, progress)


def check_failed(
    job: MotionRun,
    at_outputs,
    design,
    method: str,
    problem,
) -> None:
    """Sobol' and eFAST cannot drop robots: any non-finite output of ``method``'s robots
    at an ``at_s`` time fails the job (a :class:`PresetError` naming the corner)."""
    import numpy as np

    from planar_tui.sensitivity.failed_runs import FailedRuns, check_failed_runs

    rows = design.rows[method]
    outputs = np.stack([at_outputs[step][rows] for step in sorted(at_outputs)], axis=1)
    try:
        check_failed_runs(outputs, design.unit[rows], problem.names, 0.0, can_drop=False)
    except FailedRuns as error:
        raise PresetError(
            job.preset_path, f"{job.key}.methods", error.problem, error.expected
        ) from None


def analyse_trajectory(job, unit, trajectory, problem, labels, progress):
    """``(analyses, aggregated table, notes)`` of the PCE robots' outputs at every stop
    (``trajectory``: {step: (S, M)}): failed robots checked (dropped when
    ``allow_failed_runs`` allows), one expansion per output over its times
    (:func:`~planar_tui.sensitivity.pce_analysis.trajectory_indices`), its LOO error checked; an
    :class:`~planar_tui.sensitivity.results.Analysis` per time and the aggregated indices
    (Gamboa et al. 2014) of each output and of all of them."""
    import numpy as np

    from planar_tui.motion.results import aggregate_rows
    from planar_tui.sensitivity.failed_runs import FailedRuns, check_failed_runs
    from planar_tui.sensitivity.pce import PceError
    from planar_tui.sensitivity.pce_analysis import check_loo, trajectory_indices
    from planar_tui.sensitivity.results import Analysis, sensitivity_percent

    spec = job.spec
    steps = sorted(trajectory)
    outputs = np.stack([trajectory[step] for step in steps], axis=1)  # (S, K, M)
    times = [step * spec.step_s for step in steps]
    try:
        keep, note = check_failed_runs(
            outputs, unit, problem.names, spec.allow_failed_runs, can_drop=True
        )
        result = progress.wait_for(trajectory_indices, unit[keep], outputs[keep], spec.seed)
        names = [f"{label} at t = {t:g} s" for t in times for label in labels]
        check_loo([result], names, spec.pce_max_loo_error, len(unit))
    except (PceError, FailedRuns) as error:
        raise PresetError(
            job.preset_path, f"{job.key}.{error.key}", error.problem, error.expected
        ) from None
    progress.advance(1.0, "pce")
    analyses = []
    for k, t_s in enumerate(times):
        indices = result.indices[:, k]
        analyses.append(
            Analysis(
                "pce",
                "",
                t_s,
                problem.names,
                indices,
                sensitivity_percent(indices, "ST"),
                tuple(labels),
                f"t = {t_s:g} s",
                runs=len(unit),
                loo_error=result.loo_error[k],
                defined=np.ptp(outputs[keep][:, k], axis=0) > 0,
            )
        )
    rows = aggregate_rows(
        labels, problem.names, "pce", result.aggregated, result.overall, len(unit)
    )
    return analyses, rows, ((note,) if note else ())

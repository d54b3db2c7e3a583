"""The ``[motion_uncertainty]`` job: how tolerances on lengths and masses move the robot.

Every link length and mass (optionally inertia) is uniform on ``nominal ± tolerance`` (as
in ``[sensitivity]``); every sampled robot is integrated by RK4 under the constant torques
(as in ``[simulate]``). Results: the band (mean, standard deviation, 5/50/95 % percentiles of
every output at every recorded step, over independent uniform robots: the Monte-Carlo or
Sobol' A/B robots, or N extra Monte-Carlo robots when eFAST runs alone), Sobol'/eFAST/PCE
indices of every output at every recorded time (Sobol'/eFAST's confidence intervals at the
times ``at_s`` only) and aggregated over each trajectory, a Table-4-shaped table per time
of ``at_s``. Details: ``docs/motion.md``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from planar_tui import uq
from planar_tui.dynamics.robot import SerialRobot, rk4_step_seconds
from planar_tui.dynamics.simulate import RunSettings
from planar_tui.errors import PresetError
from planar_tui.jobkind import (
    Command,
    Job,
    JobKind,
    JobResult,
    Option,
    PreparedJob,
    Tab,
    option_or_key,
)
from planar_tui.limits import memory_problem, time_problem
from planar_tui.motion.device import DEVICES
from planar_tui.progress import Progress
from planar_tui.schema import (
    TableReader,
    integer,
    number,
    plot_setting,
    relative_path,
    setting,
    shown,
    string,
)

if TYPE_CHECKING:
    import numpy as np

    from planar_tui.sensitivity.results import Analysis

METHODS = ("montecarlo", "sobol", "efast", "pce")
OUTPUTS = ("angles", "tip")
#: Recorded band rows by default (``every`` = steps / this, at least 1).
DEFAULT_RECORDS = 100


def _read_times(reader: TableReader, name, default, robot, values) -> tuple[float, ...] | None:
    """A time or a list of times in (0, duration_s], sorted, duplicates dropped."""
    if not reader.has(name):
        return None
    duration_s = values["duration_s"]
    expected = f"a number or a list of numbers in (0, duration_s = {duration_s:g} s]"
    raw = reader.raw(name)
    items, verb = (raw, "has") if isinstance(raw, list) else ([raw], "is")
    if not items:
        raise reader.error(name, "is empty", expected)
    for item in items:
        if isinstance(item, bool) or not isinstance(item, int | float):
            raise reader.error(name, f"{verb} {shown(item)}", expected)
        if not 0 < item <= duration_s:  # also NaN, ±inf; no float() of a huge integer
            raise reader.error(name, f"{verb} {shown(item)} s", expected)
    return tuple(sorted({float(t_s) for t_s in items}))


@dataclass(frozen=True, kw_only=True)
class MotionSpec(RunSettings):
    """Settings of one motion uncertainty job (see ``docs/motion.md``).

    The device a job runs on is chosen by :func:`prepare_motion`
    (:class:`MotionPrepared`); the indices CSV's name by :func:`indices_file`.
    """

    every: int | None = setting(
        integer(minimum=1),
        default=None,
        default_doc="steps / 100",
        type_doc="integer ≥ 1",
        doc="record the band every k-th step (t = 0 and the end always)",
    )
    tolerance_length_mm: float = uq.tolerance_setting("mm", "half-width of every length's range")
    tolerance_mass_g: float = uq.tolerance_setting("g", "half-width of every mass's range")
    tolerance_inertia_kgm2: float | None = setting(
        number(positive=True),
        default=None,
        default_doc="(none: inertias fixed)",
        type_doc="0 < number < smallest inertia",
        doc="half-width of every inertia's range; makes the inertias inputs. Without it a "
        "link whose inertia is `m l²/12` (the default) keeps `m l²/12` of its sampled "
        "mass and length, any other keeps its value",
    )
    methods: tuple[str, ...] = uq.methods_setting(
        METHODS,
        default=("montecarlo", "sobol"),
        doc="Monte Carlo (band), Sobol' and eFAST (SALib's designs: indices at every recorded "
        "time, confidence intervals at `at_s`), pce (polynomial chaos: indices and intervals "
        "at every recorded time); every index method also over the trajectory; eFAST alone "
        "adds N Monte-Carlo robots for the band",
    )
    samples: int = setting(
        integer(minimum=2),
        default=1024,
        type_doc="integer ≥ 2 (Sobol': power of two ≥ 8; eFAST: > 64)",
        doc="Monte Carlo: N robots; Sobol': base N (N·(D+2) robots, D inputs); eFAST: N per "
        "input (N·D robots, and N Monte-Carlo robots for the band without montecarlo or sobol)",
    )
    pce_samples: int | None = uq.pce_samples_setting("robots")
    pce_max_loo_error: float = uq.pce_max_loo_setting(
        "largest accepted PCE leave-one-out error of any output at any recorded time",
    )
    allow_failed_runs: float = uq.allow_failed_runs_setting(
        "fraction of PCE robots that may fail (a non-finite output: a diverged "
        "simulation) and be dropped from the fit; any failure fails Sobol' and eFAST",
    )
    seed: int = uq.seed_setting("seed of sampling and bootstrap")
    at_s: tuple[float, ...] | None = setting(
        _read_times,
        default=None,
        default_doc="`duration_s`",
        type_doc="number or list of numbers in (0, `duration_s`]",
        doc="times of the terminal tables and of Sobol'/eFAST's confidence intervals "
        "(rounded to a step)",
    )
    outputs: tuple[str, ...] = setting(
        uq.read_choices(OUTPUTS),
        default=OUTPUTS,
        default_doc="both",
        type_doc='`"angles"`, `"tip"` or a list of them',
        doc="relative joint angles θ1…θn (rad) and/or the tip's x, y (m)",
    )
    device: str = setting(
        string(choices=DEVICES),
        default="cpu",
        type_doc='`"cpu"`, `"cuda"` or `"auto"`',
        doc="where the robots are integrated (`auto`: the GPU when usable, else the CPU)",
    )
    indices_output: str | None = setting(
        relative_path(),
        default=None,
        default_doc="`output` with `-indices` before `.csv`",
        type_doc="relative path",
        doc="CSV file of the indices (with `sobol` or `efast`)",
    )
    plot: str | None = plot_setting()

    @staticmethod
    def check(values: dict[str, Any], reader: TableReader, robot: SerialRobot) -> dict[str, Any]:
        """Step within the duration, tolerances below the nominal values, sample sizes
        the methods accept, and the run within the time and memory limits."""
        RunSettings.check_step(values, reader)
        uq.check_tolerances(values, reader, robot)
        spec = MotionSpec(**values)
        uq.check_samples(reader.error, spec.methods, spec.sample_keys())
        check_resources(reader.error, spec, robot)
        return values

    def sample_keys(self) -> uq.SampleSizes:
        """Every method's sample count is ``samples``, the PCE's ``pce_samples``."""
        return {
            **dict.fromkeys(METHODS, ("samples", self.samples)),
            "pce": ("pce_samples", self.pce_samples),
        }

    def pce_robots(self, num_vars: int) -> int:
        """The PCE's robots: ``pce_samples``, else ``max(128, 64 D)``."""
        from planar_tui.sensitivity.pce import default_pce_samples

        return self.pce_samples or default_pce_samples(num_vars)

    @property
    def record_every(self) -> int:
        return self.every or max(1, self.n_steps // DEFAULT_RECORDS)

    def at_steps(self) -> tuple[int, ...]:
        """The global step indices of ``at_s`` (the last step by default)."""
        if self.at_s is None:
            return (self.n_steps,)
        return tuple(sorted({min(self.n_steps, max(1, round(t / self.step_s))) for t in self.at_s}))

    def record_steps(self) -> tuple[int, ...]:
        """Steps of the band rows: 0, every, 2·every … and the last."""
        steps = set(range(0, self.n_steps + 1, self.record_every)) | {self.n_steps}
        return tuple(sorted(steps))


MotionJob = Job[MotionSpec, SerialRobot]


def indices_file(job: MotionJob) -> str:
    """The indices CSV's name: ``indices_output``, else ``OUTPUT-indices.csv`` beside the
    job's ``output``."""
    if job.spec.indices_output:
        return job.spec.indices_output
    stem = job.output[:-4] if job.output.lower().endswith(".csv") else job.output
    return f"{stem}-indices.csv"


def extra_outputs(job: MotionJob) -> dict[str, str]:
    """The indices CSV when an index method runs, and the aggregated indices' CSV beside
    it (``-indices`` → ``-aggregated``)."""
    files = {}
    if any(uq.METHODS[method].indices for method in job.spec.methods):
        files["indices"] = indices_file(job)
        stem = (
            files["indices"][:-4] if files["indices"].lower().endswith(".csv") else files["indices"]
        )
        stem = stem[: -len("-indices")] if stem.endswith("-indices") else stem
        files["aggregated"] = f"{stem}-aggregated.csv"
    return files


def check_failed(
    job: PreparedJob[MotionSpec, SerialRobot, MotionPrepared],
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
    (:func:`~planar_tui.sensitivity.pce.trajectory_indices`), its LOO error checked; an
    :class:`~planar_tui.sensitivity.results.Analysis` per time and the aggregated indices
    (Gamboa et al. 2014) of each output and of all of them."""
    import numpy as np

    from planar_tui.motion.results import aggregate_rows
    from planar_tui.sensitivity.failed_runs import FailedRuns, check_failed_runs
    from planar_tui.sensitivity.pce import PceError, check_loo, trajectory_indices
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


def num_inputs(spec: MotionSpec, robot: SerialRobot) -> int:
    return (3 if spec.tolerance_inertia_kgm2 is not None else 2) * robot.n_links


def robot_count(spec: MotionSpec, robot: SerialRobot) -> int:
    """Robots integrated: N (Monte Carlo) + N (D + 2) (Sobol') + N D (eFAST), over the
    designs of :func:`~planar_tui.motion.engine.design_methods` (eFAST alone: N more
    Monte-Carlo robots for the band)."""
    from planar_tui.motion.engine import design_methods

    d = num_inputs(spec, robot)
    return sum(
        spec.pce_robots(d) if m == "pce" else uq.design_rows(m, d, spec.samples)
        for m in design_methods(spec.methods)
    )


def extra_band_note(spec: MotionSpec) -> str:
    """What the job says when its band comes from extra Monte-Carlo robots (eFAST alone),
    else ``""`` (:func:`~planar_tui.motion.engine.design_methods` adds none)."""
    from planar_tui.motion.engine import design_methods

    if design_methods(spec.methods) == tuple(spec.methods):
        return ""
    return (
        f"band from {spec.samples} extra Monte-Carlo robots (seed {spec.seed}) beside eFAST's: "
        "eFAST's search curves correlate the inputs, its robots are not independent draws"
    )


def resource_estimate(spec: MotionSpec, robot: SerialRobot) -> tuple[float, float]:
    """``(memory_bytes, seconds)``: the robots' states and parameters, the outputs at
    ``at_s`` and the band robots' outputs; robots × steps × one RK4 step."""
    robots = robot_count(spec, robot)
    n = robot.n_links
    seconds = robots * spec.n_steps * rk4_step_seconds(n)
    n_out = (n if "angles" in spec.outputs else 0) + (2 if "tip" in spec.outputs else 0)
    at = 1 if spec.at_s is None else len(spec.at_s)
    records = spec.n_steps // spec.record_every + 2
    memory = robots * (num_inputs(spec, robot) + 8 * n + n * n + at * n_out) * 8.0
    memory += records * 5 * n_out * 8.0
    return memory, seconds


def check_resources(error: uq.ErrorFactory, spec: MotionSpec, robot: SerialRobot) -> None:
    """Refuse a job whose estimated time (robots × steps × one RK4 step) or memory (the
    robots' states and parameters, the outputs at ``at_s``, the band robots' outputs)
    exceeds :mod:`planar_tui.limits`."""
    memory, seconds = resource_estimate(spec, robot)
    problem = time_problem(seconds) or memory_problem(memory)
    if problem is not None:
        raise error(
            "samples",
            f"{robot_count(spec, robot)} robots of {robot.n_links} links × {spec.n_steps} "
            f"steps: {problem}",
            "fewer samples, a shorter duration_s or a longer step_s",
        )


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
    from planar_tui.motion.device import resolve

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


def run_motion(
    job: PreparedJob[MotionSpec, SerialRobot, MotionPrepared], progress: Progress
) -> MotionResult:
    """Sample, integrate every robot (three stages: sampling, integrating, analysis), then
    the band and the indices (see :mod:`planar_tui.motion.engine`)."""
    import numpy as np

    from planar_tui.csvio import CsvTable
    from planar_tui.motion import engine
    from planar_tui.motion.results import (
        analyse_times,
        band_table,
        index_trajectories,
        indices_table,
    )
    from planar_tui.sensitivity.engine import point_indices
    from planar_tui.sensitivity.results import AGGREGATED_HEADER

    spec, robot, device = job.spec, job.robot, job.prepared
    from planar_tui.sensitivity.engine import build_problem

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
    lengths_s = params[:, 0, :]
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
    index_methods = [m for m in spec.methods if m not in ("montecarlo", "pce")]
    # Sobol'/eFAST at every stop: point indices, and the variances (aggregation weights)
    # over independent robots: Sobol's A and B rows, the band's robots for eFAST
    every: dict[str, dict[int, np.ndarray]] = {m: {} for m in index_methods}
    variances: dict[str, dict[int, np.ndarray]] = {m: {} for m in index_methods}
    weight_rows = {
        m: design.independent_rows(m) if m == "sobol" else band_rows for m in index_methods
    }
    failed = {}  # all robots' outputs at a stop where a Sobol'/eFAST robot failed

    def on_stop(step: int, angles) -> None:
        values = engine.take_outputs(lengths_s, angles, spec.outputs)  # every robot's, (S, M)
        if step in records:
            band[records[step]] = engine.band_statistics(values[band_rows])
        if step in at_steps:
            at_outputs[step] = values
        if pce_rows is not None:
            trajectory[step] = values[pce_rows]
        for method in index_methods:
            if not np.isfinite(values[design.rows[method]]).all():
                failed[step] = values
            every[method][step] = point_indices(
                method, values[design.rows[method]], problem.num_vars
            )
            variances[method][step] = values[weight_rows[method]].var(axis=0)

    total = design.samples * spec.n_steps
    progress.start(total, "integrating", f"{design.samples} robots on {device.device_note}")
    engine.integrate(robots, spec.step_s, stops, on_stop, progress)
    progress.start(max(1, len(index_methods) * len(at_steps) + (pce_rows is not None)), "analysis")
    labels = engine.output_labels(names)
    for method in index_methods:
        check_failed(job, {**failed, **at_outputs}, design, method, problem)
    analyses, notes = analyse_times(
        design, at_outputs, spec, problem, labels, index_methods, progress
    )
    time_analyses, aggregated = index_trajectories(
        design, every, variances, analyses, spec, problem, labels
    )
    if pce_rows is not None:
        pce_analyses, pce_aggregated, pce_notes = analyse_trajectory(
            job, design.unit[pce_rows], trajectory, problem, labels, progress
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
    t_s = np.array(record_steps) * spec.step_s
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
        order = {m: i for i, m in enumerate([*index_methods, "pce"])}  # within a time
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


def render_motion(job: MotionJob, result: MotionResult, console: Any) -> None:
    """The CLI view: the band at the end and a Table-4-shaped table per time."""
    from planar_tui.motion.results import render

    render(job, result, console)


def point_figures(job: MotionJob, result: MotionResult) -> dict[str, Any]:
    """A sweep row's figures: per output its mean and standard deviation at the last
    recorded time, and the parameter of largest total index (first index method, last
    time) per output."""
    from planar_tui.motion.results import figures

    return figures(result)


JOB_KIND = JobKind(
    name="motion_uncertainty",
    robot_kind="robot",
    settings=MotionSpec,
    run=run_motion,
    summary="Monte-Carlo band and Sobol'/eFAST/PCE indices of the motion under tolerances",
    render=render_motion,
    extra_outputs=extra_outputs,
    prepare=prepare_motion,
    check=check_motion,
    point_figures=point_figures,
    command=Command(
        "motion",
        "Monte-Carlo band and Sobol'/eFAST/PCE indices of the motion of every "
        "motion_uncertainty job under length and mass tolerances: band CSV, indices CSV at "
        "every recorded time (the job's indices_output, or OUTPUT-indices.csv), aggregated "
        "indices CSV (OUTPUT-aggregated.csv) and a Table-4-shaped table per time of at_s.\n\n"
        "An option that changes a job's setting is appended to the stem of the files the preset "
        "names; a name given with --out is kept.",
        options=(
            *uq.sampling_options(METHODS, "N"),
            Option("--device", "device", "cpu, cuda or auto; overrides `device`."),
        ),
    ),
    tab=Tab(
        "Motion",
        5,
        "planar_tui.app.widgets.motion_pane:MotionPane",
        view="Output",
        view_help="the next output (θ1…θn, tip x, tip y)",
    ),
    figure="planar_tui.figures.dispatch:from_main_table",
    warmup="[motion_uncertainty]\nduration_s = 0.002\nstep_s = 0.001\nsamples = 128\n"
    'methods = ["montecarlo", "sobol", "efast"]\n',
    estimate=lambda job: resource_estimate(job.spec, job.robot),
    app_default={
        "duration_s": 0.5,
        "step_s": 0.001,
        "tolerance_length_mm": 1.0,
        "tolerance_mass_g": 10.0,
        "methods": ["montecarlo", "sobol"],
        "samples": 128,
        "seed": 42,
        "output": "app-motion.csv",
    },
)

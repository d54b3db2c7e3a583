"""The ``[motion_uncertainty]`` job: how tolerances on lengths and masses move the robot.

Every link length and mass (optionally inertia) is uniform on ``nominal ± tolerance`` (as
in ``[sensitivity]``); every sampled robot is integrated by RK4 under the constant torques
(as in ``[simulate]``). Results: the band (mean, standard deviation, 5/50/95 % percentiles of
every output at every recorded step, over independent uniform robots: the Monte-Carlo or
Sobol' A/B robots, or N extra Monte-Carlo robots when eFAST runs alone), Sobol'/eFAST
indices of every output at the times ``at_s``, a Table-4-shaped table per time. Details:
``docs/motion.md``.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from planar_tui.dynamics.robot import SerialRobot
from planar_tui.dynamics.simulate import RunSettings, rk4_step_seconds
from planar_tui.errors import PresetError
from planar_tui.jobkind import Job, JobKind, JobResult
from planar_tui.limits import memory_problem, time_problem
from planar_tui.motion.device import DEVICES
from planar_tui.progress import Progress
from planar_tui.schema import (
    OptionReader,
    TableReader,
    integer,
    number,
    plot_setting,
    read_option,
    relative_path,
    setting,
    shown,
    string,
)
from planar_tui.sensitivity.job import tolerance_setting

METHODS = ("montecarlo", "sobol", "efast")
OUTPUTS = ("angles", "tip")
#: Recorded band rows by default (``every`` = steps / this, at least 1).
DEFAULT_RECORDS = 100
#: Largest seed (SALib's eFAST bootstrap takes 32-bit seeds).
SEED_MAX = 2**32 - 1
#: eFAST needs N > 4 M² with M = 4.
EFAST_MIN_SAMPLES = 65


def _read_choices(allowed: tuple[str, ...]):
    """A reader of one of ``allowed`` or a non-empty list of them (a single string is a
    one-item list), duplicates dropped, in the given order."""
    choices = ", ".join(f'"{a}"' for a in allowed)
    expected = f"one of {choices} or a non-empty list of them"

    def read(reader: TableReader, name, default, robot, values) -> tuple[str, ...]:
        chosen = reader.raw(name, list(default))
        if isinstance(chosen, str):
            chosen = [chosen]
        if not isinstance(chosen, list) or not chosen:
            raise reader.error(name, f"is {shown(chosen)}", expected)
        for item in chosen:
            if item not in allowed:
                raise reader.error(name, f"has {shown(item)}", expected)
        return tuple(dict.fromkeys(chosen))

    return read


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

    Derived fields, not keys: ``indices_file`` is the indices CSV's name
    (``indices_output`` or the default made from ``output``); ``device_used`` is the device
    :func:`prepare_motion` chose and ``device_note`` what the summary says about it;
    ``overridden`` names the keys command-line options set (:func:`with_overrides`), so
    that :func:`prepare_motion` blames the option, not the preset, for their problems.
    """

    every: int | None = setting(
        integer(minimum=1),
        default=None,
        default_doc="steps / 100",
        type_doc="integer ≥ 1",
        doc="record the band every k-th step (t = 0 and the end always)",
    )
    tolerance_length_mm: float = tolerance_setting("mm", "half-width of every length's range")
    tolerance_mass_g: float = tolerance_setting("g", "half-width of every mass's range")
    tolerance_inertia_kgm2: float | None = setting(
        number(positive=True),
        default=None,
        default_doc="(none: inertias fixed)",
        type_doc="0 < number < smallest inertia",
        doc="half-width of every inertia's range; makes the inertias inputs. Without it a "
        "link whose inertia is `m l²/12` (the default) keeps `m l²/12` of its sampled "
        "mass and length, any other keeps its value",
    )
    methods: tuple[str, ...] = setting(
        _read_choices(METHODS),
        default=("montecarlo", "sobol"),
        type_doc='`"montecarlo"`, `"sobol"`, `"efast"` or a list of them',
        doc="Monte Carlo (band), Sobol' and eFAST (indices; SALib's designs); eFAST alone "
        "adds N Monte-Carlo robots for the band",
    )
    samples: int = setting(
        integer(minimum=2),
        default=1024,
        type_doc="integer ≥ 2 (Sobol': power of two ≥ 8; eFAST: > 64)",
        doc="Monte Carlo: N robots; Sobol': base N (N·(D+2) robots, D inputs); eFAST: N per "
        "input (N·D robots, and N Monte-Carlo robots for the band without montecarlo or sobol)",
    )
    seed: int = setting(
        integer(minimum=1, maximum=SEED_MAX),
        default=42,
        type_doc="integer in [1, 2³² − 1]",
        doc="seed of sampling and bootstrap",
    )
    at_s: tuple[float, ...] | None = setting(
        _read_times,
        default=None,
        default_doc="`duration_s`",
        type_doc="number or list of numbers in (0, `duration_s`]",
        doc="times of the indices (rounded to a step)",
    )
    outputs: tuple[str, ...] = setting(
        _read_choices(OUTPUTS),
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
    indices_file: str = dataclasses.field(default="", compare=False)
    device_used: str | None = None
    device_note: str = ""
    overridden: tuple[str, ...] = dataclasses.field(default=(), compare=False)

    @staticmethod
    def check(values: dict, reader: TableReader, robot: SerialRobot) -> dict:
        """Step within the duration, tolerances below the nominal values, sample sizes
        the methods accept, and the run within the time and memory limits."""
        RunSettings.check_step(values, reader)
        for name, nominal, unit in (
            ("tolerance_length_mm", min(robot.lengths_m) * 1e3, "mm"),
            ("tolerance_mass_g", min(robot.masses_kg) * 1e3, "g"),
            ("tolerance_inertia_kgm2", min(robot.inertias_kgm2), "kg m²"),
        ):
            value = values[name]
            if value is not None and value >= nominal:
                raise reader.error(
                    name,
                    f"is {value:g} {unit}, not below the smallest nominal value {nominal:g} {unit}",
                    f"0 < tolerance < {nominal:g}",
                )
        check_samples(reader.error, values["methods"], values["samples"])
        check_resources(reader.error, MotionSpec(**values), robot)
        values["indices_file"] = values["indices_output"] or default_indices_name(reader)
        return values

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


def default_indices_name(reader: TableReader) -> str:
    """``OUTPUT-indices.csv`` beside the job's ``output`` (its default name when absent)."""
    output = reader.raw("output", None)
    if not isinstance(output, str) or not output:
        index = reader.prefix.rpartition("[")[2].rstrip("]") if "[" in reader.prefix else "1"
        output = f"{reader.path.stem}-motion_uncertainty-{index}.csv"
    stem = output[:-4] if output.lower().endswith(".csv") else output
    return f"{stem}-indices.csv"


def extra_outputs(spec: MotionSpec) -> dict[str, str]:
    """The indices CSV when an index method runs."""
    if any(method != "montecarlo" for method in spec.methods):
        return {"indices": spec.indices_file}
    return {}


def check_samples(error, methods, samples: int) -> None:
    """Sobol' N must be a power of two >= 8; eFAST N must exceed 4 M² = 64."""
    if "sobol" in methods and not (samples >= 8 and samples & (samples - 1) == 0):
        raise error(
            "samples", f"is {samples}, not a power of two >= 8 (Sobol')", "8, 16, ... 1024, ..."
        )
    if "efast" in methods and samples < EFAST_MIN_SAMPLES:
        raise error("samples", f"is {samples} (eFAST)", "an integer > 4 M² = 64 (M = 4)")


def num_inputs(spec: MotionSpec, robot: SerialRobot) -> int:
    return (3 if spec.tolerance_inertia_kgm2 is not None else 2) * robot.n_links


def robot_count(spec: MotionSpec, robot: SerialRobot) -> int:
    """Robots integrated: N (Monte Carlo) + N (D + 2) (Sobol') + N D (eFAST), over the
    designs of :func:`~planar_tui.motion.engine.design_methods` (eFAST alone: N more
    Monte-Carlo robots for the band)."""
    from planar_tui.motion.engine import design_methods
    from planar_tui.sensitivity.engine import design_rows

    d = num_inputs(spec, robot)
    return sum(
        spec.samples if m == "montecarlo" else design_rows(m, d, spec.samples)
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


def check_resources(error, spec: MotionSpec, robot: SerialRobot) -> None:
    """Refuse a job whose estimated time (robots × steps × one RK4 step) or memory (the
    robots' states and parameters, the outputs at ``at_s``, the band robots' outputs)
    exceeds :mod:`planar_tui.limits`."""
    robots = robot_count(spec, robot)
    n = robot.n_links
    seconds = robots * spec.n_steps * rk4_step_seconds(n)
    n_out = (n if "angles" in spec.outputs else 0) + (2 if "tip" in spec.outputs else 0)
    at = 1 if spec.at_s is None else len(spec.at_s)
    records = spec.n_steps // spec.record_every + 2
    memory = robots * (num_inputs(spec, robot) + 8 * n + n * n + at * n_out) * 8.0
    memory += records * 5 * n_out * 8.0
    problem = time_problem(seconds) or memory_problem(memory)
    if problem is not None:
        raise error(
            "samples",
            f"{robots} robots of {n} links × {spec.n_steps} steps: {problem}",
            "fewer samples, a shorter duration_s or a longer step_s",
        )


#: The command-line option of each key :func:`with_overrides` sets.
OPTIONS = {"methods": "--method", "samples": "--samples", "seed": "--seed", "device": "--device"}


def _checked_device(job: Job) -> tuple[str, str]:
    """The job's resources checked again (overrides change them) and its device chosen
    (:func:`~planar_tui.motion.device.resolve`): ``(device, note)``; ``cuda`` without a
    usable GPU is a :class:`PresetError` on ``device``.

    A problem with a value a command-line option set names the option (``command line:
    --device``), not the preset's key: the device when ``--device`` set it, the resources
    (checked on the preset's values when it was read) when ``--samples`` or ``--method``
    changed them."""
    from planar_tui.motion.device import resolve

    overridden = job.spec.overridden

    def error(name, problem, expected):
        causes = ("samples", "methods") if name == "samples" else (name,)
        option = next((OPTIONS[key] for key in causes if key in overridden), None)
        if option is not None:
            return PresetError("command line", option, problem, expected)
        return PresetError(job.preset_path, f"{job.key}.{name}", problem, expected)

    check_resources(error, job.spec, job.robot)
    used, note = resolve(job.spec.device)
    if used is None:
        raise error("device", note, '"cpu" or "auto", or a machine with a usable CUDA GPU')
    return used, note


def check_motion(job: Job) -> None:
    """Refuse a job that cannot run here (resources, an unusable ``cuda`` device) without
    computing anything: the job kind's ``check``, run on every sweep point."""
    _checked_device(job)


def prepare_motion(job: Job) -> Job:
    """The job with its resources checked again (overrides change them) and its device
    chosen: ``cuda`` without a usable GPU is a :class:`PresetError` on ``device``."""
    if job.spec.device_used is not None:
        return job
    used, note = _checked_device(job)
    spec = dataclasses.replace(job.spec, device_used=used, device_note=note)
    return dataclasses.replace(job, spec=spec)


def with_overrides(spec: MotionSpec, options: Mapping[str, Any]) -> MotionSpec:
    """The spec with command-line overrides (``methods``, ``samples``, ``seed``,
    ``device``; ``None`` keeps the preset's value), checked like the preset's keys."""

    def error(name, problem, expected):
        return PresetError("command line", f"--{name.replace('_', '-')}", problem, expected)

    given = {
        name: options[name]
        for name in ("samples", "seed", "device")
        if options.get(name) is not None
    }
    reader = OptionReader(given, {})
    changes: dict[str, Any] = {name: read_option(MotionSpec, reader, name) for name in given}
    methods = options.get("methods")
    if methods:
        for method in methods:
            if method not in METHODS:
                raise error("method", f"is {method!r}", "montecarlo, sobol or efast")
        changes["methods"] = tuple(dict.fromkeys(methods))
    overridden = tuple(key for key in OPTIONS if key in changes or key in spec.overridden)
    updated = dataclasses.replace(spec, **changes, overridden=overridden)
    check_samples(error, updated.methods, updated.samples)
    return updated


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
    t_s: Any
    band: Any
    names: tuple[str, ...]
    analyses: list
    notes: tuple[str, ...]
    device: str
    robots: int
    design: Any = None
    at_outputs: Any = None


def run_motion(job: Job, progress: Progress) -> MotionResult:
    """Sample, integrate every robot (three stages: sampling, integrating, analysis), then
    the band and the indices (see :mod:`planar_tui.motion.engine`)."""
    import numpy as np

    from planar_tui.motion import engine
    from planar_tui.motion.results import analyse_times, band_table, indices_table

    job = prepare_motion(job)
    spec, robot = job.spec, job.robot
    from planar_tui.sensitivity.engine import build_problem

    inertia_tol = spec.tolerance_inertia_kgm2
    problem = build_problem(robot, spec.tolerance_length_mm * 1e-3, spec.tolerance_mass_g * 1e-3,
                            inertia_tol)  # fmt: skip
    lengths, masses, inertias = robot.arrays()
    rod = inertias == masses * lengths * lengths / 12.0
    progress.start(len(engine.design_methods(spec.methods)), "sampling")
    design = engine.build_design(spec.methods, problem.num_vars, spec.samples, spec.seed, progress)
    robots, params = engine.make_robots(
        spec.device_used, problem, design, rod, robot,
        np.radians(np.array(spec.theta0_deg, dtype=np.float64)),
        np.radians(np.array(spec.omega0_deg_s, dtype=np.float64)),
        np.array(spec.torques_Nm, dtype=np.float64),
    )  # fmt: skip
    lengths_s = params[:, 0, :]
    band_rows = design.band_rows()
    record_steps = spec.record_steps()
    at_steps = spec.at_steps()
    stops = sorted(set(record_steps) | set(at_steps))
    records = {step: i for i, step in enumerate(record_steps)}
    names = engine.output_names(robot.n_links, spec.outputs)
    band = np.empty((len(record_steps), 5, len(names)))
    at_outputs = {}

    def on_stop(step: int, angles) -> None:
        if step in records:
            values = engine.take_outputs(lengths_s[band_rows], angles[band_rows], spec.outputs)
            band[records[step]] = engine.band_statistics(values)
        if step in at_steps:
            at_outputs[step] = engine.take_outputs(lengths_s, angles, spec.outputs)

    total = design.samples * spec.n_steps
    progress.start(total, "integrating", f"{design.samples} robots on {spec.device_note}")
    engine.integrate(robots, spec.step_s, stops, on_stop, progress)
    index_methods = [m for m in spec.methods if m != "montecarlo"]
    progress.start(max(1, len(index_methods) * len(at_steps)), "analysis")
    labels = engine.output_labels(names)
    analyses, notes = analyse_times(
        design, at_outputs, spec, problem, labels, index_methods, progress
    )
    band_note = extra_band_note(spec)
    if band_note:
        notes = (band_note, *notes)
    t_s = np.array(record_steps) * spec.step_s
    last = band[-1]
    summary = (
        f"{robot.label}: {design.samples} robots × {spec.n_steps} steps on {spec.device_note}; "
        + ", ".join(
            f"{label} {m:.4g}±{s:.2g}" for label, m, s in zip(labels, last[0], last[1], strict=True)
        )
        + f" at t = {t_s[-1]:g} s"
        + (f"; band from {spec.samples} extra Monte-Carlo robots" if band_note else "")
    )
    return MotionResult(
        table=band_table(t_s, band, names),
        extra_tables={"indices": indices_table(analyses, names)} if analyses else {},
        summary=summary,
        robot_label=robot.label,
        t_s=t_s,
        band=band,
        names=names,
        analyses=analyses,
        notes=notes,
        device=spec.device_note,
        robots=design.samples,
        design=design,
        at_outputs=at_outputs,
    )


def render_motion(job: Job, result: MotionResult, console) -> None:
    """The CLI view: the band at the end and a Table-4-shaped table per time."""
    from planar_tui.motion.results import render

    render(job, result, console)


def point_figures(job: Job, result: MotionResult) -> dict[str, Any]:
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
    summary="Monte-Carlo band and Sobol'/eFAST indices of the motion under tolerances",
    render=render_motion,
    extra_outputs=extra_outputs,
    overrides=with_overrides,
    prepare=prepare_motion,
    check=check_motion,
    point_figures=point_figures,
)

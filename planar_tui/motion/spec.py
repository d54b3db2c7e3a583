"""The ``[motion_uncertainty]`` job's settings: its preset keys (the simulation's, the
tolerances, the methods and their sample sizes, the recorded times), their cross-key
checks, the robots each method integrates and the resource estimate that refuses a job
too large to run."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from planar_tui import uq
from planar_tui.dynamics.robot import SerialRobot, rk4_step_seconds
from planar_tui.dynamics.simulate import RunSettings
from planar_tui.jobkind import Job
from planar_tui.limits import memory_problem, time_problem
from planar_tui.motion.device import DEVICES
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

    The device a job runs on is chosen by
    :func:`~planar_tui.motion.runner.prepare_motion`
    (:class:`~planar_tui.motion.runner.MotionPrepared`); the indices CSV's name by
    :func:`~planar_tui.motion.job.indices_file`.
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

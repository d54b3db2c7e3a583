"""The path jobs' shared part: their common keys, the runner, the CSV columns, the summary
and the :class:`~planar_tui.jobkind.JobKind` a robot's ``path.py`` declares with
:func:`path_job_kind`.

A path job samples a quintic rest-to-rest platform path (:mod:`.quintic`) at ``steps + 1``
times, asks the robot's mechanism for its actuators' coordinates and efforts there
(``inverse_dynamics``) and writes one CSV row per time: ``t_s, x_cm, y_cm[, phi_deg]``,
per actuator its coordinate, rate and acceleration, then the efforts and the powers. A
time where a leg cannot close, leaves its joint limits or meets a singularity fails the
job (exit code 1, one line naming the first such time). With ``feed_forward = true`` the
platform's forward dynamics (:mod:`.forward`) is integrated under the path's own efforts
and its largest deviation from the path and the loop-closure drift are reported; with
``constant_efforts`` it is integrated from rest at ``from_pose`` under those efforts and
written beside the CSV (:func:`~.forward.constant_motion`, ``OUTPUT-forward.csv``).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, fields
from typing import TYPE_CHECKING, Any, ClassVar

from planar_tui.csvio import CsvTable
from planar_tui.errors import JobError, PresetError
from planar_tui.jobkind import Command, Job, JobKind, JobResult, PreparedJob, Tab
from planar_tui.limits import memory_problem, time_problem
from planar_tui.progress import Progress
from planar_tui.schema import boolean, integer, number, numbers, setting
from planar_tui.workspace.path.certify import (
    Certificate,
    certificate_outputs,
    certify,
    check_certificate,
)
from planar_tui.workspace.path.forward import PathFailure, constant_motion, simulate
from planar_tui.workspace.path.model import OK, PathModel, PathSolution, problem_text

if TYPE_CHECKING:
    from planar_tui.workspace.paving.mechanism import Mechanism

#: Most steps of one path (its CSV rows minus one).
MAX_STEPS = 1_000_000
#: Memory per CSV cell (the arrays and the CSV's text), as the torques job's.
BYTES_PER_CELL = 320
#: Seconds per sampled pose of the inverse dynamics (with its Python wrapper), and per
#: forward-dynamics step (four stages of five inverse dynamics each, from Python); measured
#: on a loaded 2-core machine, rounded up.
POSE_SECONDS = 2e-6
FEED_FORWARD_STEP_SECONDS = 2e-3

POSE_DOCS = {3: "`[x_cm, y_cm, phi_deg]`", 2: "`[x_cm, y_cm]`"}


def pose_setting(dimension: int, doc: str) -> Any:
    """``from_pose`` / ``to_pose``: the platform's pose, cm and degrees."""
    return setting(numbers(length=dimension), type_doc=POSE_DOCS[dimension], doc=doc)


def duration_setting() -> Any:
    return setting(
        number(positive=True), default=1.0, type_doc="number > 0", doc="the path's duration"
    )


def steps_setting() -> Any:
    return setting(
        integer(minimum=1, maximum=MAX_STEPS),
        default=100,
        type_doc=f"integer in [1, {MAX_STEPS:,}]",
        doc="time steps: the path is sampled at `steps + 1` times `t = k T / steps`",
    )


def feed_forward_setting() -> Any:
    return setting(
        boolean(),
        default=False,
        type_doc="boolean",
        doc="also integrate the forward dynamics (RK4, same steps) under the path's own "
        "efforts and report the largest deviation from the path and the closure drift",
    )


def constant_efforts_setting(actuators: int, unit: str) -> Any:
    """``constant_efforts``: one effort per actuator (N m revolute, N prismatic), held from
    rest at ``from_pose`` (:func:`~.forward.constant_motion`)."""
    names = ", ".join(f"e{i}" for i in range(1, actuators + 1))

    def read(reader: Any, name: str, default: Any, context: Any, values: Any) -> Any:
        expected = f"{actuators} efforts in {unit}, one per actuator"
        return reader.numbers(name, default, length=actuators, items_doc=expected)

    return setting(
        read,
        default=None,
        default_doc="(none)",
        type_doc=f"`[{names}]`, {unit}",
        doc="also integrate the forward dynamics (RK4, same steps and duration) from rest "
        "at from_pose under these constant efforts; writes OUTPUT-forward.csv (the poses "
        "and their rates until the platform leaves the workspace)",
    )


def forward_runs(spec: Any) -> int:
    """How many forward-dynamics integrations the spec (or its values) asks for."""
    get = spec.get if isinstance(spec, dict) else lambda name: getattr(spec, name, None)
    return int(bool(get("feed_forward"))) + int(get("constant_efforts") is not None)


def path_needs(steps: int, runs: int, model: PathModel) -> tuple[float, float]:
    """``(memory_bytes, seconds)`` of a path of ``steps`` steps: its CSV's cells, its poses
    and the ``runs`` forward-dynamics integrations' steps (:func:`forward_runs`)."""
    seconds = (steps + 1) * POSE_SECONDS + runs * steps * FEED_FORWARD_STEP_SECONDS
    return (steps + 1) * len(path_header(model)) * BYTES_PER_CELL, seconds


def estimate(job: Job[Any, Any]) -> tuple[float, float]:
    """``(memory_bytes, seconds)`` of a path job (:func:`path_needs`)."""
    spec = job.spec
    return path_needs(spec.steps, forward_runs(spec), spec.mechanism.path_model(job.robot))


def check_path(values: dict[str, Any], reader: Any, robot: Any, mechanism: Any) -> dict[str, Any]:
    """A path job fits the time and memory limits (:func:`path_needs`,
    :mod:`planar_tui.limits`): one line on ``steps`` otherwise."""
    steps = values["steps"]
    memory, seconds = path_needs(steps, forward_runs(values), mechanism.path_model(robot))
    problem = time_problem(seconds) or memory_problem(memory)
    if problem is not None:
        raise reader.error("steps", f"is {steps:,}: the path {problem}", "fewer steps")
    return values


@dataclass(frozen=True, kw_only=True)
class PathSpec:
    """The keys every path job starts with: a quintic rest-to-rest path of the platform
    (cm, degrees, seconds) from ``from_pose`` to ``to_pose``; a robot's spec adds its own
    keys after these (a point robot declares ``from_pose`` and ``to_pose`` again, of
    dimension 2) and sets its :attr:`mechanism`."""

    from_pose: tuple[float, ...] = pose_setting(3, "the platform's pose at t = 0")
    to_pose: tuple[float, ...] = pose_setting(3, "the platform's pose at t = duration_s")
    duration_s: float = duration_setting()
    steps: int = steps_setting()

    mechanism: ClassVar[Mechanism]

    @classmethod
    def check(cls, values: dict[str, Any], reader: Any, robot: Any) -> dict[str, Any]:
        """``kappa_max`` above 1 (:func:`~planar_tui.workspace.path.certify.check_certificate`)
        and the job within the time and memory limits (:func:`check_path`) for the spec's
        :attr:`mechanism`."""
        check_certificate(values, reader)
        return check_path(values, reader, robot, cls.mechanism)


def resolved_modes(job: Any, key: str, per_leg: Any, example: str) -> tuple[int, ...]:
    """A working mode per leg, where ``per_leg`` gives each leg's modes (``1``, ``-1``) that
    close it at ``from_pose`` within its limits, two only where they are distinct
    solutions: the one mode where there is one; ``1`` where there is none (the run then
    fails at t = 0); a :class:`PresetError` on ``key`` (``example``: the key written out)
    where a leg closes both ways."""
    modes = []
    for leg, allowed in enumerate(per_leg, start=1):
        if len(allowed) == 2:
            raise PresetError(
                job.preset_path,
                f"{job.key}.{key}",
                f"is not given and leg {leg} closes in both working modes at from_pose",
                example,
            )
        modes.append(allowed[0] if allowed else 1)
    return tuple(modes)


def pose_si(pose: tuple[float, ...]) -> tuple[float, ...]:
    """A preset's pose (cm, cm[, deg]) in SI units (m, m[, rad])."""
    return (pose[0] / 100.0, pose[1] / 100.0, *(math.radians(p) for p in pose[2:]))


@dataclass(frozen=True, kw_only=True)
class PathResult(JobResult):
    """A path job's samples: times (s), the mechanism's solution, and with
    ``feed_forward`` the forward dynamics' largest pose deviation (m or rad) and drift."""

    times_s: Any
    solution: PathSolution
    model: PathModel
    deviation: float | None = None
    drift_m: float | None = None
    certificate: Certificate | None = None


def path_header(model: PathModel) -> tuple[str, ...]:
    """The CSV columns (module docstring)."""
    pose = ("x_cm", "y_cm", "phi_deg")[: model.pose_dimension]
    unit = "cm" if model.prismatic else "rad"
    actuators = range(1, model.actuators + 1)
    name = model.coordinate
    return (
        "t_s",
        *pose,
        *(f"{name}{i}_{unit}{suffix}" for i in actuators for suffix in ("", "_s", "_s2")),
        *(f"{model.effort}{i}_{model.effort_unit}" for i in actuators),
        *(f"power{i}_W" for i in actuators),
    )


def figures(model: PathModel, solution: PathSolution) -> dict[str, float]:
    """Per actuator: peak |effort|, RMS effort and peak |power| over the samples (NaN
    where there are none)."""
    import numpy as np

    effort, power = solution.effort, solution.effort * solution.rate
    out: dict[str, float] = {}
    for i in range(model.actuators):
        name, unit = f"{model.effort}{i + 1}", model.effort_unit
        if not len(effort):
            out.update(dict.fromkeys((f"{name}_abs_max_{unit}", f"{name}_rms_{unit}"), math.nan))
            out[f"power{i + 1}_abs_max_W"] = math.nan
            continue
        out[f"{name}_abs_max_{unit}"] = float(np.abs(effort[:, i]).max())
        out[f"{name}_rms_{unit}"] = float(np.sqrt(np.mean(effort[:, i] ** 2)))
        out[f"power{i + 1}_abs_max_W"] = float(np.abs(power[:, i]).max())
    return out


#: A certified path's sweep and optimisation columns (with ``kappa_max``): 1 when the
#: certificate says ``yes`` (else 0), the certified prefix's end (T when certified) and
#: the upper end of the largest κ's bracket (nan where nothing is certified).
CERTIFICATE_FIGURES = ("path_certified", "certified_until_s", "kappa_peak_hi")


def figure_names(job: Job[Any, Any]) -> tuple[str, ...]:
    """The columns :func:`point_figures` reports, without running the job."""
    model = job.spec.mechanism.path_model(job.robot)
    names = []
    for i in range(1, model.actuators + 1):
        name, unit = f"{model.effort}{i}", model.effort_unit
        names += [f"{name}_abs_max_{unit}", f"{name}_rms_{unit}", f"power{i}_abs_max_W"]
    if getattr(job.spec, "kappa_max", None) is not None:
        names += CERTIFICATE_FIGURES
    return tuple(names)


def point_figures(job: Job[Any, Any], result: PathResult) -> dict[str, float]:
    """A sweep row's figures (:func:`figures`; with a certificate,
    :data:`CERTIFICATE_FIGURES`)."""
    found = figures(result.model, result.solution)
    certificate = result.certificate
    if certificate is not None:
        yes = certificate.certified == "yes"
        lo = certificate.failure_lo_s
        until = job.spec.duration_s if yes or lo is None else lo
        found.update(
            path_certified=1.0 if yes else 0.0,
            certified_until_s=until,
            kappa_peak_hi=float(certificate.kappa_peak_hi),
        )
    return found


def _listed(values: Any) -> str:
    return "[" + ", ".join(f"{v:.4g}" for v in values) + "]"


def run_path(ready: PreparedJob[Any, Any, Any], progress: Progress) -> PathResult:
    """Sample the path and solve the mechanism at every time; without ``kappa_max`` fail at
    the first bad time, with it certify the path (:mod:`.certify`) and write the efforts
    where the legs close."""
    import numpy as np

    from planar_tui.workspace.path.quintic import quintic, sample_times

    job, spec, robot = ready.job, ready.prepared, ready.robot
    mechanism = spec.mechanism
    model = mechanism.path_model(robot)
    times = sample_times(spec.duration_s, spec.steps)
    start, stop = pose_si(spec.from_pose), pose_si(spec.to_pose)
    certificate = _certificate(spec, robot, progress)
    progress.start(len(times), "inverse dynamics")
    pose, rate, acceleration = quintic(start, stop, spec.duration_s, times)
    solution = mechanism.inverse_dynamics(robot, spec, pose, rate, acceleration)
    progress.advance(len(times))
    bad = np.flatnonzero(solution.status != OK)
    if len(bad) and certificate is None:
        k = int(bad[0])
        raise JobError(
            job.preset_path,
            job.key,
            f"the path fails at t = {times[k]:.6g} s (step {k}): "
            f"{problem_text(int(solution.status[k]))}",
            "a path inside the workspace, off its singularities",
        )
    pose_columns = np.column_stack([pose[:, :2] * 100.0, np.degrees(pose[:, 2:])])
    # prismatic legs in cm; revolute angles continuous along the path (unwrapped)
    scale = 100.0 if model.prismatic else 1.0
    coordinate = solution.coordinate * scale
    closed = solution.status == OK
    if not model.prismatic:  # over the closed rows only (a failing row's angle is no angle)
        coordinate[closed] = np.unwrap(coordinate[closed], axis=0)
    coordinates = np.stack(
        [coordinate, solution.rate * scale, solution.acceleration * scale], axis=2
    ).reshape(len(times), -1)
    power = solution.effort * solution.rate
    rows: Any = np.column_stack([times, pose_columns, coordinates, solution.effort, power])
    if len(bad):
        solution = _rows_of(solution, closed)
        rows = _blank_failures(rows, closed, 1 + model.pose_dimension)
    found = figures(model, solution)
    unit = model.effort_unit.replace("Nm", "N m")
    summary = (
        f"{int(closed.sum())} poses over {spec.duration_s:g} s, peak |{model.effort}| = "
        f"{_listed(found[k] for k in found if '_abs_max_N' in k)} {unit}, RMS = "
        f"{_listed(found[k] for k in found if '_rms_' in k)} {unit}, peak power = "
        f"{_listed(found[k] for k in found if k.startswith('power'))} W"
    )
    if len(bad):
        summary += f" ({len(bad)} of {len(times)} sampled poses fail: no efforts there)"
    deviation = drift = None
    if spec.feed_forward and not len(bad):
        progress.start(spec.steps, "forward dynamics")
        try:
            deviation, drift = feed_forward(mechanism, robot, spec, start, stop, times, progress)
        except PathFailure as failure:  # the simulated platform strays out of the workspace
            where = f"{job.key}.feed_forward"
            raise JobError(
                job.preset_path, where, f"the forward dynamics fails {failure}"
            ) from None
        summary += f"; feed-forward: deviation {deviation:.3g}, closure drift {drift:.3g} m"
    extra = {}
    if spec.constant_efforts is not None:
        progress.start(spec.steps, "forward dynamics (constant efforts)")
        extra["forward"], words = constant_motion(mechanism, robot, spec, start, progress.advance)
        summary += f"; constant efforts: {words}"
    if certificate is not None:
        summary += f"; {certificate.describe()}"
        extra["certificate"] = certificate.table()
    return PathResult(
        table=CsvTable(path_header(model), rows),
        summary=summary,
        extra_tables=extra,
        times_s=times[closed],
        solution=solution,
        model=model,
        deviation=deviation,
        drift_m=drift,
        certificate=certificate,
    )


def _certificate(spec: Any, robot: Any, progress: Progress) -> Certificate | None:
    """The path's certificate with ``kappa_max`` (cm, cm[, rad] poses), else ``None``."""
    kappa_max = getattr(spec, "kappa_max", None)
    if kappa_max is None:
        return None
    test = spec.mechanism.path_box_test(robot, spec)
    start = (*spec.from_pose[:2], *(math.radians(p) for p in spec.from_pose[2:]))
    stop = (*spec.to_pose[:2], *(math.radians(p) for p in spec.to_pose[2:]))
    return certify(test, start, stop, spec.duration_s, kappa_max, progress)


def _rows_of(solution: PathSolution, keep: Any) -> PathSolution:
    """The solution's rows ``keep`` (a mask)."""
    return PathSolution(*(getattr(solution, f.name)[keep] for f in fields(PathSolution)))


def _blank_failures(rows: Any, closed: Any, kept_columns: int) -> list[list[Any]]:
    """The CSV rows with every cell after the time and pose empty where the legs do not
    close (``closed`` false)."""
    blank = [None] * (rows.shape[1] - kept_columns)
    return [
        row.tolist() if ok else [*row[:kept_columns].tolist(), *blank]
        for row, ok in zip(rows, closed, strict=True)
    ]


def feed_forward(
    mechanism: Any, robot: Any, spec: Any, start: Any, stop: Any, times: Any, progress: Progress
) -> tuple[float, float]:
    """Integrate the forward dynamics from rest at ``start`` under the path's own efforts
    (the inverse dynamics of the quintic at every RK4 stage's time): the largest deviation
    of the pose from the path (m and rad mixed, max-norm) and the closure drift (m)."""
    import numpy as np

    from planar_tui.workspace.path.quintic import quintic

    def effort(t: float) -> Any:
        state = quintic(start, stop, spec.duration_s, np.array([t]))
        return mechanism.inverse_dynamics(robot, spec, *state).effort[0]

    zero = np.zeros(len(start))
    motion = simulate(
        mechanism, robot, spec, start, zero, effort, spec.duration_s, spec.steps, progress.advance
    )
    path = quintic(start, stop, spec.duration_s, times)[0]
    return float(np.abs(motion.pose - path).max()), motion.drift_m


def path_job_kind(
    name: str,
    robot_kind: str,
    settings: type,
    robot_words: str,
    prepare: Callable[[Job[Any, Any]], Any],
    warmup: str,
) -> JobKind:
    """The :class:`JobKind` of a robot's path job: ``prepare(job)`` returns the spec the
    mechanism is given (its working mode resolved; :class:`PresetError` where it cannot)."""
    return JobKind(
        name=name,
        robot_kind=robot_kind,
        settings=settings,
        run=run_path,
        summary=f"{robot_words} actuator efforts along a quintic platform path",
        prepare=prepare,
        point_figures=point_figures,
        figure_names=figure_names,
        estimate=estimate,
        command=Command(
            name,
            f"Actuator efforts of the {robot_words} along the quintic path of every {name} "
            "job: one CSV per job (pose, actuator coordinates, efforts, powers by time).",
        ),
        figure="planar_tui.figures.path:from_result",
        extra_outputs=path_outputs,
        warmup=warmup,
        tab=Tab(f"{robot_words} path", PATH_TAB_ORDER, path_pane(name)),
    )


def path_outputs(job: Job[Any, Any]) -> dict[str, str]:
    """The extra CSVs beside the job's: the certificate (:func:`certificate_outputs`) and,
    with ``constant_efforts``, the forward motion (``-forward.csv``)."""
    outputs = certificate_outputs(job)
    if getattr(job.spec, "constant_efforts", None) is not None:
        stem = job.output[:-4] if job.output.lower().endswith(".csv") else job.output
        outputs["forward"] = f"{stem}-forward.csv"
    return outputs


#: The path tabs' place, after the workspace tabs (among them by title).
PATH_TAB_ORDER = 9


def path_pane(name: str) -> str:
    """The app's pane of the path kind ``name`` (``path3rrr`` → ``Path3RRRPane``)."""
    return f"planar_tui.app.widgets.path_pane:Path{name.removeprefix('path').upper()}Pane"

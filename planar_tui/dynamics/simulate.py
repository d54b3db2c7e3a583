"""The ``[simulate]`` job: RK4 forward dynamics under constant joint torques.

Settings (the preset keys), the runner (chunked RK4 with progress and cancel), the typed
result and the CSV columns of one job kind.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from planar_tui.csvio import CsvTable
from planar_tui.dynamics.robot import SerialRobot, rk4_step_seconds
from planar_tui.jobkind import Command, Job, JobKind, JobResult, PreparedJob, Tab
from planar_tui.limits import memory_problem, time_problem
from planar_tui.progress import Progress
from planar_tui.schema import (
    PER_LINK,
    TableReader,
    integer,
    number,
    numbers,
    per_link_zeros,
    plot_setting,
    setting,
)

if TYPE_CHECKING:
    import numpy as np

#: Most RK4 steps per kernel call (about 30 ms for a 6R robot).
STEPS_PER_CHUNK = 20_000
#: Wall time a kernel call aims at: Ctrl-C and Cancel are checked between calls, and a
#: step's cost grows with the links (about 4 µs at n = 6, 0.16 ms at n = 400, 0.4 ms at
#: n = 1000), so chunks are sized from the measured time per step, not a step count.
CHUNK_SECONDS = 0.05
#: How much a chunk may grow over the previous one (the first chunk is one step).
CHUNK_GROWTH = 8


#: Memory per recorded value: the trajectory arrays, the CSV table and its row lists.
BYTES_PER_CELL = 48


def next_chunk_steps(steps: int, seconds: float, left: int, most: int | None = None) -> int:
    """Steps of the next kernel call after ``steps`` steps took ``seconds``: about
    :data:`CHUNK_SECONDS` of work, growing at most :data:`CHUNK_GROWTH`-fold, at most
    ``most`` steps (``None``: no cap) and the ``left`` steps; at least one.

    The one chunk rule of every time-stepping job: the simulate job caps it at
    :data:`STEPS_PER_CHUNK`, the motion job (whose calls hold many robots) does not."""
    grown = steps * CHUNK_GROWTH
    target = grown if seconds <= 0 else int(steps * CHUNK_SECONDS / seconds)
    cap = grown if most is None else min(grown, most)
    return max(1, min(target, cap, left))


def per_link_numbers(doc: str, default_doc: str = "zeros") -> Any:
    """A per-link array of numbers (one per link; default zeros), e.g. `torques_Nm`."""
    return setting(
        numbers(length=PER_LINK),
        default=per_link_zeros,
        default_doc=default_doc,
        type_doc="n numbers",
        doc=doc,
    )


@dataclass(frozen=True, kw_only=True)
class RunSettings:
    """The keys of a constant-torque RK4 run from a given state, declared once for every
    job that integrates the robot (``[simulate]``, ``[motion_uncertainty]``)."""

    duration_s: float = setting(
        number(positive=True),
        type_doc="number > 0",
        doc="simulated time; the run takes `round(duration_s / step_s)` steps",
    )
    step_s: float = setting(
        number(positive=True), type_doc="number > 0, ≤ `duration_s`", doc="RK4 step"
    )
    theta0_deg: tuple[float, ...] = per_link_numbers("initial relative joint angles")
    omega0_deg_s: tuple[float, ...] = per_link_numbers("initial joint rates")
    torques_Nm: tuple[float, ...] = per_link_numbers("constant joint torques", "zeros (free fall)")

    @staticmethod
    def check_step(values: dict[str, Any], reader: TableReader) -> None:
        """The step must not exceed the duration, nor be so short that the step count
        ``duration_s / step_s`` overflows (a finite count is held to the time limit)."""
        duration_s, step_s = values["duration_s"], values["step_s"]
        if step_s > duration_s:
            raise reader.error(
                "step_s",
                f"is {step_s:g} s, longer than duration_s = {duration_s:g} s",
                "step_s <= duration_s",
            )
        if not math.isfinite(duration_s / step_s):  # step_s = 5e-324
            raise reader.error(
                "step_s",
                f"is {step_s:g} s: duration_s / step_s is {duration_s / step_s:.3g} steps",
                "a step_s giving a finite number of steps",
            )

    @property
    def n_steps(self) -> int:
        """Number of RK4 steps: ``round(duration_s / step_s)``."""
        return max(1, round(self.duration_s / self.step_s))


def simulate_estimate(n_steps: float, every: int, n_links: int) -> tuple[float, float]:
    """``(memory_bytes, seconds)`` of a run: ``n_steps / every + 1`` rows of ``2n + 6``
    cells, ``n_steps`` RK4 steps (:func:`rk4_step_seconds`)."""
    rows = n_steps / every + 1
    return rows * (2 * n_links + 6) * BYTES_PER_CELL, n_steps * rk4_step_seconds(n_links)


def estimate(job: Job[SimulateSpec, SerialRobot]) -> tuple[float, float]:
    """``(memory_bytes, seconds)`` of ``job`` (:func:`simulate_estimate`)."""
    return simulate_estimate(
        job.spec.duration_s / job.spec.step_s, job.spec.every, job.robot.n_links
    )


@dataclass(frozen=True, kw_only=True)
class SimulateSpec(RunSettings):
    """Settings of one forward-dynamics run (angles are relative joint angles): the run's
    keys (:class:`RunSettings`), then what it records."""

    every: int = setting(
        integer(minimum=1),
        default=1,
        type_doc="integer ≥ 1",
        doc="write every k-th step (t = 0 always)",
    )
    characteristic_length_cm: float | None = setting(
        number(positive=True),
        default=None,
        type_doc="number > 0",
        default_doc="(no `kappa_pose` column)",
        doc="length L weighting the tip's rotation in the pose's κ (`kappa_pose`, "
        "docs/dexterity.md)",
    )
    plot: str | None = plot_setting()

    @staticmethod
    def check(values: dict[str, Any], reader: TableReader, robot: SerialRobot) -> dict[str, Any]:
        """The step must not exceed the duration; the run must fit the time and memory
        limits (:mod:`planar_tui.limits`)."""
        RunSettings.check_step(values, reader)
        n_steps = values["duration_s"] / values["step_s"]
        memory, seconds = simulate_estimate(n_steps, values["every"], robot.n_links)
        problem = time_problem(seconds) or memory_problem(memory)
        if problem is not None:
            raise reader.error(
                "duration_s",
                f"{n_steps:.3g} steps of {robot.n_links} links {problem}",
                "a shorter duration_s, a longer step_s or a larger every",
            )
        return values


@dataclass(frozen=True, kw_only=True)
class SimulateResult(JobResult):
    """The recorded trajectory: times, relative joint angles and rates, energies (SI)."""

    t_s: np.ndarray
    theta_rad: np.ndarray
    omega_rad_s: np.ndarray
    kinetic_J: np.ndarray
    potential_J: np.ndarray


def simulate_header(n_links: int, pose: bool = False) -> tuple[str, ...]:
    """CSV columns of a simulation: time, relative angles, rates, energies (SI units), the
    tip Jacobian's κ (positions; with ``pose``, the pose's too)."""
    return (
        "t_s",
        *(f"theta{i}_rad" for i in range(1, n_links + 1)),
        *(f"omega{i}_rad_s" for i in range(1, n_links + 1)),
        "kinetic_J",
        "potential_J",
        "energy_J",
        "kappa",
        *(("kappa_pose",) if pose else ()),
    )


class UnboundedBlank(Sequence[list[Any]]):
    """The rows of a float array ``values`` whose infinite cells from column ``first`` on
    (κ at a singular pose) are written empty, as the dexterity boxes' unbounded κ; the
    other columns must be finite (:meth:`non_finite_column`)."""

    def __init__(self, values: np.ndarray, first: int):
        self._values, self._first = values, first

    def __len__(self) -> int:
        return len(self._values)

    def __getitem__(self, index: Any) -> Any:
        if isinstance(index, slice):
            return [self[i] for i in range(*index.indices(len(self)))]
        row = self._values[index].tolist()
        return [*row[: self._first], *("" if c == math.inf else c for c in row[self._first :])]

    def non_finite_column(self) -> int | None:
        """The first column holding a NaN, or an infinity before column ``first``."""
        import numpy as np

        bad = ~np.isfinite(self._values)
        bad[:, self._first :] &= ~np.isposinf(self._values[:, self._first :])
        columns = np.flatnonzero(bad.any(axis=0))
        return int(columns[0]) if len(columns) else None


def kappa_columns(lengths_m: Any, theta_rad: Any, length_cm: float | None) -> list[Any]:
    """The κ of the tip Jacobian at each row of ``theta_rad`` (:mod:`kernels.serial_kappa`):
    of the positions, then of the pose with :math:`L` = ``length_cm`` where given."""
    import numpy as np

    from planar_tui.kernels.serial_kappa import tip_kappa

    lengths = [0.0] if length_cm is None else [0.0, length_cm / 100.0]
    columns = []
    for length_m in lengths:
        kappa = np.empty(len(theta_rad))
        tip_kappa(lengths_m, np.ascontiguousarray(theta_rad), length_m, kappa)
        columns.append(kappa)
    return columns


def run_simulate(
    job: PreparedJob[SimulateSpec, SerialRobot, None] | Job[SimulateSpec, SerialRobot],
    progress: Progress,
) -> SimulateResult:
    """Integrate the forward dynamics ``θ̈ = I⁻¹(τ + γ − C θ̇)`` with classical RK4.

    Records every ``spec.every``-th step including t = 0. The kernel runs in chunks of
    about :data:`CHUNK_SECONDS` (:func:`next_chunk_steps`), reporting progress and
    honouring a cancel between them; the result is bit-identical to one call.
    """
    import numpy as np

    from planar_tui.kernels.rk4 import rk4_integrate, rk4_record_count

    spec, robot = job.spec, job.robot
    lengths_m, masses_kg, inertias_kgm2 = robot.arrays()
    n = robot.n_links
    theta = np.radians(np.array(spec.theta0_deg, dtype=np.float64))
    omega = np.radians(np.array(spec.omega0_deg_s, dtype=np.float64))
    torque = np.array(spec.torques_Nm, dtype=np.float64)
    n_steps = spec.n_steps
    rows = rk4_record_count(n_steps, spec.every)
    t_s = np.empty(rows)
    theta_rad = np.empty((rows, n))
    omega_rad_s = np.empty((rows, n))
    kinetic_J = np.empty(rows)
    potential_J = np.empty(rows)

    progress.start(n_steps, "integrating", f"{n_steps} steps of {spec.step_s:g} s")
    done = row = 0
    chunk = 1
    while done < n_steps:
        started = time.perf_counter()
        row += rk4_integrate(
            lengths_m,
            masses_kg,
            inertias_kgm2,
            robot.gravity_m_s2,
            torque,
            theta,
            omega,
            spec.step_s,
            chunk,
            spec.every,
            done,
            t_s[row:],
            theta_rad[row:],
            omega_rad_s[row:],
            kinetic_J[row:],
            potential_J[row:],
        )
        done += chunk
        t_end_s = done * spec.step_s
        progress.advance(chunk, f"t = {t_end_s:.4g} s", t_s=t_end_s)
        elapsed_s = time.perf_counter() - started
        chunk = next_chunk_steps(chunk, elapsed_s, n_steps - done, STEPS_PER_CHUNK)
    if row != rows:
        raise RuntimeError(f"RK4 wrote {row} records, expected {rows}")

    energy_J = kinetic_J + potential_J
    kappa = kappa_columns(lengths_m, theta_rad, spec.characteristic_length_cm)
    values = np.column_stack(
        [t_s, theta_rad, omega_rad_s, kinetic_J, potential_J, energy_J, *kappa]
    )
    table = UnboundedBlank(values, values.shape[1] - len(kappa))
    summary = f"{n_steps} RK4 steps, {rows} rows, t_end = {t_s[-1]:.6g} s"
    drift_J = float(np.max(np.abs(energy_drift_J(energy_J, theta_rad, torque))))
    summary += (
        f", max |E - E0 - W| = {drift_J:.2e} J"
        if torque.any()
        else f", max |E - E0| = {drift_J:.2e} J"
    )
    return SimulateResult(
        table=CsvTable(simulate_header(n, spec.characteristic_length_cm is not None), table),
        summary=summary,
        t_s=t_s,
        theta_rad=theta_rad,
        omega_rad_s=omega_rad_s,
        kinetic_J=kinetic_J,
        potential_J=potential_J,
    )


def torque_work_J(theta_rad: Any, torques_Nm: Any) -> Any:
    r"""The work of constant joint torques since the first row (J), from the relative joint
    angles ``theta_rad`` (rows × joints), the generalised coordinates:

    .. math:: W(t) = \int_0^t \tau^T\dot\theta\,dt' = \sum_i \tau_i(\theta_i(t) - \theta_i(0))

    so the integrator's energy drift is :math:`E(t) - E(0) - W(t)` (:func:`energy_drift_J`)."""
    import numpy as np

    theta_rad = np.asarray(theta_rad, dtype=float)
    return (theta_rad - theta_rad[0]) @ np.asarray(torques_Nm, dtype=float)


def energy_drift_J(energy_J: Any, theta_rad: Any, torques_Nm: Any) -> Any:
    """The energy balance :math:`E(t) - E(0) - W(t)` of every row (J): zero for an exact
    solution, whatever the constant torques (:func:`torque_work_J`)."""
    import numpy as np

    energy_J = np.asarray(energy_J, dtype=float)
    return energy_J - energy_J[0] - torque_work_J(theta_rad, torques_Nm)


def point_figures(job: Job[SimulateSpec, SerialRobot], result: SimulateResult) -> dict[str, float]:
    """A sweep row's figures: the final time and state (relative angles and rates, SI) and
    the largest energy drift ``max_t |E(t) − E(0) − W(t)|`` over the recorded rows (J; net
    of the torques' work, :func:`energy_drift_J`)."""
    import numpy as np

    n = result.theta_rad.shape[1]
    energy_J = result.kinetic_J + result.potential_J
    figures = {"t_end_s": float(result.t_s[-1])}
    figures.update(
        {f"theta{i}_end_rad": float(result.theta_rad[-1, i - 1]) for i in range(1, n + 1)}
    )
    figures.update(
        {f"omega{i}_end_rad_s": float(result.omega_rad_s[-1, i - 1]) for i in range(1, n + 1)}
    )
    drift_J = energy_drift_J(energy_J, result.theta_rad, job.spec.torques_Nm)
    figures["energy_drift_max_J"] = float(np.max(np.abs(drift_J)))
    return figures


def figure_names(job: Job[Any, Any]) -> tuple[str, ...]:
    """The columns :func:`point_figures` reports for ``job``, without running it."""
    n = job.robot.n_links
    return (
        "t_end_s",
        *(f"theta{i}_end_rad" for i in range(1, n + 1)),
        *(f"omega{i}_end_rad_s" for i in range(1, n + 1)),
        "energy_drift_max_J",
    )


JOB_KIND = JobKind(
    name="simulate",
    robot_kind="robot",
    settings=SimulateSpec,
    run=run_simulate,
    summary="RK4 forward dynamics under constant torques",
    point_figures=point_figures,
    command=Command(
        "simulate",
        "Integrate the forward dynamics (RK4) of every simulate job; one CSV per job.",
    ),
    tab=Tab("Simulate", 3, "planar_tui.app.widgets.simulate_pane:SimulatePane"),
    figure="planar_tui.figures.simulate:from_result",
    warmup="[simulate]\nduration_s = 0.002\nstep_s = 0.001\n",
    figure_names=figure_names,
    estimate=estimate,
    app_default={
        "duration_s": 1.0,
        "step_s": 0.001,
        "torques_Nm": [],
        "every": 10,
        "output": "app-simulate.csv",
    },
)

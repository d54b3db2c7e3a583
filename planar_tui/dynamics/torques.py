"""The ``[torques]`` job: inverse dynamics ``τ = I θ̈ + C θ̇ − γ`` at listed states."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from planar_tui.csvio import CsvTable
from planar_tui.dynamics.robot import SerialRobot, rk4_step_seconds
from planar_tui.jobkind import Command, Job, JobKind, JobResult, PreparedJob, Tab
from planar_tui.limits import memory_problem, time_problem
from planar_tui.progress import Progress
from planar_tui.schema import PER_LINK, TableReader, number_rows, plot_setting, setting

if TYPE_CHECKING:
    import numpy as np


def _zero_rows(robot: SerialRobot, values: dict[str, Any]) -> tuple[tuple[float, ...], ...]:
    """Default of a state array: zeros, as many rows as ``theta_deg``."""
    return ((0.0,) * robot.n_links,) * len(values["theta_deg"])


def _rows(doc: str, required: bool = False) -> Any:
    reader = number_rows(columns=PER_LINK)
    if required:
        return setting(reader, type_doc="rows of n numbers", doc=doc)
    return setting(
        reader, type_doc="rows of n numbers", doc=doc, default=_zero_rows, default_doc="zeros"
    )


@dataclass(frozen=True, kw_only=True)
class TorquesSpec:
    """States (rows of relative joint angles, rates, accelerations) to evaluate."""

    theta_deg: tuple[tuple[float, ...], ...] = _rows(
        "relative joint angles, one state per row", required=True
    )
    omega_deg_s: tuple[tuple[float, ...], ...] = _rows("joint rates, as many rows as `theta_deg`")
    alpha_deg_s2: tuple[tuple[float, ...], ...] = _rows("joint accelerations, as many rows")
    plot: str | None = plot_setting()

    @staticmethod
    def check(values: dict[str, Any], reader: TableReader, robot: SerialRobot) -> dict[str, Any]:
        """Every array has as many rows as ``theta_deg``; the job fits the time and memory
        limits (:func:`torques_estimate`, :mod:`planar_tui.limits`)."""
        count = len(values["theta_deg"])
        for name in ("omega_deg_s", "alpha_deg_s2"):
            if len(values[name]) != count:
                raise reader.error(
                    name, f"has {len(values[name])} rows", f"{count}, as many as theta_deg"
                )
        memory, seconds = torques_estimate(count, robot.n_links)
        problem = time_problem(seconds) or memory_problem(memory)
        if problem is not None:
            raise reader.error(
                "theta_deg", f"{count:,} states of {robot.n_links} links {problem}", "fewer states"
            )
        return values


#: Memory per cell of a state (``4n`` cells a state: θ, θ̇, θ̈, τ): the preset's parsed
#: values, the arrays, the CSV's text. Measured: 60 000 states of a 2R took 146 MB above
#: the process's own 170 MB (304 bytes a cell).
BYTES_PER_STATE_CELL = 320


def torques_estimate(n_states: int, n_links: int) -> tuple[float, float]:
    """``(memory_bytes, seconds)`` of ``n_states`` states: ``4 n`` cells of
    :data:`BYTES_PER_STATE_CELL` each; one dynamics evaluation each, a quarter of an RK4
    step (:func:`~planar_tui.dynamics.robot.rk4_step_seconds`)."""
    cells = n_states * 4 * n_links
    return cells * BYTES_PER_STATE_CELL, n_states * rk4_step_seconds(n_links) / 4


def estimate(job: Job[TorquesSpec, SerialRobot]) -> tuple[float, float]:
    """``(memory_bytes, seconds)`` of ``job`` (:func:`torques_estimate`)."""
    return torques_estimate(len(job.spec.theta_deg), job.robot.n_links)


@dataclass(frozen=True, kw_only=True)
class TorquesResult(JobResult):
    """The joint torques, one row per state (N m)."""

    tau_Nm: np.ndarray


def torques_header(n_links: int) -> tuple[str, ...]:
    """CSV columns of the torques job: the state in SI units, then the joint torques."""
    joints = range(1, n_links + 1)
    return (
        *(f"theta{i}_rad" for i in joints),
        *(f"omega{i}_rad_s" for i in joints),
        *(f"alpha{i}_rad_s2" for i in joints),
        *(f"tau{i}_Nm" for i in joints),
    )


def run_torques(
    job: PreparedJob[TorquesSpec, SerialRobot, None] | Job[TorquesSpec, SerialRobot],
    progress: Progress,
) -> TorquesResult:
    """Evaluate the inverse dynamics at every listed state (one batched kernel call)."""
    import numpy as np

    from planar_tui.kernels.dynamics_batch import inverse_dynamics_batch_states

    spec, robot = job.spec, job.robot
    theta = np.radians(np.array(spec.theta_deg, dtype=np.float64))
    omega = np.radians(np.array(spec.omega_deg_s, dtype=np.float64))
    alpha = np.radians(np.array(spec.alpha_deg_s2, dtype=np.float64))
    progress.start(len(theta), "inverse dynamics")
    lengths_m, masses_kg, inertias_kgm2 = robot.arrays()
    tau = inverse_dynamics_batch_states(
        lengths_m, masses_kg, inertias_kgm2, robot.gravity_m_s2, theta, omega, alpha
    )
    progress.advance(len(theta))
    rows = np.column_stack([theta, omega, alpha, tau])
    peak = np.abs(tau).max(axis=0)
    return TorquesResult(
        table=CsvTable(torques_header(robot.n_links), rows),
        summary=f"{len(theta)} states, max |tau| = [{', '.join(f'{v:.4g}' for v in peak)}] N m",
        tau_Nm=tau,
    )


def point_figures(job: Job[TorquesSpec, SerialRobot], result: TorquesResult) -> dict[str, float]:
    """A sweep row's figures: per joint the largest ``|τ_i|`` over the states (N m)."""
    import numpy as np

    peak = np.abs(result.tau_Nm).max(axis=0)
    return {f"tau{i}_abs_max_Nm": float(v) for i, v in enumerate(peak, start=1)}


def figure_names(job: Job[Any, Any]) -> tuple[str, ...]:
    """The columns :func:`point_figures` reports for ``job``, without running it."""
    return tuple(f"tau{i}_abs_max_Nm" for i in range(1, job.robot.n_links + 1))


JOB_KIND = JobKind(
    name="torques",
    robot_kind="robot",
    settings=TorquesSpec,
    run=run_torques,
    summary="inverse dynamics at listed states",
    point_figures=point_figures,
    command=Command(
        "torques",
        "Inverse dynamics at the listed states of every torques job; one CSV per job.",
    ),
    tab=Tab("Torques", 4, "planar_tui.app.widgets.torques_pane:TorquesPane"),
    figure="planar_tui.figures.torques:from_result",
    warmup="[torques]\ntheta_deg = [[0, 10]]\n",
    figure_names=figure_names,
    estimate=estimate,
)

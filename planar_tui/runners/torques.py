"""Runner of the ``[torques]`` job: inverse dynamics ``τ = I θ̈ + C θ̇ − γ`` per state."""

from __future__ import annotations

import numpy as np

from planar_tui.csvio import CsvTable
from planar_tui.jobs.base import JobResult
from planar_tui.presets import Job
from planar_tui.progress import Progress


def torques_header(n_links: int) -> tuple[str, ...]:
    """CSV columns of the torques job: the state in SI units, then the joint torques."""
    joints = range(1, n_links + 1)
    return (
        *(f"theta{i}_rad" for i in joints),
        *(f"omega{i}_rad_s" for i in joints),
        *(f"alpha{i}_rad_s2" for i in joints),
        *(f"tau{i}_Nm" for i in joints),
    )


def run_torques(job: Job, progress: Progress) -> JobResult:
    """Evaluate the inverse dynamics at every listed state (one batched kernel call)."""
    from kernels.dynamics import inverse_dynamics_batch_states

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
    return JobResult(
        table=CsvTable(torques_header(robot.n_links), rows),
        summary=f"{len(theta)} states, max |tau| = [{', '.join(f'{v:.4g}' for v in peak)}] N m",
        data={"tau_Nm": tau},
    )

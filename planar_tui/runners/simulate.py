"""Runner of the ``[simulate]`` job: chunked RK4 with progress and cancellation."""

from __future__ import annotations

import numpy as np

from planar_tui.csvio import CsvTable
from planar_tui.jobs.base import JobResult
from planar_tui.presets import Job
from planar_tui.progress import Progress

#: RK4 steps per kernel call: about 30 ms for a 6R robot, so Cancel is honoured quickly.
STEPS_PER_CHUNK = 20_000


def simulate_header(n_links: int) -> tuple[str, ...]:
    """CSV columns of a simulation: time, relative angles, rates, energies (SI units)."""
    return (
        "t_s",
        *(f"theta{i}_rad" for i in range(1, n_links + 1)),
        *(f"omega{i}_rad_s" for i in range(1, n_links + 1)),
        "kinetic_J",
        "potential_J",
        "energy_J",
    )


def run_simulate(job: Job, progress: Progress) -> JobResult:
    """Integrate the forward dynamics ``θ̈ = I⁻¹(τ + γ − C θ̇)`` with classical RK4.

    Records every ``spec.every``-th step including t = 0; ``result.data`` holds the
    arrays ``t_s, theta_rad, omega_rad_s, kinetic_J, potential_J`` for plots.
    """
    from kernels.rk4 import rk4_integrate, rk4_record_count

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
    while done < n_steps:
        chunk = min(STEPS_PER_CHUNK, n_steps - done)
        row += rk4_integrate(
            lengths_m, masses_kg, inertias_kgm2, robot.gravity_m_s2, torque, theta, omega,
            spec.step_s, chunk, spec.every, done,
            t_s[row:], theta_rad[row:], omega_rad_s[row:], kinetic_J[row:], potential_J[row:],
        )  # fmt: skip
        done += chunk
        progress.advance(chunk, f"t = {done * spec.step_s:.4g} s")
    if row != rows:
        raise RuntimeError(f"RK4 wrote {row} records, expected {rows}")

    energy_J = kinetic_J + potential_J
    table = np.column_stack([t_s, theta_rad, omega_rad_s, kinetic_J, potential_J, energy_J])
    summary = f"{n_steps} RK4 steps, {rows} rows, t_end = {t_s[-1]:.6g} s"
    if not torque.any():
        drift_J = float(np.max(np.abs(energy_J - energy_J[0])))
        summary += f", max |E - E0| = {drift_J:.2e} J"
    return JobResult(
        table=CsvTable(simulate_header(n), table),
        summary=summary,
        data={
            "t_s": t_s,
            "theta_rad": theta_rad,
            "omega_rad_s": omega_rad_s,
            "kinetic_J": kinetic_J,
            "potential_J": potential_J,
        },
    )

"""The simulation checks for cancel by elapsed work, not a fixed step count: a 400-link
robot (about 0.2 ms per RK4 step, the O(n) forward dynamics) stops within a second of being
asked, and the chunked run stays bit-identical to one kernel call."""

from __future__ import annotations

import time

import numpy as np
import pytest

from planar_tui.dynamics.simulate import next_chunk_steps, run_simulate
from planar_tui.errors import Cancelled
from planar_tui.presets import parse_preset
from planar_tui.progress import Progress


def simulate_job(n_links: int, n_steps: int, step_s: float = 1e-3, every: int = 1):
    document = {
        "robot": {"lengths_m": [0.1] * n_links, "masses_kg": [0.1] * n_links},
        "simulate": {
            "duration_s": n_steps * step_s,
            "step_s": step_s,
            "theta0_deg": [3.0] * n_links,
            "torques_Nm": [0.01] * n_links,
            "every": every,
        },
    }
    (job,) = parse_preset("chunks.toml", document).jobs
    return job


def test_a_400_link_simulation_is_cancelled_promptly():
    """Within 5 s of being asked (25x the 0.2 s goal of benchmarks/bench_cancel.py; the
    run takes about 25 s, so a kernel that ignores the cancel fails this)."""
    job = simulate_job(400, 150_000, every=1000)  # about 25 s of RK4 at 0.17 ms per step
    ask_at: list[float] = []

    def on_update(state) -> None:
        if state.completed > 0 and not ask_at:  # the kernel is compiled and running
            ask_at.append(time.perf_counter() + 0.3)

    def should_stop() -> bool:
        return bool(ask_at) and time.perf_counter() >= ask_at[0]

    with pytest.raises(Cancelled):
        run_simulate(job, Progress(on_update, should_stop))
    latency_s = time.perf_counter() - ask_at[0]
    assert latency_s <= 5.0, f"cancelled {latency_s:.2f} s after being asked"


def test_adaptively_chunked_run_is_bit_identical_to_one_kernel_call():
    from planar_tui.kernels.rk4 import rk4_integrate, rk4_record_count

    job = simulate_job(6, 45_000, step_s=2e-5)  # many chunk sizes, the largest capped
    sizes: list[float] = []
    result = run_simulate(job, Progress(lambda state: sizes.append(state.completed)))
    assert len(sizes) > 5  # it was chunked

    robot, spec = job.robot, job.spec
    n = robot.n_links
    rows = rk4_record_count(spec.n_steps, 1)
    out = [np.empty(rows), np.empty((rows, n)), np.empty((rows, n)), np.empty(rows)]
    out.append(np.empty(rows))
    theta = np.radians(np.array(spec.theta0_deg))
    omega = np.zeros(n)
    torque = np.array(spec.torques_Nm)
    rk4_integrate(
        *robot.arrays(),
        robot.gravity_m_s2,
        torque,
        theta,
        omega,
        spec.step_s,
        spec.n_steps,
        1,
        0,
        *out,
    )
    assert result.t_s.tobytes() == out[0].tobytes()
    assert result.theta_rad.tobytes() == out[1].tobytes()
    assert result.omega_rad_s.tobytes() == out[2].tobytes()
    assert result.kinetic_J.tobytes() == out[3].tobytes()


def test_the_chunk_rule_grows_to_about_50_ms_with_or_without_a_cap():
    """One rule for every time-stepping job: fast calls grow 8-fold (the simulate job's
    capped at its 20 000 steps, the motion job's not), slow ones shrink to about 0.05 s of
    work, never past the steps left, at least one step."""
    assert next_chunk_steps(10_000, 0.001, 10**9, 20_000) == 20_000
    assert next_chunk_steps(10_000, 0.001, 10**9) == 80_000
    assert next_chunk_steps(1_000, 0.01, 10**9) == 5_000  # 1000 × 0.05 / 0.01
    assert next_chunk_steps(100, 0.5, 10**9) == 10
    assert next_chunk_steps(100, 0.0, 50) == 50
    assert next_chunk_steps(5, 10.0, 100) == 1

# ruff: noqa: E402  (the repository root goes on sys.path and numba is set up first)
"""Benchmark of the motion uncertainty job (``python benchmarks/bench_motion.py``).

Rows (kernels warmed first, baselines in the same process, each timing the best of
``--repeats``):

* ``rk4_integrate`` (the simulate job's kernel) on the Table 1 robot, 1 s at 1e-4 s, one
  robot after another: the scalar baseline time per robot;
* the scalar batched kernel ``rk4_batch`` (one robot at a time, ``prange`` over robots) on
  ``--scalar-robots`` (256) Table 1 robots with their own parameters (±1 mm, ±10 g);
* the lane-batched kernel ``rk4_lanes`` (the motion job's, ``LANES`` robots per SIMD block) on
  ``--robots`` (2048) such robots, 1 thread and 2 threads: time per robot, ratios to the
  scalar kernels and to MuJoCo, 2-thread speed-up; the 6-link Table 1 chain takes its fused
  step (``kernels/motion_lanes_n6.py``);
* the general lane kernel (``rk4_lanes_general``, what the motion job ran before
  the fused step) on the same robots, 1 thread: the fused step's baseline;
* MuJoCo's multi-robot ``mujoco.rollout`` (RK4, 1e-4 s, each robot its own ``MjModel``,
  the torques as ``qfrc_applied``) on ``--mujoco-robots`` (64) robots, one thread;
* with ``--asm``: the packed (ymm/zmm) and scalar double-precision instructions in the
  machine code of the lane kernels' forward dynamics and of the fused step (compiled
  afresh: numba cannot show the assembly of cached code);
* a GPU column when a usable CUDA GPU is present (``--gpu-robots``, 65 536), else one line
  saying why it is skipped;
* the Sobol' study of the Table 1 robot (12 inputs, ``--sobol-samples`` N = 1024, i.e.
  N (D + 2) robots) end to end through the CLI (``planar-tui motion
  paper-a-table1-motion --samples N``) in a fresh process on 2 threads.

``--cpu-time`` times the one-thread rows by the calling thread's CPU time (robust to the
load of a shared machine); the 2-thread row stays wall time.

Goals (issue 21): ≤ 2.0 ms per robot on one thread and ≥ 40× MuJoCo's rollout, ≥ 1.9× on 2
threads; (issue 11) 65 536 robots ≤ 3 s on an H100.
"""

import argparse
import os
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numba
import numpy as np

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from planar_tui.runtime import prepare_kernels

prepare_kernels()  # before any kernel is imported

from planar_tui.kernels.motion_lanes import LANES, rk4_lanes, rk4_lanes_general
from planar_tui.kernels.motion_rk4 import design_parameters, rk4_batch
from planar_tui.kernels.rk4 import rk4_integrate

from benchmarks.mujoco_model import chain_model
from planar_tui.motion.engine import run_lanes

G = 9.81
LENGTHS = np.array([0.25, 0.25, 0.20, 0.20, 0.15, 0.15])
MASSES = np.array([0.484, 0.484, 0.387, 0.387, 0.290, 0.290])
INERTIAS = np.array([2.54e-3, 2.54e-3, 1.31e-3, 1.31e-3, 5.61e-4, 5.61e-4])
TORQUES = np.array([2.0, 0.3, 0.1, 0.03, 0.03, 0.001])
STEP_S, N_STEPS = 1e-4, 10_000
#: Clock of the one-thread rows: wall time, or with ``--cpu-time`` the CPU time of the
#: calling thread (it runs the work of a one-thread ``prange`` and of ``rollout``), which the
#: other engineers' processes on this shared machine disturb far less than the wall clock.
#: The 2-thread row is always wall time (its speed-up is what it measures).
one_thread_clock = time.perf_counter


def loadavg() -> str:
    return " ".join(Path("/proc/loadavg").read_text().split()[:3])


def table1_design(robots: int, seed: int = 1):
    """Unit design, bounds: every length ± 1 mm, every mass ± 10 g."""
    unit = np.random.default_rng(seed).random((robots, 12))
    centre = np.concatenate([LENGTHS, MASSES])
    half = np.concatenate([np.full(6, 1e-3), np.full(6, 1e-2)])
    return unit, centre - half, centre + half


def baseline_ms(robots: int = 8) -> float:
    """``rk4_integrate`` per robot, one after another (best of the robots)."""
    records = [np.empty(2), np.empty((2, 6)), np.empty((2, 6)), np.empty(2), np.empty(2)]
    best = np.inf
    for _ in range(robots):
        theta, omega = np.zeros(6), np.zeros(6)
        started = one_thread_clock()
        rk4_integrate(
            LENGTHS,
            MASSES,
            INERTIAS,
            G,
            TORQUES,
            theta,
            omega,
            STEP_S,
            N_STEPS,
            N_STEPS,
            0,
            *records,
        )
        best = min(best, one_thread_clock() - started)
    return best * 1e3


def cpu_ms(
    robots: int, threads: int, kernel=rk4_lanes, repeats: int = 1
) -> tuple[float, np.ndarray]:
    """Best time per robot (ms) of ``kernel`` on ``robots`` Table 1 robots, and their angles
    (on ``threads`` threads as the motion job runs it: :func:`planar_tui.motion.engine.run_lanes`)."""
    numba.set_num_threads(threads)
    unit, lower, upper = table1_design(robots)
    params = design_parameters(unit, lower, upper, INERTIAS, np.zeros(6, dtype=np.bool_))
    clock = one_thread_clock if threads == 1 else time.perf_counter
    best = np.inf
    for _ in range(repeats):
        theta, omega = np.zeros((robots, 6)), np.zeros((robots, 6))
        started = clock()
        run_lanes(kernel, params, G, TORQUES, theta, omega, STEP_S, N_STEPS)
        best = min(best, clock() - started)
    return best / robots * 1e3, theta


def mujoco_rollout_ms(robots: int, repeats: int = 1) -> tuple[float, np.ndarray]:
    """``mujoco.rollout`` of ``robots`` Table 1 robots, each its own model, one thread:
    best time per robot (ms) and the final angles."""
    import mujoco
    from mujoco import rollout

    unit, lower, upper = table1_design(robots)
    params = design_parameters(unit, lower, upper, INERTIAS, np.zeros(6, dtype=np.bool_))
    models = [chain_model(*params[s], G, timestep_s=STEP_S)[0] for s in range(robots)]
    data = mujoco.MjData(models[0])
    spec = mujoco.mjtState.mjSTATE_FULLPHYSICS
    state = np.zeros(mujoco.mj_stateSize(models[0], spec))
    mujoco.mj_getState(models[0], data, state, spec)
    control_spec = mujoco.mjtState.mjSTATE_QFRC_APPLIED
    control = np.tile(TORQUES, (robots, 1, 1))
    best, states = np.inf, None
    for _ in range(repeats):
        started = one_thread_clock()
        states, _ = rollout.rollout(
            models,
            data,
            np.tile(state, (robots, 1)),
            control,
            control_spec=control_spec,
            nstep=N_STEPS,
        )
        best = min(best, one_thread_clock() - started)
    qpos = states[:, -1, 1 : 1 + 6]  # FULLPHYSICS: time, qpos, qvel, ...
    return best / robots * 1e3, qpos


def packed_instructions() -> str:
    """Packed and scalar double-precision instructions in the lane kernels' forward
    dynamics (NOC and articulated-body), compiled afresh without the cache."""
    import collections

    from numba import njit
    from planar_tui.kernels import motion_lanes

    n, lanes = 6, LANES
    common = (
        np.ones((3, n, lanes)),
        G,
        np.zeros(n),
        np.zeros((n, lanes)),
        np.zeros((n, lanes)),
        np.zeros(9 * n * lanes),
    )
    cases = {
        "_noc_lanes": (
            *common,
            np.zeros((n, n, lanes)),
            np.zeros((4, n, lanes)),
            0,
            np.zeros(9 * lanes),
            np.zeros(3 * lanes),
        ),
        "_aba_lanes": (
            *common,
            np.zeros((4, n, lanes)),
            0,
            np.zeros(9 * lanes),
            np.zeros(3 * lanes),
        ),
    }
    lines = []
    for name, args in cases.items():
        function = njit(error_model="numpy")(getattr(motion_lanes, name).py_func)
        function(*args)
        counts = collections.Counter()
        for line in next(iter(function.inspect_asm().values())).splitlines():
            fields = line.split()
            if not fields or not fields[0].startswith("v"):
                continue
            register = "zmm" if "zmm" in line else "ymm" if "ymm" in line else "xmm"
            if fields[0].endswith("pd") and register != "xmm":
                counts[f"packed {register}"] += 1
            elif fields[0].endswith("sd"):
                counts["scalar sd"] += 1
        lines.append(f"{name}: " + ", ".join(f"{k} {v}" for k, v in sorted(counts.items())))
    from planar_tui.kernels import motion_lanes_n6

    function = njit(error_model="numpy", fastmath={"contract"})(motion_lanes_n6.rk4_step_6.py_func)
    state = np.zeros(motion_lanes_n6.STATE_ROWS * lanes)
    function(np.ones(3 * n * lanes), G, np.zeros(n), state, 1e-4)
    counts = collections.Counter()
    for line in next(iter(function.inspect_asm().values())).splitlines():
        fields = line.split()
        if fields and fields[0].startswith("v"):
            register = "ymm" if "ymm" in line else "xmm"
            if fields[0].endswith("pd") and register == "ymm":
                counts["packed ymm"] += 1
            elif fields[0].endswith("sd"):
                counts["scalar sd"] += 1
            if "fmadd" in fields[0] or "fmsub" in fields[0]:
                counts["FMA"] += 1
    lines.append("rk4_step_6 (fused): " + ", ".join(f"{k} {v}" for k, v in sorted(counts.items())))
    return "; ".join(lines)


def gpu_seconds(robots: int) -> float | str:
    """Seconds for ``robots`` robots on the GPU (parameters made there), or why not."""
    from planar_tui.motion.device import cuda_problem

    problem = cuda_problem()
    if problem is None and os.environ.get("NUMBA_ENABLE_CUDASIM") == "1":
        problem = "numba's CUDA simulator is on (no timing on a simulator)"
    if problem is not None:
        return problem
    from planar_tui.kernels.motion_cuda import CudaBatch

    unit, lower, upper = table1_design(robots)
    zeros = np.zeros((robots, 6))
    warm = CudaBatch(
        unit[:256], lower, upper, INERTIAS, np.zeros(6, bool), zeros[:256], zeros[:256], G, TORQUES
    )
    warm.advance(STEP_S, 2)
    started = time.perf_counter()
    batch = CudaBatch(unit, lower, upper, INERTIAS, np.zeros(6, bool), zeros, zeros, G, TORQUES)
    batch.advance(STEP_S, N_STEPS)
    batch.angles()
    return time.perf_counter() - started


def sobol_study_seconds(samples: int) -> float:
    """``planar-tui motion paper-a-table1-motion --samples N`` in a fresh process, 2 threads."""
    env = {**os.environ, "NUMBA_NUM_THREADS": "2"}
    with tempfile.TemporaryDirectory() as folder:
        command = [
            sys.executable,
            "-m",
            "planar_tui",
            "motion",
            "paper-a-table1-motion",
            "--samples",
            str(samples),
            "--out-dir",
            folder,
        ]
        started = time.perf_counter()
        subprocess.run(command, env=env, check=True, capture_output=True)
        return time.perf_counter() - started


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robots", type=int, default=2048)
    parser.add_argument("--scalar-robots", type=int, default=256)
    parser.add_argument("--mujoco-robots", type=int, default=64)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--asm", action="store_true", help="count vector instructions")
    parser.add_argument("--cpu-time", action="store_true", help="one-thread rows: thread CPU time")
    parser.add_argument("--gpu-robots", type=int, default=65536)
    parser.add_argument("--sobol-samples", type=int, default=0, help="0 skips the study")
    arguments = parser.parse_args()
    repeats = arguments.repeats
    global one_thread_clock
    if arguments.cpu_time:
        one_thread_clock = time.thread_time
    print(
        f"# {platform.machine()} {platform.processor() or ''}, {os.cpu_count()} CPUs, "
        f"numba {numba.__version__}; load {loadavg()}"
    )
    cpu_ms(LANES + 1, 1)  # compile / load the kernels
    cpu_ms(17, 1, rk4_batch)
    baseline = baseline_ms()
    scalar, scalar_theta = cpu_ms(arguments.scalar_robots, 1, rk4_batch, repeats)
    cpu_ms(LANES + 1, 1, rk4_lanes_general)
    general, general_theta = cpu_ms(arguments.robots, 1, rk4_lanes_general, repeats)
    one, lanes_theta = cpu_ms(arguments.robots, 1, rk4_lanes, repeats)
    two, _ = cpu_ms(arguments.robots, 2, rk4_lanes, repeats)
    mujoco, mujoco_theta = mujoco_rollout_ms(arguments.mujoco_robots, max(1, repeats - 1))
    gap = np.abs(lanes_theta[: arguments.scalar_robots] - scalar_theta).max()
    gap_mj = np.abs(lanes_theta[: arguments.mujoco_robots] - mujoco_theta).max()
    clock = "thread CPU time" if arguments.cpu_time else "wall time"
    print(
        f"Table 1 robots (±1 mm, ±10 g), 1 s at 1e-4 s ({N_STEPS} RK4 steps); one-thread rows: "
        f"{clock}, 2 threads: wall time; load {loadavg()}"
    )
    print("| case | ms per robot | ratio to rk4_lanes, 1 thread |")
    print("|---|---:|---:|")
    print(
        f"| rk4_integrate, one robot at a time, 1 thread | {baseline:.2f} | {baseline / one:.2f} |"
    )
    print(
        f"| rk4_batch (scalar), {arguments.scalar_robots} robots, 1 thread | {scalar:.2f} | "
        f"{scalar / one:.2f} |"
    )
    print(
        f"| rk4_lanes_general, {arguments.robots} robots, 1 thread | "
        f"{general:.3f} | {general / one:.2f} |"
    )
    print(
        f"| **rk4_lanes** (fused 6-link step), {arguments.robots} robots, 1 thread | {one:.3f} "
        f"| 1.00 |"
    )
    print(f"| rk4_lanes, {arguments.robots} robots, 2 threads | {two:.3f} | {two / one:.2f} |")
    print(
        f"| MuJoCo rollout, {arguments.mujoco_robots} robots (own models), 1 thread | "
        f"{mujoco:.2f} | {mujoco / one:.1f} |"
    )
    gap_general = np.abs(lanes_theta - general_theta).max()
    print(
        f"max |Δθ| lanes - scalar {gap:.1e} rad, lanes - general lanes {gap_general:.1e} rad, "
        f"lanes - MuJoCo {gap_mj:.1e} rad"
    )
    two_note = (
        "2 threads: wall time, no ratio to the CPU-time row"
        if arguments.cpu_time
        else f"2 threads: {one / two:.2f}× (goal ≥ 1.9×)"
    )
    print(
        f"1 thread: {one:.2f} ms per robot (goal ≤ 2.0), {mujoco / one:.1f}× MuJoCo rollout "
        f"(goal ≥ 40×), {scalar / one:.2f}× the scalar kernel, {general / one:.2f}× the general "
        f"lane kernel; {two_note}"
    )
    if arguments.asm:
        print(f"vector instructions: {packed_instructions()}")
    gpu = gpu_seconds(arguments.gpu_robots)
    if isinstance(gpu, str):
        print(f"GPU column skipped: {gpu}")
    else:
        per_robot = gpu / arguments.gpu_robots * 1e3
        print(
            f"| GPU, {arguments.gpu_robots} robots | {per_robot:.4f} | "
            f"{per_robot / one:.4f} |  total {gpu:.2f} s (goal ≤ 3 s on an H100); "
            f"CPU 2 threads would take {two * arguments.gpu_robots / 1e3:.0f} s"
        )
    if arguments.sobol_samples <= 0:
        print("Sobol' study skipped (--sobol-samples 0)")
        return
    seconds = sobol_study_seconds(arguments.sobol_samples)
    robots = arguments.sobol_samples * 14
    print(
        f"Sobol' study, 12 inputs, N = {arguments.sobol_samples} ({robots} robots) through "
        f"the CLI on 2 threads: {seconds:.1f} s ({seconds / robots * 1e3:.2f} ms per robot); "
        f"load {loadavg()}"
    )


if __name__ == "__main__":
    main()

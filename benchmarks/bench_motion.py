# ruff: noqa: E402  (the repository root goes on sys.path and numba is set up first)
"""Benchmark of the motion uncertainty job (``python benchmarks/bench_motion.py``).

Rows (kernels warmed first, baselines in the same process):

* ``rk4_integrate`` (the simulate job's kernel) on the Table 1 robot, 1 s at 1e-4 s, one
  robot after another: the baseline time per robot;
* the batched CPU kernel ``rk4_batch`` on ``--robots`` (4096) Table 1 robots with their
  own parameters (±1 mm, ±10 g), 1 thread and 2 threads: time per robot, ratio to the
  baseline, 2-thread speed-up;
* a GPU column when a usable CUDA GPU is present (``--gpu-robots``, 65 536), else one line
  saying why it is skipped;
* the Sobol' study of the Table 1 robot (12 inputs, ``--sobol-samples`` N = 1024, i.e.
  N (D + 2) robots) end to end through the CLI (``planar-tui motion
  paper-a-table1-motion --samples N``) in a fresh process on 2 threads.

Goals (issue 11): ≤ 1.0 ms per robot on one core, ≥ 1.8× on 2 cores, 65 536 robots ≤ 3 s on
an H100.
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

from planar_tui.kernels.motion_rk4 import design_parameters, rk4_batch
from planar_tui.kernels.rk4 import rk4_integrate

G = 9.81
LENGTHS = np.array([0.25, 0.25, 0.20, 0.20, 0.15, 0.15])
MASSES = np.array([0.484, 0.484, 0.387, 0.387, 0.290, 0.290])
INERTIAS = np.array([2.54e-3, 2.54e-3, 1.31e-3, 1.31e-3, 5.61e-4, 5.61e-4])
TORQUES = np.array([2.0, 0.3, 0.1, 0.03, 0.03, 0.001])
STEP_S, N_STEPS = 1e-4, 10_000


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
        started = time.perf_counter()
        rk4_integrate(LENGTHS, MASSES, INERTIAS, G, TORQUES, theta, omega, STEP_S, N_STEPS,
                      N_STEPS, 0, *records)  # fmt: skip
        best = min(best, time.perf_counter() - started)
    return best * 1e3


def cpu_ms(robots: int, threads: int) -> float:
    numba.set_num_threads(threads)
    unit, lower, upper = table1_design(robots)
    params = design_parameters(unit, lower, upper, INERTIAS, np.zeros(6, dtype=np.bool_))
    theta, omega = np.zeros((robots, 6)), np.zeros((robots, 6))
    started = time.perf_counter()
    rk4_batch(params, G, TORQUES, theta, omega, STEP_S, N_STEPS)
    return (time.perf_counter() - started) / robots * 1e3


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
    warm = CudaBatch(unit[:256], lower, upper, INERTIAS, np.zeros(6, bool), zeros[:256],
                     zeros[:256], G, TORQUES)  # fmt: skip
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
        command = [sys.executable, "-m", "planar_tui", "motion", "paper-a-table1-motion",
                   "--samples", str(samples), "--out-dir", folder]  # fmt: skip
        started = time.perf_counter()
        subprocess.run(command, env=env, check=True, capture_output=True)
        return time.perf_counter() - started


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robots", type=int, default=4096)
    parser.add_argument("--gpu-robots", type=int, default=65536)
    parser.add_argument("--sobol-samples", type=int, default=1024, help="0 skips the study")
    arguments = parser.parse_args()
    print(f"# {platform.machine()} {platform.processor() or ''}, {os.cpu_count()} CPUs, "
          f"numba {numba.__version__}; load {loadavg()}")  # fmt: skip
    cpu_ms(16, 1)  # compile / load the kernels
    baseline = baseline_ms()
    one = cpu_ms(arguments.robots, 1)
    two = cpu_ms(arguments.robots, 2)
    gpu = gpu_seconds(arguments.gpu_robots)
    print(f"Table 1 robot, 1 s at 1e-4 s ({N_STEPS} RK4 steps); load {loadavg()}")
    print("| case | ms per robot | ratio to rk4_integrate |")
    print("|---|---:|---:|")
    print(f"| rk4_integrate, one robot at a time | {baseline:.2f} | 1.00 |")
    print(f"| rk4_batch, {arguments.robots} robots, 1 thread | {one:.2f} | {one / baseline:.2f} |")
    print(f"| rk4_batch, {arguments.robots} robots, 2 threads | {two:.2f} | {two / baseline:.2f} |")
    print(f"2-thread speed-up: {one / two:.2f}× (goal ≥ 1.8×); 1 core: {one:.2f} ms per robot "
          "(goal ≤ 1.0 ms)")  # fmt: skip
    if isinstance(gpu, str):
        print(f"GPU column skipped: {gpu}")
    else:
        per_robot = gpu / arguments.gpu_robots * 1e3
        print(f"| GPU, {arguments.gpu_robots} robots | {per_robot:.4f} | "
              f"{per_robot / baseline:.4f} |  total {gpu:.2f} s (goal ≤ 3 s on an H100); "
              f"CPU 2 threads would take {two * arguments.gpu_robots / 1e3:.0f} s")  # fmt: skip
    if arguments.sobol_samples <= 0:
        print("Sobol' study skipped (--sobol-samples 0)")
        return
    seconds = sobol_study_seconds(arguments.sobol_samples)
    robots = arguments.sobol_samples * 14
    print(f"Sobol' study, 12 inputs, N = {arguments.sobol_samples} ({robots} robots) through "
          f"the CLI on 2 threads: {seconds:.1f} s ({seconds / robots * 1e3:.2f} ms per robot); "
          f"load {loadavg()}")  # fmt: skip


if __name__ == "__main__":
    main()

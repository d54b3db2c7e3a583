# ruff: noqa: E402  (the repository root goes on sys.path and numba is set up first)
"""Benchmark of the NOC dynamics kernels (``python benchmarks/bench_dynamics.py``).

Rows (JIT warmed first, best of several repeats, baselines run in the same process):

* batched 6R inverse dynamics, 10^6 samples with their own parameters, 1 and 2 threads;
* MuJoCo ``mj_inverse`` in a Python loop, writing body_mass / body_inertia / body_pos /
  body_ipos per sample (10^4 samples, scaled per sample);
* a NumPy-vectorised Newton-Euler (loop over links, arrays over samples), 10^6 samples;
* the paper A Table 1 simulation (6R, 1 s, RK4 step 1e-4 s): ``rk4_integrate`` vs MuJoCo's
  own RK4 ``mj_step`` in a Python loop (10^4 steps), with the time per forward-dynamics
  call (simulation / 4·10^4, and ``forward_dynamics_into`` alone in a jitted loop);
* one inverse / forward dynamics evaluation for n = 2..64 with the fitted exponent of
  time ~ n^p (called from Python, and from a jitted loop, which removes the dispatch cost);
* ``--part forward`` (also part of ``all``, the default): forward dynamics per call at
  n = 6, 20, 100, 1000 (random robots and states) by the NOC mass matrix + ``LDLᵀ`` and by the
  O(n) articulated-body algorithm (``kernels/aba_planar.py``), in a jitted loop and called
  from Python, against Pinocchio's ``aba`` called from Python (the ``bench`` extra), with
  the largest difference; the crossover table n = 2..16 (NOC vs ABA in a jitted loop); and
  one RK4 step (``rk4_integrate``) against MuJoCo's RK4 step (``mujoco.rollout`` of one
  robot: MuJoCo's own C loop, no Python per step).

Goals (issue 21): faster than Pinocchio's ``aba`` at n = 20, 100, 1000; one RK4 step faster
than MuJoCo's at every n.
"""

import argparse
import datetime
import os
import platform
import sys
import time
from functools import partial
from pathlib import Path

import numba
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from planar_tui.runtime import prepare_kernels

prepare_kernels()  # before any kernel is imported

from planar_tui.kernels._jit import kernel
from planar_tui.kernels.aba_planar import ABA_WORK_ROWS, aba_forward_dynamics, aba_rows
from planar_tui.kernels.dynamics import (
    _forward_dynamics_rows,
    forward_dynamics,
    forward_dynamics_into,
    forward_dynamics_work,
    inverse_dynamics,
)
from planar_tui.kernels.dynamics_batch import inverse_dynamics_batch
from planar_tui.kernels.rk4 import rk4_integrate, rk4_record_count

from benchmarks.baselines import import_pinocchio, numpy_newton_euler, pinocchio_chain
from benchmarks.mujoco_model import chain_model, set_chain_parameters

G = 9.81
LENGTHS = np.array([0.25, 0.25, 0.20, 0.20, 0.15, 0.15])
MASSES = np.array([0.484, 0.484, 0.387, 0.387, 0.290, 0.290])
INERTIAS = np.array([2.54e-3, 2.54e-3, 1.31e-3, 1.31e-3, 5.61e-4, 5.61e-4])
TORQUES = np.array([2.0, 0.3, 0.1, 0.03, 0.03, 0.001])


def best_time(function, repeats=5):
    """Best wall time of ``function()`` in seconds."""
    best = np.inf
    for _ in range(repeats):
        start = time.perf_counter()
        function()
        best = min(best, time.perf_counter() - start)
    return best


def samples(count, rng):
    """Parameters of ``count`` 6R robots: nominal ± 1 mm, ± 10 g, inertias ± 1 %."""
    lengths = LENGTHS + rng.uniform(-1e-3, 1e-3, (count, 6))
    masses = MASSES + rng.uniform(-1e-2, 1e-2, (count, 6))
    inertias = INERTIAS * rng.uniform(0.99, 1.01, (count, 6))
    return lengths, masses, inertias


def mujoco_inverse_loop(lengths, masses, inertias, theta, omega, alpha):
    import mujoco

    model, data = chain_model(LENGTHS, MASSES, INERTIAS, G)
    data.qpos[:], data.qvel[:], data.qacc[:] = theta, omega, alpha
    out = np.empty_like(lengths)
    for s in range(lengths.shape[0]):
        set_chain_parameters(model, lengths[s], masses[s], inertias[s])
        mujoco.mj_inverse(model, data)
        out[s] = data.qfrc_inverse
    return out


def simulate_kernel(every):
    steps = 10_000
    rows = rk4_record_count(steps, every)
    theta, omega = np.zeros(6), np.zeros(6)
    outputs = (
        np.zeros(rows),
        np.zeros((rows, 6)),
        np.zeros((rows, 6)),
        np.zeros(rows),
        np.zeros(rows),
    )
    rk4_integrate(
        LENGTHS, MASSES, INERTIAS, G, TORQUES, theta, omega, 1e-4, steps, every, 0, *outputs
    )
    return theta


def simulate_mujoco():
    import mujoco

    model, data = chain_model(LENGTHS, MASSES, INERTIAS, G, timestep_s=1e-4)
    data.qfrc_applied[:] = TORQUES
    for _ in range(10_000):
        mujoco.mj_step(model, data)
    return data.qpos.copy()


@kernel
def _repeat(count, forward, lengths, masses, inertias, theta, omega, alpha_or_tau):
    """``count`` calls of inverse (or forward) dynamics inside compiled code."""
    total = 0.0
    for _ in range(count):
        theta[0] += 1e-12
        if forward:
            total += forward_dynamics(lengths, masses, inertias, 9.81, theta, omega, alpha_or_tau)[
                0
            ]
        else:
            total += inverse_dynamics(lengths, masses, inertias, 9.81, theta, omega, alpha_or_tau)[
                0
            ]
    return total


@kernel
def _repeat_forward_into(count, lengths, masses, inertias, theta, omega, tau):
    """``count`` allocation-free forward dynamics (the RK4 stage evaluation) in compiled code."""
    work, matrix = forward_dynamics_work(lengths.shape[0])
    alpha = np.empty(lengths.shape[0])
    total = 0.0
    for _ in range(count):
        theta[0] += 1e-12
        forward_dynamics_into(
            lengths, masses, inertias, 9.81, theta, omega, tau, work, matrix, alpha
        )
        total += alpha[0]
    return total


def _python_calls(count, lengths, masses, inertias, theta, omega, alpha):
    for _ in range(count):
        inverse_dynamics(lengths, masses, inertias, G, theta, omega, alpha)


def scaling(rng):
    """Per-call times (s) for n in 2..64: Python call of inverse_dynamics, jitted loops."""
    calls = 20_000
    table = []
    for n in [2, 4, 8, 16, 32, 64]:
        lengths, masses = rng.uniform(0.1, 0.3, n), rng.uniform(0.2, 1.0, n)
        inertias = masses * lengths**2 / 12
        args = (lengths, masses, inertias, *rng.normal(size=(3, n)))
        _repeat(1, False, *args)
        _repeat(1, True, *args)
        times = [
            best_time(partial(_python_calls, calls, *args)),
            best_time(partial(_repeat, calls, False, *args), 9),
            best_time(partial(_repeat, calls, True, *args), 9),
        ]
        table.append((n, *(t / calls for t in times)))
    return table


def exponent(sizes, times):
    """Least-squares slope of log(time) on log(n) over n >= 8 (past the fixed overheads)."""
    sizes, times = np.asarray(sizes, float), np.asarray(times)
    keep = sizes >= 8
    return np.polyfit(np.log(sizes[keep]), np.log(times[keep]), 1)[0]


@kernel
def _repeat_forward_algorithm(count, aba, lengths, masses, inertias, theta, omega, tau):
    """``count`` forward dynamics in compiled code by one algorithm: the articulated-body
    recursion (``aba``) or the NOC mass matrix + LDLᵀ."""
    n = lengths.shape[0]
    work = np.zeros((ABA_WORK_ROWS, n))
    matrix = np.zeros((n, n))
    alpha = np.empty((1, n))
    total = 0.0
    for _ in range(count):
        theta[0] += 1e-12
        if aba:
            aba_rows(lengths, masses, inertias, 9.81, theta, omega, tau, work, alpha, 0)
        else:
            _forward_dynamics_rows(
                lengths, masses, inertias, 9.81, theta, omega, tau, work, matrix, alpha, 0, True
            )
        total += alpha[0, 0]
    return total


#: Pinocchio's Data of an n-joint chain takes about n³ · 65 bytes (measured: 1.7 GB at 300).
PINOCCHIO_MAX_LINKS = 300


def random_chain(rng, n):
    lengths, masses = rng.uniform(0.1, 0.3, n), rng.uniform(0.2, 1.0, n)
    inertias = masses * lengths**2 / 12
    theta, omega, tau = rng.uniform(-0.3, 0.3, n), rng.normal(0, 1, n), rng.normal(0, 1, n)
    return lengths, masses, inertias, theta, omega, tau


def forward_part(rng):
    """Forward dynamics per call vs Pinocchio's ``aba``, the crossover, one RK4 step vs MuJoCo."""
    import mujoco
    from mujoco import rollout

    pin = import_pinocchio()
    rows = []
    for n in (6, 20, 100, 300, 1000):
        lengths, masses, inertias, theta, omega, tau = random_chain(rng, n)
        calls = max(3, int(2e6 / n)) if n < 1000 else 2000
        noc_calls = max(3, int(2e6 / n**2.2))
        args = (lengths, masses, inertias, theta.copy(), omega, tau)
        for aba in (True, False):
            _repeat_forward_algorithm(1, aba, *args)
        aba_jit = best_time(partial(_repeat_forward_algorithm, calls, True, *args), 5) / calls
        noc_jit = best_time(partial(_repeat_forward_algorithm, noc_calls, False, *args), 3)
        noc_jit /= noc_calls
        py_calls = max(3, calls // 10)

        def our_calls(c=py_calls, a=args):
            for _ in range(c):
                aba_forward_dynamics(*a[:3], G, *a[3:])

        ours_py = best_time(our_calls) / py_calls
        times = (
            f"ABA jit {aba_jit * 1e9:.0f} | NOC jit {noc_jit * 1e9:.0f} | ABA from Python "
            f"{ours_py * 1e9:.0f}"
        )
        if n > PINOCCHIO_MAX_LINKS:
            rows.append(
                (f"n = {n}: forward dynamics per call (Pinocchio: see note)", times + " ns", "")
            )
            continue
        model, data = pinocchio_chain(lengths, masses, inertias, G)

        def pinocchio_calls(c=py_calls, m=model, d=data, state=(theta, omega, tau)):
            for _ in range(c):
                pin.aba(m, d, *state)

        pin_py = best_time(pinocchio_calls) / py_calls
        reference = pin.aba(model, data, theta, omega, tau).copy()
        ours = aba_forward_dynamics(lengths, masses, inertias, G, theta, omega, tau)
        gap = np.abs(reference - ours).max() / np.abs(reference).max()
        del model, data
        print(f"  forward dynamics n = {n} done", file=sys.stderr, flush=True)
        rows.append(
            (
                f"n = {n}: forward dynamics per call (max |Δθ̈| / max |θ̈| vs Pinocchio {gap:.0e})",
                times + f" | Pinocchio aba from Python {pin_py * 1e9:.0f} ns",
                f"Pin/ours {pin_py / ours_py:.2f} (Python), {pin_py / aba_jit:.2f} (jit)",
            )
        )
    rows.append(
        (
            f"note: Pinocchio {pin.__version__}'s Data grows as n³ (1.7 GB at n = 300, about "
            f"60 GB at n = 1000): not run above n = {PINOCCHIO_MAX_LINKS}",
            "",
            "",
        )
    )
    crossover = []
    for n in range(2, 17):
        args = (
            *random_chain(rng, n)[:3],
            rng.uniform(-0.3, 0.3, n),
            rng.normal(0, 1, n),
            rng.normal(0, 1, n),
        )
        times = []
        for aba in (False, True):
            _repeat_forward_algorithm(1, aba, *args)
            times.append(best_time(partial(_repeat_forward_algorithm, 20_000, aba, *args), 7))
        crossover.append(f"{n}: {times[0] / times[1]:.2f}")
    rows.append(("crossover: NOC time / ABA time (jit loop), n: ratio", ", ".join(crossover), ""))
    for n in (6, 20, 100, 1000):
        lengths, masses, inertias, theta, omega, tau = random_chain(rng, n)
        steps = max(20, int(2e5 / n))
        records = [np.zeros(2), np.zeros((2, n)), np.zeros((2, n)), np.zeros(2), np.zeros(2)]

        def ours(steps=steps, args=(lengths, masses, inertias, G, tau), q=theta, records=records):
            rk4_integrate(*args, q.copy(), np.zeros(len(q)), 1e-4, steps, 10**9, 1, *records)

        ours()
        ours_step = best_time(ours, 3) / steps
        model, data = chain_model(lengths, masses, inertias, G, timestep_s=1e-4)
        data.qpos[:] = theta
        spec = mujoco.mjtState.mjSTATE_FULLPHYSICS
        state = np.zeros(mujoco.mj_stateSize(model, spec))
        mujoco.mj_getState(model, data, state, spec)
        control = tau[None, None, :]
        mj_steps = max(3, int(2e4 / n**1.5))  # MuJoCo's dense chain factorisation is O(n³)
        run = partial(
            rollout.rollout,
            model,
            data,
            state[None],
            control,
            control_spec=mujoco.mjtState.mjSTATE_QFRC_APPLIED,
            nstep=mj_steps,
        )
        run()
        mj_step_time = best_time(run, 3) / mj_steps
        print(f"  RK4 step n = {n} done", file=sys.stderr, flush=True)
        rows.append(
            (
                f"n = {n}: one RK4 step, rk4_integrate | MuJoCo rollout (RK4)",
                f"{ours_step * 1e6:.2f} | {mj_step_time * 1e6:.2f} µs",
                f"MuJoCo/ours {mj_step_time / ours_step:.2f}",
            )
        )
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--part", choices=("all", "forward", "inverse"), default="all")
    part = parser.parse_args().part
    rng = np.random.default_rng(20160601)
    header = (
        f"bench_dynamics  {datetime.date.today().isoformat()}  {platform.machine()} "
        f"{_cpu_name()}, {os.cpu_count()} cores, numba {numba.__version__}, numpy {np.__version__}, "
        f"mujoco {_mujoco_version()}; load {' '.join(Path('/proc/loadavg').read_text().split()[:3])}"
    )
    if part in ("all", "forward"):
        _print(header + " (forward dynamics, RK4 step)", forward_part(rng))
    if part in ("all", "inverse"):
        inverse_part(rng, header)


def inverse_part(rng, header):
    theta, omega, alpha = rng.uniform(-1, 1, (3, 6))
    count = 1_000_000
    params = samples(count, rng)
    inverse_dynamics_batch(*(p[:10] for p in params), G, theta, omega, alpha)  # compile
    simulate_kernel(10)

    rows = []
    thread_times = {}
    for threads in (1, 2):
        numba.set_num_threads(threads)
        thread_times[threads] = (
            best_time(lambda: inverse_dynamics_batch(*params, G, theta, omega, alpha)) / count
        )
    numba.set_num_threads(numba.config.NUMBA_NUM_THREADS)
    mj_count = 10_000
    mj_params = tuple(p[:mj_count] for p in params)
    mj_time = best_time(lambda: mujoco_inverse_loop(*mj_params, theta, omega, alpha), 3) / mj_count
    np_time = best_time(lambda: numpy_newton_euler(*params, G, theta, omega, alpha), 3) / count
    agree_np = np.abs(
        numpy_newton_euler(*params, G, theta, omega, alpha)
        - inverse_dynamics_batch(*params, G, theta, omega, alpha)
    ).max()
    agree_mj = np.abs(
        mujoco_inverse_loop(*mj_params, theta, omega, alpha)
        - inverse_dynamics_batch(*mj_params, G, theta, omega, alpha)
    ).max()
    base = thread_times[1]
    rows.append(
        (
            "batched 6R inverse dynamics, 10^6 samples, 1 thread",
            f"{base * 1e9:.1f} ns/sample",
            "1.00",
        )
    )
    rows.append(
        (
            "  same, 2 threads",
            f"{thread_times[2] * 1e9:.1f} ns/sample",
            f"{thread_times[2] / base:.2f}",
        )
    )
    rows.append(
        (
            f"MuJoCo mj_inverse Python loop (10^4 samples, max |Δτ| {agree_mj:.1e} N m)",
            f"{mj_time * 1e9:.0f} ns/sample",
            f"{mj_time / base:.0f}",
        )
    )
    rows.append(
        (
            f"NumPy-vectorised Newton-Euler, 10^6 samples (max |Δτ| {agree_np:.1e} N m)",
            f"{np_time * 1e9:.1f} ns/sample",
            f"{np_time / base:.1f}",
        )
    )

    fd_calls = 40_000
    fd_args = (LENGTHS, MASSES, INERTIAS, theta.copy(), omega.copy(), TORQUES)
    _repeat_forward_into(1, *fd_args)
    fd_time = best_time(partial(_repeat_forward_into, fd_calls, *fd_args), 15) / fd_calls
    sim_every10 = best_time(lambda: simulate_kernel(10), 15)
    sim_every1 = best_time(lambda: simulate_kernel(1), 15)
    sim_mj = best_time(simulate_mujoco, 3)
    gap = np.abs(simulate_kernel(1) - simulate_mujoco()).max()
    rows.append(
        (
            "Table 1 simulation, 1 s, RK4 1e-4 s, rk4_integrate, every=10",
            f"{sim_every10 * 1e3:.2f} ms",
            "1.00",
        )
    )
    rows.append(
        (
            "  same, every=1 (energies every step)",
            f"{sim_every1 * 1e3:.2f} ms",
            f"{sim_every1 / sim_every10:.2f}",
        )
    )
    rows.append(
        (
            f"  MuJoCo RK4 mj_step Python loop, 10^4 steps (final |Δθ| {gap:.1e} rad)",
            f"{sim_mj * 1e3:.1f} ms",
            f"{sim_mj / sim_every10:.1f}",
        )
    )
    rows.append(
        (
            "  per forward dynamics: simulation time / (4 × 10^4 calls)",
            f"{sim_every10 / 4e4 * 1e9:.0f} ns",
            "",
        )
    )
    rows.append(
        (
            "  one 6R forward_dynamics_into in a jit loop (allocation-free)",
            f"{fd_time * 1e9:.0f} ns",
            "",
        )
    )

    table = scaling(rng)
    sizes = [r[0] for r in table]
    for n, python, jit_inverse, jit_forward in table:
        rows.append(
            (
                f"n = {n}: inverse_dynamics from Python | in jit loop | forward_dynamics in jit loop",
                f"{python * 1e9:.0f} | {jit_inverse * 1e9:.0f} | {jit_forward * 1e9:.0f} ns",
                "",
            )
        )
    fits = [exponent(sizes, [r[k] for r in table]) for k in (1, 2, 3)]
    rows.append(
        ("fitted exponent p (time ~ n^p, n >= 8)", " | ".join(f"{p:.2f}" for p in fits), "")
    )
    increments = [[r[k] - table[0][k] for r in table[2:]] for k in (1, 2, 3)]
    rows.append(
        (
            "fitted exponent of the increment t(n) - t(2), n >= 8",
            " | ".join(
                f"{exponent(sizes[2:], inc):.2f}" if min(inc) > 0 else "noisy" for inc in increments
            ),
            "",
        )
    )

    _print(header, rows)


def _cpu_name():
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor()


def _mujoco_version():
    import mujoco

    return mujoco.__version__


def _print(header, rows):
    try:
        from rich.console import Console
        from rich.table import Table
    except ImportError:
        print(header)
        for row in rows:
            print(" | ".join(row))
        return
    table = Table(title=header, title_justify="left")
    table.add_column("case")
    table.add_column("time", justify="right")
    table.add_column("ratio", justify="right")
    for row in rows:
        table.add_row(*row)
    Console(width=150).print(table)


if __name__ == "__main__":
    main()

"""Benchmark of the paper A Tables 4+5 reproduction.

Prints, for every job of presets/paper-a-table4.toml and paper-a-table5.toml (2R, 3R, 6R;
singular and isotropic; Sobol' and eFAST), in one process, split into sampling / model
evaluation / analysis:

1. our pipeline with an empty design cache (SALib draws the unit designs), with the
   designs on disk (a new run: the per-process memo cleared) and with them in memory;
   model = one Numba kernel per design, analysis = jitted Sobol' / threaded-FFT eFAST;
2. a plain SALib + NumPy pipeline on the same problems and N (SALib sampling per job, a
   vectorised NumPy Newton-Euler model, SALib's default ``analyze`` with its bootstrap),
   and the ratios;
3. the Sobol' N at which every bootstrap half-width is <= 0.01, and our time there;
4. whole processes: ``planar-tui run paper-a-table4 paper-a-table5`` with a cold and a warm
   design cache (Numba cache warm), and the SALib + NumPy pipeline as its own process
   (imports included); medians, with the load average (the machine is shared).

With ``--model``: only the model evaluation, one thread, CPU time of the thread
(robust on the shared machine): the lane-batched ``design_torques`` (128 robots per SIMD
block, scaling on the fly) against the scalar ``inverse_dynamics_batch`` on the pre-scaled
columns (one robot at a time), ns per robot, 6R design of 200 000 rows, best of 5; both give
the same doubles (checked here).

Every cache used lives in a temporary folder (``PLANAR_TUI_CACHE_DIR``), never the user's.
Run: ``python benchmarks/bench_sensitivity.py [--runs 7]``.
"""

from __future__ import annotations

import dataclasses
import os
import statistics
import subprocess
import sys
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from planar_tui.runtime import prepare_kernels  # noqa: E402

prepare_kernels()  # before any kernel is imported

from benchmarks.baselines import numpy_newton_euler  # noqa: E402
from planar_tui.batch import prepare_jobs  # noqa: E402
from planar_tui.presets import load_preset  # noqa: E402
from planar_tui.sensitivity import engine  # noqa: E402
from planar_tui.sensitivity.design_cache import ENV_VAR  # noqa: E402
from planar_tui.sensitivity.spec import sample_sizes  # noqa: E402

PRESETS = [REPO / "presets" / "paper-a-table4.toml", REPO / "presets" / "paper-a-table5.toml"]


def jobs(samples=None):
    """The Tables 4-5 jobs, prepared (their postures solved once, outside every timing)."""
    found = [job for path in PRESETS for job in load_preset(path).jobs_of("sensitivity")]
    if samples is not None:
        found = [
            dataclasses.replace(j, spec=dataclasses.replace(j.spec, samples=samples)) for j in found
        ]
    return prepare_jobs(found)


def state(job):
    n = job.robot.n_links
    return (
        np.array(job.prepared.posture.theta_rad),
        np.full(n, job.spec.speeds_rad_s[0]),
        np.full(n, job.spec.alpha_rad_s2),
    )


def ours(job_list, methods=("sobol", "efast")):
    """Our pipeline (as the runner: unit design, kernel, estimators); returns (sampling,
    evaluation, analysis) seconds and the largest Sobol' half-width."""
    split = np.zeros(3)
    worst = 0.0
    for job in job_list:
        spec = job.spec
        problem = engine.build_problem(job.robot, spec.tolerance_length_m, spec.tolerance_mass_kg)
        sizes = sample_sizes(spec, problem.num_vars)
        for method in methods:
            t0 = time.perf_counter()
            design = engine.unit_design(method, problem.num_vars, sizes[method], spec.seed)
            t1 = time.perf_counter()
            torques = engine.evaluate(problem, design, job.robot, *state(job))
            t2 = time.perf_counter()
            indices = engine.analyse(method, torques, problem.num_vars, spec.seed)
            t3 = time.perf_counter()
            split += (t1 - t0, t2 - t1, t3 - t2)
            if method == "sobol":
                worst = max(worst, float(indices[[1, 3]].max()))
    return split, worst


def salib_numpy(job_list):
    """SALib sampling per job, NumPy model, SALib default analysis (with bootstrap)."""
    from SALib.analyze import fast, sobol
    from SALib.sample import fast_sampler
    from SALib.sample import sobol as sobol_sample

    split = np.zeros(3)
    for job in job_list:
        spec = job.spec
        problem = engine.build_problem(job.robot, spec.tolerance_length_m, spec.tolerance_mass_kg)
        sizes = sample_sizes(spec, problem.num_vars)
        salib_problem = problem.salib()
        n = job.robot.n_links
        for method in ("sobol", "efast"):
            t0 = time.perf_counter()
            if method == "sobol":
                design = sobol_sample.sample(
                    salib_problem, sizes[method], calc_second_order=False, seed=spec.seed
                )
            else:
                design = fast_sampler.sample(salib_problem, sizes[method], M=4, seed=spec.seed)
            t1 = time.perf_counter()
            inertias = np.broadcast_to(job.robot.arrays()[2], (len(design), n))
            torques = numpy_newton_euler(
                design[:, :n], design[:, n:], inertias, job.robot.gravity_m_s2, *state(job)
            )
            t2 = time.perf_counter()
            for column in torques.T:
                if method == "sobol":
                    sobol.analyze(
                        salib_problem, column.copy(), calc_second_order=False, seed=spec.seed
                    )
                else:
                    with warnings.catch_warnings():
                        warnings.simplefilter("ignore")
                        fast.analyze(salib_problem, column.copy(), M=4, seed=spec.seed)
            t3 = time.perf_counter()
            split += (t1 - t0, t2 - t1, t3 - t2)
    return split


def row(name, split, extra=""):
    total = split.sum()
    print(
        f"| {name:<48} | {split[0]:8.3f} | {split[1]:8.3f} | {split[2]:8.3f} | {total:8.3f} | {extra}"
    )


def load() -> str:
    return (
        " ".join(Path("/proc/loadavg").read_text().split()[:3])
        if Path("/proc/loadavg").exists()
        else "?"
    )


def walls(command, env, runs):
    """Wall times of ``runs`` fresh processes, and the 1-min load average before each."""
    times, loads = [], []
    for _ in range(runs):
        loads.append(load().split()[0])
        t0 = time.perf_counter()
        subprocess.run(command, capture_output=True, check=True, cwd=REPO, env=env)
        times.append(time.perf_counter() - t0)
    return times, loads


def describe(name, times, loads):
    print(
        f"| {name} | {statistics.median(times):.2f} | {min(times):.2f} | {max(times):.2f} | "
        f"{len(times)} | {', '.join(loads)} |"
    )
    return statistics.median(times)


def in_process(cache_root: Path):
    """Tables 1-3 of the report: pipelines in this process."""
    job_list = jobs()
    os.environ[ENV_VAR] = str(cache_root / "warm-up")
    ours(job_list[:1] + job_list[-1:])  # load the compiled kernels (Numba cache) and imports
    os.environ[ENV_VAR] = str(cache_root / "in-process")
    print(
        "| pipeline (Tables 4+5: 10 jobs, Sobol' N=8192, eFAST N=4000) | sampling s | "
        "model s | analysis s | total s | note"
    )
    print("|---|---:|---:|---:|---:|---|")
    engine.unit_design.cache_clear()
    cold, worst = ours(job_list)
    row("ours, design cache empty (SALib draws)", cold, f"max Sobol' CI ±{worst:.4f}")
    engine.unit_design.cache_clear()
    warm, _ = ours(job_list)
    row("ours, designs read from the disk cache", warm)
    memo, _ = ours(job_list)
    row("ours, designs already in memory", memo)
    baseline = salib_numpy(job_list)
    row(
        "SALib + NumPy model + SALib analyze",
        baseline,
        f"ratio {baseline.sum() / cold.sum():.1f}× (cache empty), "
        f"{baseline.sum() / warm.sum():.1f}× (disk cache)",
    )
    print(f"analysis share of the SALib pipeline: {100 * baseline[2] / baseline.sum():.0f} %")
    needed = 8192 * int(2 ** np.ceil(np.log2((worst / 0.01) ** 2)))
    big, worst_big = ours(jobs(needed), methods=("sobol",))
    row(f"ours, Sobol' only at N={needed}", big, f"max Sobol' CI ±{worst_big:.4f}")


def whole_process(cache_root: Path, runs: int):
    """Table 4 of the report: fresh processes, medians."""
    print(f"\nwhole process, {runs} runs each, load average before: {load()}")
    print("| process | median s | min s | max s | runs | 1-min load before each |")
    print("|---|---:|---:|---:|---:|---|")
    with tempfile.TemporaryDirectory() as folder:
        command = [sys.executable, "-m", "planar_tui", "run", *map(str, PRESETS), "-d", folder]
        env = dict(os.environ, PYTHONPATH=str(REPO))
        cold_times, cold_loads = [], []
        for k in range(max(3, runs // 2)):  # a new empty cache folder each time
            env[ENV_VAR] = str(cache_root / f"cold-{k}")
            t, lo = walls(command, env, 1)
            cold_times += t
            cold_loads += lo
        describe("`planar-tui run` tables 4+5, design cache empty", cold_times, cold_loads)
        env[ENV_VAR] = str(cache_root / "cold-0")  # now filled
        ours_warm = describe(
            "`planar-tui run` tables 4+5, design cache warm", *walls(command, env, runs)
        )
        baseline_command = [sys.executable, str(Path(__file__).resolve()), "--baseline-only"]
        base = describe(
            "SALib + NumPy pipeline process (imports included)",
            *walls(baseline_command, env, max(3, runs // 2)),
        )
    print(f"whole-process ratio (medians): {base / ours_warm:.1f}×; load average after: {load()}")


def model_evaluation(rows: int = 200_000, n: int = 6) -> None:
    """``--model``: lane-batched against scalar torques per robot (module docstring)."""
    import numba
    from planar_tui.kernels.dynamics_batch import inverse_dynamics_batch
    from planar_tui.kernels.sensitivity_model import design_torques

    numba.set_num_threads(1)
    rng = np.random.default_rng(21)
    unit = rng.random((rows, 2 * n))
    lower = rng.uniform(0.1, 1.0, 2 * n)
    upper = lower + 0.01
    inertias = rng.uniform(1e-3, 1e-2, n)
    shared = (9.81, rng.normal(size=n), rng.normal(size=n), rng.normal(size=n))
    scaled = unit * (upper - lower) + lower
    columns = (
        np.ascontiguousarray(scaled[:, :n]),
        np.ascontiguousarray(scaled[:, n:]),
        np.tile(inertias, (rows, 1)),
    )
    best = {"lanes": np.inf, "scalar": np.inf}
    for _ in range(5):
        started = time.thread_time()
        lanes = design_torques(unit, lower, upper, inertias, *shared)
        best["lanes"] = min(best["lanes"], time.thread_time() - started)
        started = time.thread_time()
        scalar = inverse_dynamics_batch(*columns, *shared)
        best["scalar"] = min(best["scalar"], time.thread_time() - started)
    assert np.array_equal(lanes, scalar)
    lane_ns, scalar_ns = (best[k] / rows * 1e9 for k in ("lanes", "scalar"))
    print(
        f"6R torques per robot, 1 thread, load {load()}: lanes {lane_ns:.1f} ns, scalar "
        f"{scalar_ns:.1f} ns, ratio {scalar_ns / lane_ns:.2f} (identical doubles)"
    )


def main():
    if "--model" in sys.argv:
        model_evaluation()
        return
    if "--baseline-only" in sys.argv:
        salib_numpy(jobs())
        return
    runs = int(sys.argv[sys.argv.index("--runs") + 1]) if "--runs" in sys.argv else 7
    print(f"load average at start: {load()}")
    with tempfile.TemporaryDirectory() as root:
        in_process(Path(root))
        whole_process(Path(root), runs)


if __name__ == "__main__":
    main()

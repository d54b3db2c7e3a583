"""Benchmark of the paper A Tables 4+5 reproduction (issue 3).

Prints, for every job of presets/paper-a-table4.toml and paper-a-table5.toml (2R, 3R, 6R;
singular and isotropic; Sobol' and eFAST):

1. our pipeline (SALib sampling with the per-process unit-design cache, one batched Numba
   inverse-dynamics call, jitted Sobol' / vectorised eFAST estimators), split into
   sampling / model evaluation / analysis, JIT warmed first;
2. a plain SALib + NumPy pipeline on the same problems and N (SALib sampling per job, a
   vectorised NumPy Newton-Euler model, SALib's default ``analyze`` with its bootstrap),
   in the same process, and the ratio;
3. the Sobol' N at which every bootstrap half-width is <= 0.01, and our time there;
4. the whole-process wall time of ``planar-tui run paper-a-table4 paper-a-table5``.

Run: ``/work/venv/bin/python benchmarks/bench_sensitivity.py``.
"""

from __future__ import annotations

import dataclasses
import subprocess
import sys
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from planar_tui.presets import load_preset  # noqa: E402
from planar_tui.sensitivity import engine  # noqa: E402
from planar_tui.sensitivity.runner import sample_sizes  # noqa: E402

PRESETS = [REPO / "presets" / "paper-a-table4.toml", REPO / "presets" / "paper-a-table5.toml"]


def numpy_inverse_dynamics(lengths, masses, inertias, gravity, theta, omega, alpha):
    """Plain NumPy Newton-Euler over all samples at once (the baseline model), (S, n)."""
    phi, rate, accel = np.cumsum(theta), np.cumsum(omega), np.cumsum(alpha)
    ux, uy = np.cos(phi), np.sin(phi)
    samples, n = lengths.shape
    ax = np.zeros(samples)
    ay = np.full(samples, gravity)
    fx = np.empty((samples, n))
    fy = np.empty((samples, n))
    for i in range(n):
        bx = -accel[i] * uy[i] - rate[i] ** 2 * ux[i]
        by = accel[i] * ux[i] - rate[i] ** 2 * uy[i]
        fx[:, i] = masses[:, i] * (ax + 0.5 * lengths[:, i] * bx)
        fy[:, i] = masses[:, i] * (ay + 0.5 * lengths[:, i] * by)
        ax = ax + lengths[:, i] * bx
        ay = ay + lengths[:, i] * by
    tau = np.empty((samples, n))
    big_fx = np.zeros(samples)
    big_fy = np.zeros(samples)
    moment = np.zeros(samples)
    for i in range(n - 1, -1, -1):
        hx = 0.5 * lengths[:, i] * ux[i]
        hy = 0.5 * lengths[:, i] * uy[i]
        moment = moment + inertias[:, i] * accel[i] + hx * fy[:, i] - hy * fx[:, i]
        moment = moment + 2.0 * (hx * big_fy - hy * big_fx)
        big_fx = big_fx + fx[:, i]
        big_fy = big_fy + fy[:, i]
        tau[:, i] = moment
    return tau


def jobs(samples=None):
    found = [job for path in PRESETS for job in load_preset(path).jobs_of("sensitivity")]
    if samples is None:
        return found
    return [
        dataclasses.replace(j, spec=dataclasses.replace(j.spec, samples=samples)) for j in found
    ]


def state(job):
    n = job.robot.n_links
    return (
        np.array(job.spec.posture.theta_rad),
        np.full(n, job.spec.speeds_rad_s[0]),
        np.full(n, job.spec.alpha_rad_s2),
    )


def ours(job_list, methods=("sobol", "efast")):
    """Our pipeline; returns (sampling, evaluation, analysis) seconds and max Sobol' CI."""
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
            torques = numpy_inverse_dynamics(
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
        f"| {name:<44} | {split[0]:8.3f} | {split[1]:8.3f} | {split[2]:8.3f} | {total:8.3f} | {extra}"
    )


def main():
    job_list = jobs()
    ours(job_list[:1] + job_list[-1:])  # warm the JIT (cached machine code) and imports
    engine.unit_design.cache_clear()
    print(
        "| pipeline (Tables 4+5: 10 jobs, Sobol' N=8192, eFAST N=4000) | sampling s | "
        "model s | analysis s | total s | note"
    )
    print("|---|---:|---:|---:|---:|---|")
    first, worst = ours(job_list)
    row("ours, first pass (SALib samples unit designs)", first, f"max Sobol' CI ±{worst:.4f}")
    again, _ = ours(job_list)
    row("ours, designs cached in process", again)
    baseline = salib_numpy(job_list)
    row(
        "SALib + NumPy model + SALib analyze",
        baseline,
        f"ratio {baseline.sum() / first.sum():.1f}× (first pass)",
    )
    print(f"analysis share of the SALib pipeline: {100 * baseline[2] / baseline.sum():.0f} %")
    needed = 8192 * int(2 ** np.ceil(np.log2((worst / 0.01) ** 2)))
    big, worst_big = ours(jobs(needed), methods=("sobol",))
    row(f"ours, Sobol' only at N={needed}", big, f"max Sobol' CI ±{worst_big:.4f}")
    with tempfile.TemporaryDirectory() as folder:
        command = [sys.executable, "-m", "planar_tui", "run", *map(str, PRESETS), "-d", folder]
        subprocess.run(command, capture_output=True, check=True, cwd=REPO)  # warm-up
        walls = []
        for _ in range(3):
            t0 = time.perf_counter()
            subprocess.run(command, capture_output=True, check=True, cwd=REPO)
            walls.append(time.perf_counter() - t0)
    print(
        f"whole process `planar-tui run paper-a-table4 paper-a-table5`: "
        f"best {min(walls):.2f} s, median {sorted(walls)[1]:.2f} s (3 runs, compiled)"
    )


if __name__ == "__main__":
    main()

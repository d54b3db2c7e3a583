"""Polynomial chaos against Saltelli on paper A's Tables 4-5 problems (issue 22).

For every job of presets/paper-a-table4.toml and paper-a-table5.toml (2R, 3R, 6R; D = 4,
6, 12 inputs), in one process:

1. the exact indices: the torques are polynomials of degree ≤ 2 in each input, so a
   3-point Gauss-Legendre tensor grid (3^D model runs) gives every conditional variance
   exactly (``exact_indices``, independent of any expansion);
2. Saltelli's Sobol' design at N = 8192 (N (D + 2) runs, our jitted estimators = SALib's);
3. our PCE (:mod:`planar_tui.sensitivity.pce`: NumPy Legendre basis, OMP, corrected LOO,
   degree adaptivity, bootstrap) at its default ``pce_samples``;
4. Chaospy 4 (``generate_expansion`` + ``fit_regression`` least squares, degree 2, and
   ``Sens_m``/``Sens_t``) and OpenTURNS (``FunctionalChaosAlgorithm`` with LARS and the
   corrected LOO, degree 3, ``FunctionalChaosSobolIndices``) on the same design;

and prints, per method, the largest |ST − exact| and |ST − Saltelli| over the jobs, the
model runs and the seconds (fit + indices; the library's import timed apart), and the
ratios. Run: ``.venv/bin/python benchmarks/bench_pce.py [--no-libraries]``.
"""

from __future__ import annotations

import argparse
import dataclasses
import importlib.util
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from planar_tui.runtime import prepare_kernels  # noqa: E402

prepare_kernels()

from planar_tui.batch import prepare_jobs  # noqa: E402
from planar_tui.presets import load_preset  # noqa: E402
from planar_tui.sensitivity import engine, pce, pce_analysis  # noqa: E402

PRESETS = [REPO / "presets" / "paper-a-table4.toml", REPO / "presets" / "paper-a-table5.toml"]
SALTELLI_N = 8192
#: Chaospy runs up to this D (its Sens_t took 29 s at D = 6 and over 250 s at D = 12).
CHAOSPY_MAX_D = 6


def jobs():
    found = [job for path in PRESETS for job in load_preset(path).jobs_of("sensitivity")]
    return list(prepare_jobs(found))


def model(job):
    """(problem, f(unit design) -> torques (S, n))."""
    spec, robot, posture = job.spec, job.robot, job.prepared.posture
    problem = engine.build_problem(robot, spec.tolerance_length_m, spec.tolerance_mass_kg)
    n = robot.n_links
    state = (
        np.array(posture.theta_rad),
        np.full(n, spec.speeds_rad_s[0]),
        np.full(n, spec.alpha_rad_s2),
    )
    return problem, lambda unit: engine.evaluate(problem, np.ascontiguousarray(unit), robot, *state)


def exact_indices(f, num_vars: int):
    """S1, ST (n, D) by 3-point Gauss-Legendre tensor quadrature (exact for outputs of
    degree ≤ 2 in each input: their squares have degree ≤ 4 < 6)."""
    x, w = np.polynomial.legendre.leggauss(3)
    w = w / 2.0
    grid = np.stack(np.meshgrid(*([(x + 1.0) / 2.0] * num_vars), indexing="ij"), axis=-1)
    y = f(grid.reshape(-1, num_vars))
    weights = np.ones(())
    for _ in range(num_vars):
        weights = np.multiply.outer(weights, w)
    first = np.empty((y.shape[1], num_vars))
    total = np.empty_like(first)
    for t in range(y.shape[1]):
        values = y[:, t].reshape((3,) * num_vars)
        mean = float((weights * values).sum())
        variance = float((weights * (values - mean) ** 2).sum())
        for a in range(num_vars):
            others = tuple(i for i in range(num_vars) if i != a)
            given_a = (weights * values).sum(axis=others) / w
            first[t, a] = float(w @ (given_a - mean) ** 2) / variance
            given_others = np.expand_dims(np.moveaxis(values, a, -1) @ w, a)
            total[t, a] = float((weights * (values - given_others) ** 2).sum()) / variance
    return first, total


def chaospy_indices(unit, y, degree=2):
    import chaospy

    num_vars = unit.shape[1]
    dist = chaospy.J(*[chaospy.Uniform(0.0, 1.0) for _ in range(num_vars)])
    expansion = chaospy.generate_expansion(degree, dist, normed=True)
    fitted = chaospy.fit_regression(expansion, unit.T, y)
    return np.asarray(chaospy.Sens_m(fitted, dist)).T, np.asarray(chaospy.Sens_t(fitted, dist)).T


def openturns_indices(unit, y, degree=3):
    import openturns as ot

    num_vars = unit.shape[1]
    dist = ot.JointDistribution([ot.Uniform(-1.0, 1.0)] * num_vars)
    enumerate_function = ot.LinearEnumerateFunction(num_vars)
    factory = ot.OrthogonalProductPolynomialFactory(
        [ot.LegendreFactory()] * num_vars, enumerate_function
    )
    size = enumerate_function.getStrataCumulatedCardinal(degree)
    selection = ot.LeastSquaresMetaModelSelectionFactory(ot.LARS(), ot.CorrectedLeaveOneOut())
    algo = ot.FunctionalChaosAlgorithm(
        ot.Sample(2.0 * unit - 1.0),
        ot.Sample(y),
        dist,
        ot.FixedStrategy(factory, size),
        ot.LeastSquaresStrategy(selection),
    )
    algo.run()
    sobol = ot.FunctionalChaosSobolIndices(algo.getResult())
    first = np.array(
        [[sobol.getSobolIndex(i, t) for i in range(num_vars)] for t in range(y.shape[1])]
    )
    total = np.array(
        [[sobol.getSobolTotalIndex(i, t) for i in range(num_vars)] for t in range(y.shape[1])]
    )
    return first, total


def import_seconds(module: str) -> float:
    """Seconds to import ``module`` in a fresh interpreter (minus a bare start)."""
    times = []
    for code in ("pass", f"import {module}"):
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-c", code], check=True)
        times.append(time.perf_counter() - t0)
    return times[1] - times[0]


@dataclasses.dataclass
class Tally:
    runs: int = 0
    seconds: float = 0.0
    vs_exact: float = 0.0
    vs_saltelli: float = 0.0

    def add(self, runs, seconds, total, exact, saltelli):
        self.runs = max(self.runs, runs)
        self.seconds += seconds
        self.vs_exact = max(self.vs_exact, float(np.abs(total - exact).max()))
        if saltelli is not None:
            self.vs_saltelli = max(self.vs_saltelli, float(np.abs(total - saltelli).max()))


def motion_outputs(job, unit, steps):
    """Outputs (S, K, M) of the motion job's robots (rows of ``unit``) at ``steps``, by the
    motion engine's public functions (the job's own model, CPU)."""
    from planar_tui.motion import engine as motion

    spec, robot = job.spec, job.robot
    problem = engine.build_problem(
        robot,
        spec.tolerance_length_mm * 1e-3,
        spec.tolerance_mass_g * 1e-3,
        spec.tolerance_inertia_kgm2,
    )
    lengths, masses, inertias = robot.arrays()
    rod = inertias == masses * lengths * lengths / 12.0
    design = motion.Design(np.ascontiguousarray(unit), {"sobol": slice(0, len(unit))})
    robots, params = motion.make_robots(
        "cpu",
        problem,
        design,
        rod,
        robot,
        np.radians(np.array(spec.theta0_deg, dtype=float)),
        np.radians(np.array(spec.omega0_deg_s, dtype=float)),
        np.array(spec.torques_Nm, dtype=float),
    )
    recorded = {}

    def on_stop(step, angles):
        if step in steps:
            recorded[step] = motion.take_outputs(params[:, 0, :], angles, spec.outputs)

    motion.integrate(robots, spec.step_s, sorted({0, *steps}), on_stop)
    return np.stack([recorded[k] for k in steps], axis=1), problem


def motion_study(sobol_samples: int) -> None:
    """paper-a-table1-motion: PCE at its default runs against Sobol' at N = sobol_samples,
    ST at every ``at_s`` time; run counts and seconds (integration + analysis)."""
    (job,) = prepare_jobs(
        load_preset(REPO / "presets" / "paper-a-table1-motion.toml").jobs_of("motion_uncertainty")
    )
    steps = job.spec.at_steps()
    d = 12
    t0 = time.perf_counter()
    unit = engine.unit_design("sobol", d, sobol_samples, job.spec.seed)
    y, _ = motion_outputs(job, unit, steps)
    flat = y.reshape(len(unit), -1)
    saltelli = engine.analyse("sobol", flat, d, job.spec.seed)
    sobol_s = time.perf_counter() - t0
    samples = pce.default_pce_samples(d)
    t0 = time.perf_counter()
    design = pce.pce_unit_design(d, samples, job.spec.seed)
    y, _ = motion_outputs(job, design, steps)
    result = pce_analysis.trajectory_indices(np.asarray(design), y, job.spec.seed)
    pce_s = time.perf_counter() - t0
    chaos = result.indices[2].reshape(-1, d)  # (K M, D) in the order of flat's columns
    error = np.abs(chaos - saltelli[2])
    print(f"\nmotion, paper-a-table1-motion (D = 12, times {[k * job.spec.step_s for k in steps]})")
    print("| method | robots | seconds | max |ST − Sobol'| | max Sobol' ST half-width | max LOO |")
    print("|---|---:|---:|---:|---:|---:|")
    print(
        f"| Sobol' N = {sobol_samples} | {sobol_samples * (d + 2)} | {sobol_s:.1f} | — "
        f"| {saltelli[3].max():.3f} | — |"
    )
    print(
        f"| PCE | {samples} ({sobol_samples * (d + 2) / samples:.0f}× fewer) "
        f"| {pce_s:.1f} ({sobol_s / pce_s:.1f}×) | {error.max():.4f} | — "
        f"| {result.loo_error.max():.1e} |"
    )


def whole_process(methods: str, out: Path) -> float:
    """Seconds of ``planar-tui run paper-a-table4 paper-a-table5`` with every job's
    ``methods`` replaced (presets copied with that one line changed)."""
    for path in PRESETS:
        text = path.read_text().replace('methods = ["sobol", "efast"]', f"methods = [{methods}]")
        (out / path.name).write_text(text)
    command = [sys.executable, "-m", "planar_tui", "run"]  # this checkout's code
    command += [str(out / p.name) for p in PRESETS] + ["-d", str(out)]
    t0 = time.perf_counter()
    subprocess.run(
        command, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, cwd=REPO
    )
    return time.perf_counter() - t0


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--no-libraries", action="store_true", help="skip Chaospy, OpenTURNS")
    parser.add_argument("--whole-process", action="store_true", help="time planar-tui run too")
    parser.add_argument(
        "--motion",
        type=int,
        default=0,
        metavar="N",
        help="also the Table 1 motion study against Sobol' at this N",
    )
    args = parser.parse_args()
    tallies = {name: Tally() for name in ("saltelli", "pce", "chaospy", "openturns")}
    print("| job | D | runs PCE | degree | terms | LOO | max |ST-exact| PCE | Saltelli |")
    print("|---|---|---|---|---|---|---|---|")
    for job in jobs():
        problem, f = model(job)
        d = problem.num_vars
        _first_exact, total_exact = exact_indices(f, d)
        t0 = time.perf_counter()
        unit = engine.unit_design("sobol", d, SALTELLI_N, job.spec.seed)
        saltelli = engine.analyse("sobol", f(unit), d, job.spec.seed)[2]
        tallies["saltelli"].add(
            SALTELLI_N * (d + 2), time.perf_counter() - t0, saltelli, total_exact, None
        )
        samples = pce.default_pce_samples(d)
        t0 = time.perf_counter()
        design = pce.pce_unit_design(d, samples, job.spec.seed)
        y = f(design)
        indices, fits = pce.pce_indices(design, y, job.spec.seed, shared=True)
        tallies["pce"].add(samples, time.perf_counter() - t0, indices[2], total_exact, saltelli)
        loo = max(float(fit.loo_error.max()) for fit in fits)
        terms = max(len(fit.indices) for fit in fits)
        degree = max(fit.degree for fit in fits)
        print(
            f"| {job.label} | {d} | {samples} | {degree} | {terms} | {loo:.1e} "
            f"| {np.abs(indices[2] - total_exact).max():.1e} "
            f"| {np.abs(saltelli - total_exact).max():.1e} |"
        )
        if not args.no_libraries:
            for name, fitter in (("chaospy", chaospy_indices), ("openturns", openturns_indices)):
                if name == "chaospy" and d > CHAOSPY_MAX_D:
                    continue  # its symbolic Sens_t takes minutes
                if importlib.util.find_spec(name) is None:
                    print(f"({name} is not installed: skipped)")
                    continue
                t0 = time.perf_counter()
                _, total = fitter(np.asarray(design), y)
                tallies[name].add(samples, time.perf_counter() - t0, total, total_exact, saltelli)
    print()
    print(
        "| method | runs (max) | seconds (10 jobs) | import s | max |ST − exact| "
        "| max |ST − Saltelli 8192| |"
    )
    print("|---|---|---|---|---|---|")
    imports = {"chaospy": "chaospy", "openturns": "openturns"}
    base = tallies["saltelli"]
    for name, tally in tallies.items():
        if tally.runs == 0:
            continue
        imported = f"{import_seconds(imports[name]):.2f}" if name in imports else "-"
        print(
            f"| {name} | {tally.runs} ({base.runs / tally.runs:.0f}× fewer) "
            f"| {tally.seconds:.2f} ({base.seconds / tally.seconds:.1f}×) | {imported} "
            f"| {tally.vs_exact:.1e} | {tally.vs_saltelli:.1e} |"
        )
    if args.motion:
        motion_study(args.motion)
    if args.whole_process:
        with tempfile.TemporaryDirectory() as folder:
            out = Path(folder)
            os.environ.setdefault("PLANAR_TUI_CACHE_DIR", str(out / "cache"))
            whole_process('"sobol"', out)  # draw the designs once
            whole_process('"pce"', out)
            sobol = min(whole_process('"sobol"', out) for _ in range(3))
            chaos = min(whole_process('"pce"', out) for _ in range(3))
        print(
            f"\nwhole process, Tables 4+5: Sobol' {sobol:.2f} s, PCE {chaos:.2f} s, "
            f"ratio {sobol / chaos:.1f}×"
        )
    print(f"load average: {Path('/proc/loadavg').read_text().split()[0]}")


if __name__ == "__main__":
    main()

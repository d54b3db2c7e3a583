"""Sweeps on Dask (``python benchmarks/bench_sweep.py [--points 64] [--precision 0.1]``).

Prints three tables, each against a baseline measured in this process:

* per-task overhead: 400 trivial points (one inverse-dynamics state of a 2R robot, a few
  µs of work) in-process and on a warm 2-process local cluster; the overhead per point is
  ``wall · workers / points − compute``, where ``compute`` is the points' own mean
  ``seconds`` (goal: ≤ 20 ms a point);
* the speed-up of a 64-point workspace sweep (paper B's robot, Table 3 limits, orientations
  −31.5..31.5°, mean-value form on the joint strategy, ε = 0.1 cm: about 0.55 s a point on an idle core, the issue's "points of ≥ 0.5 s") on 2 workers over 1
  (in-process), with the cluster warm and with its start-up counted (goal ≥ 1.8×);
  the last column, CPU time over wall time of each computing process, says how much of a
  core each got (1.00: a core of its own; less: the machine was shared), and ``busy`` the
  share of the wall time the workers spent inside points (100 %: the scheduler never
  left a worker waiting);
* 1/2/4/8/16 workers, as many of them as this machine has cores (goal ≥ 12× on 16); the
  rest are reported as not measured;
* the optimiser loop's overhead (issue 23): 400 evaluations of the same trivial job by a
  GA (generations of 20 submitted at once) on the same warm 2-process cluster, with and
  without its checkpoint (one ``fsync`` per evaluation), ``wall · workers / evaluations −
  compute`` against the sweep's per-task overhead above (goal: ≤ 20 ms an evaluation).
  ``--optimise-only`` prints the per-task and optimiser tables alone.

Every sweep's CSV is checked equal to the in-process one in every column but ``seconds``.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

TRIVIAL = """# trivial points
[robot]
lengths_m = [0.3, 0.2]
masses_kg = [1.0, 0.5]

[torques]
theta_deg = [[10, 20]]

[[sweep]]
job = "torques"
values."theta_deg[1][1]" = {{ from = 0, to = 90, count = {count} }}

[[optimise]]
job = "torques"
variables."theta_deg[1][1]" = {{ from = 0, to = 90 }}
variables."theta_deg[1][2]" = {{ from = 0, to = 90 }}
maximise = "tau1_abs_max_Nm"
budget = {count}
population = 20
output = "opt.csv"
"""

WORKSPACE = """# workspace points
[robot3rrr]
base_side_cm = 120
platform_side_cm = 40
proximal_cm = 30
distal_cm = 30

[workspace]
form = "mean-value"
strategy = "joint"
precision_cm = {precision}
joint_limits_deg = [[20, 70], [110, 160], [245, 295]]
geometric_reference = false

[[sweep]]
job = "workspace"
values.orientation_deg = {{ from = -31.5, to = 31.5, count = {count} }}
"""


def sweep_from(folder: Path, text: str):
    from planar_tui.presets import load_preset
    from planar_tui.sweep.spec import parse_sweeps

    path = folder / f"bench-{abs(hash(text))}.toml"
    path.write_text(text)
    (sweep,) = parse_sweeps(load_preset(path))
    return sweep


def optimisation_from(folder: Path, text: str):
    from planar_tui.optimise.spec import parse_optimisations
    from planar_tui.presets import load_preset

    path = folder / f"bench-opt-{abs(hash(text))}.toml"
    path.write_text(text)
    (optimisation,) = parse_optimisations(load_preset(path))
    return optimisation


def optimiser_overhead(folder: Path, text: str, client, sweep_overhead_ms: float) -> None:
    """The optimiser loop's table (see the module's docstring)."""
    from planar_tui.optimise.run import run_optimisation

    optimisation = optimisation_from(folder, text)
    run_optimisation(optimisation, client=client)  # pymoo imported, the workers warm
    print(
        f"\noptimiser loop, {optimisation.budget} trivial evaluations in generations of "
        f"{optimisation.population} (goal <= 20 ms an evaluation)"
    )
    print("| runner | wall s | compute ms/eval | overhead ms/eval | vs sweep per-task |")
    print("|---|---:|---:|---:|---:|")
    print(f"| sweep, 2 worker processes (baseline, above) | | | {sweep_overhead_ms:.3f} | 1.00x |")
    for label, out_dir in (
        ("2 worker processes", None),
        ("2 worker processes, checkpoint", folder / "out"),
    ):
        wall_s, run = timed(
            lambda out_dir=out_dir: run_optimisation(optimisation, client=client, out_dir=out_dir)
        )
        compute = statistics.mean(e.outcome.seconds for e in run.evaluations)
        overhead = 1e3 * (wall_s * 2 / len(run.evaluations) - compute)
        print(
            f"| {label} | {wall_s:.3f} | {1e3 * compute:.3f} | {overhead:.3f} | "
            f"{overhead / sweep_overhead_ms:.2f}x |"
        )


def timed(function):
    start = time.perf_counter()
    result = function()
    return time.perf_counter() - start, result


def without_seconds(run):
    return [tuple(row[:-1]) for row in run.table.rows]


def warm(client) -> None:
    """Import the package and load the kernels in every worker (what a first point does)."""
    from planar_tui.sweep.worker import warm_worker

    client.run(warm_worker, "torques")
    client.run(warm_worker, "workspace")


def load() -> list[str]:
    """The 1, 5 and 15 minute load averages."""
    return Path("/proc/loadavg").read_text().split()[:3]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--points", type=int, default=64)
    parser.add_argument("--precision", type=float, default=0.1)
    parser.add_argument("--trivial", type=int, default=400)
    parser.add_argument(
        "--optimise-only", action="store_true", help="the per-task and optimiser-loop tables only"
    )
    args = parser.parse_args()

    from distributed import Client

    from planar_tui.runtime import configure_process, prepare_kernels
    from planar_tui.sweep.execute import default_workers, local_cluster
    from planar_tui.sweep.service import run_sweep

    configure_process()
    prepare_kernels()
    cores = default_workers()
    print(f"machine: {cores} cores; load {load()}")
    with tempfile.TemporaryDirectory() as scratch:
        folder = Path(scratch)
        trivial = sweep_from(folder, TRIVIAL.format(count=args.trivial))
        work = sweep_from(folder, WORKSPACE.format(precision=args.precision, count=args.points))
        run_sweep(trivial, workers=1)  # kernels loaded in this process
        alone_s, alone = timed(lambda: run_sweep(trivial, workers=1))
        compute_s = statistics.mean(o.seconds for o in alone.outcomes.values())
        started_s, cluster = timed(lambda: local_cluster(2))
        with cluster, Client(cluster) as client:
            warm(client)
            spread_s, spread = timed(lambda: run_sweep(trivial, client=client))
            assert without_seconds(spread) == without_seconds(alone)
            spread_compute = statistics.mean(o.seconds for o in spread.outcomes.values())
            print(f"\nper-task overhead, {args.trivial} trivial points (goal <= 20 ms a point)")
            print("| runner | wall s | compute ms/point | overhead ms/point |")
            print("|---|---:|---:|---:|")
            overhead = 1e3 * (alone_s / args.trivial - compute_s)
            print(
                f"| in-process (baseline) | {alone_s:.3f} | {1e3 * compute_s:.3f} | {overhead:.3f} |"
            )
            overhead = 1e3 * (spread_s * 2 / args.trivial - spread_compute)
            print(
                f"| 2 worker processes | {spread_s:.3f} | {1e3 * spread_compute:.3f} | "
                f"{overhead:.3f} |"
            )
            optimiser_overhead(folder, TRIVIAL.format(count=args.trivial), client, overhead)
            if args.optimise_only:
                print(f"\nload after the runs: {load()}")
                return

            cpu_before = time.process_time()
            one_s, one = timed(lambda: run_sweep(work, workers=1))
            one_cpu = (time.process_time() - cpu_before) / one_s
            per_point = statistics.mean(o.seconds for o in one.outcomes.values())
            workers_before = sum(client.run(time.process_time).values())
            two_s, two = timed(lambda: run_sweep(work, client=client))
            two_cpu = (sum(client.run(time.process_time).values()) - workers_before) / two_s / 2
            assert without_seconds(two) == without_seconds(one)
            busy = sum(o.seconds for o in two.outcomes.values()) / two_s / 2
        print(
            f"\n{args.points}-point workspace sweep, {per_point:.2f} s a point in-process "
            "(goal >= 1.8x on 2 workers)"
        )
        print("| workers | wall s | speed-up | CPU s per wall s, per process | busy |")
        print("|---|---:|---:|---:|---:|")
        print(f"| 1 (in-process, baseline) | {one_s:.2f} | 1.00x | {one_cpu:.2f} | |")
        print(
            f"| 2, warm cluster | {two_s:.2f} | {one_s / two_s:.2f}x | {two_cpu:.2f} | "
            f"{100 * busy:.0f} % |"
        )
        print(
            f"| 2, cluster start-up ({started_s:.2f} s) counted | {two_s + started_s:.2f} | "
            f"{one_s / (two_s + started_s):.2f}x | | |"
        )

        print("\nworkers table (goal >= 12x on 16)")
        print("| workers | wall s | speed-up |")
        print("|---|---:|---:|")
        for workers in (1, 2, 4, 8, 16):
            if workers > cores:
                print(f"| {workers} | not measured: this machine has {cores} cores | |")
                continue
            if workers in (1, 2):  # measured above
                wall_s = one_s if workers == 1 else two_s
                print(f"| {workers} | {wall_s:.2f} | {one_s / wall_s:.2f}x |")
                continue
            with local_cluster(workers) as cluster, Client(cluster) as client:
                warm(client)
                wall_s, run = timed(lambda client=client: run_sweep(work, client=client))
                assert without_seconds(run) == without_seconds(one)
            print(f"| {workers} | {wall_s:.2f} | {one_s / wall_s:.2f}x |")
    print(f"\nload after the runs: {load()}")


if __name__ == "__main__":
    os.environ.setdefault("PYTHONWARNINGS", "ignore")
    main()

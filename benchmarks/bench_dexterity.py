"""Benchmark of the certified dexterous region: ``python benchmarks/bench_dexterity.py``.

The 3-RRR of paper B's Table 3 (joints [20, 70], [110, 160], [245, 295] deg, φ = 0, working
mode ``elbow = [1, -1, 1]``), κ ≤ 4 with L the platform's circumradius (25 cm), at
ε = 0.1 cm (``form = "arc-distance"`` for the workspace beside it):

* in process (kernels compiled and loaded first): the dexterity paving's seconds (best of
  3), boxes decided and the certified bracket ``[inside, kept]``;
* a grid estimate of the same area, independent of the kernels: the elbows by circle
  intersection, κ by central differences of the joint angles and numpy's SVD on a grid of
  step ``--grid`` cm (default 0.01); the bracket's ends in % of it (goal: within 3 %);
* the whole process through the CLI (median of 3 fresh processes, Numba cache warm; goal
  ≤ 5 s on 2 cores): its wall time and its CPU time (user + system, the child's
  ``getrusage``: on a shared machine the wall time is mostly waiting for a core), with
  Python's bytecode cache warm as an installed package has it, then without one
  (``PYTHONDONTWRITEBYTECODE=1`` and an empty ``PYTHONPYCACHEPREFIX``: every module
  compiled from source in every process, as in a fresh environment that sets the first),
  beside the same job without ``kappa_max`` (the
  process's floor).

The 1, 5 and 15 minute load averages are printed with the figures (the machine is shared).
"""

from __future__ import annotations

import math
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from benchmarks.timing import load  # noqa: E402
from planar_tui.runtime import prepare_kernels  # noqa: E402

prepare_kernels()  # before any kernel is imported

PRESET = """[robot3rrr]
base_side_cm = 120
platform_side_cm = 40
proximal_cm = 30
distal_cm = 30

[[workspace]]
form = "arc-distance"
precision_cm = 0.1
joint_limits_deg = [[20, 70], [110, 160], [245, 295]]
geometric_reference = false
elbow = [1, -1, 1]
kappa_max = 4
output = "dexterity.csv"
"""
KAPPA_MAX = 4.0
LENGTH_CM = 25.0


def in_process(folder: Path):
    """The job's dexterity paving, best of 3: ``(seconds, outcome)``."""
    from planar_tui.batch import prepare_jobs
    from planar_tui.presets import load_preset
    from planar_tui.progress import Progress
    from planar_tui.workspace.paving.levels import BoxBudget
    from planar_tui.workspace.rrr.job import rrr_dexterity

    path = folder / "dexterity.toml"
    path.write_text(PRESET, encoding="utf-8")
    (ready,) = prepare_jobs(load_preset(path).jobs)
    extent = (-4.0, 124.0, -4.0, 124.0)  # holds the reach
    best, outcome = math.inf, None
    for _ in range(3):
        budget = BoxBudget(ready.job, Progress())
        started = time.perf_counter()
        outcome = rrr_dexterity(ready, extent, budget)
        best = min(best, time.perf_counter() - started)
    return best, outcome, ready


def grid_estimate(ready, outcome, step_cm: float) -> float:
    """The dexterous area by a grid of step ``step_cm`` over the kept boxes' bounding box
    (module docstring), in chunks of rows."""
    import numpy as np

    robot, spec = ready.job.robot, ready.job.spec
    elbow = ready.prepared.circle.elbow
    l1, l2 = robot.proximal_cm, robot.distal_cm
    points = (robot.base_joints_cm(), robot.platform_points_cm(), elbow, spec.limits_rad)
    legs = list(zip(*points, strict=True))

    def angles(x, y, phi):
        valid = np.ones(x.shape, dtype=bool)
        out = []
        for (ax, ay), (qx, qy), sign, (lo, hi) in legs:
            cx = x + math.cos(phi) * qx - math.sin(phi) * qy - ax
            cy = y + math.sin(phi) * qx + math.cos(phi) * qy - ay
            d = np.hypot(cx, cy)
            a = (l1 * l1 - l2 * l2 + d * d) / (2 * d)
            h = np.sqrt(np.maximum(l1 * l1 - a * a, 0.0))
            valid &= (d < l1 + l2) & (d > abs(l1 - l2))
            theta = np.arctan2(a * cy / d + sign * h * cx / d, a * cx / d - sign * h * cy / d)
            valid &= np.mod(theta - lo, 2 * np.pi) <= hi - lo
            out.append(theta)
        return valid, np.array(out)

    b = outcome.boxes
    xs = np.arange(b[:, 0].min() - 0.5, b[:, 1].max() + 0.5, step_cm) + 0.5 * step_cm
    ys = np.arange(b[:, 2].min() - 0.5, b[:, 3].max() + 0.5, step_cm) + 0.5 * step_cm
    h = 1e-6
    count = 0
    for y in ys:
        x, yy = xs, np.full_like(xs, y)
        valid, _ = angles(x, yy, 0.0)
        columns = []
        for dx, dy, dphi in ((h, 0, 0), (0, h, 0), (0, 0, h / LENGTH_CM)):
            ahead = angles(x + dx, yy + dy, dphi)[1]
            behind = angles(x - dx, yy - dy, -dphi)[1]
            columns.append(np.angle(np.exp(1j * (ahead - behind))) / (2 * h))
        inverse = np.moveaxis(np.array(columns), (0, 1), (-1, -2))
        sigma = np.linalg.svd(inverse, compute_uv=False)
        with np.errstate(divide="ignore", invalid="ignore"):
            kappa = sigma[:, 0] / sigma[:, -1]
        count += int(np.count_nonzero(valid & (kappa <= KAPPA_MAX)))
    return count * step_cm * step_cm


def process(command, env, runs=3) -> tuple[float, float]:
    """The median wall and CPU (user + system) seconds of ``runs`` fresh processes."""
    walls, cpus = [], []
    for _ in range(runs):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        started = time.perf_counter()
        subprocess.run(command, check=True, capture_output=True, cwd=REPO, env=env)
        walls.append(time.perf_counter() - started)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpus.append(after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime)
    return statistics.median(walls), statistics.median(cpus)


def main(step_cm: float) -> None:
    print(f"load before: {load()}")
    with tempfile.TemporaryDirectory() as name:
        folder = Path(name)
        seconds, outcome, ready = in_process(folder)
        estimate = grid_estimate(ready, outcome, step_cm)
        lo, hi = outcome.area_inside_cm2, outcome.area_kept_cm2
        print("| figure | value | goal |")
        print("|---|---|---|")
        print(f"| dexterity paving in process, ε = 0.1 cm (s, best of 3) | {seconds:.2f} | |")
        print(f"| boxes decided | {outcome.boxes_processed:,} | |")
        print(f"| certified bracket (cm²) | [{lo:.3f}, {hi:.3f}] | |")
        print(f"| grid estimate, step {step_cm} cm (cm²) | {estimate:.3f} | |")
        below, above = 100 * (lo / estimate - 1), 100 * (hi / estimate - 1)
        print(f"| bracket ends vs the grid (%) | {below:+.2f}, {above:+.2f} | within ±3 |")
        (folder / "dexterity.toml").write_text(PRESET, encoding="utf-8")
        command = [
            sys.executable,
            "-m",
            "planar_tui",
            "workspace",
            str(folder / "dexterity.toml"),
            "--no-map",
            "--out-dir",
            str(folder),
        ]
        cached = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
        # no bytecode read or written: an empty cache folder, nothing written to it
        empty = str(folder / "no-bytecode")
        uncached = {**cached, "PYTHONDONTWRITEBYTECODE": "1", "PYTHONPYCACHEPREFIX": empty}
        process(command, cached, runs=1)  # the Numba and bytecode caches warm
        seconds, cpu = process(command, cached)
        print(f"| whole process, warm (s, median of 3; load {load()}) | {seconds:.2f} | ≤ 5 |")
        print(f"| its CPU time, user + system (s, median of 3) | {cpu:.2f} | |")
        seconds, cpu = process(command, uncached)
        print(f"| the same, no bytecode cache (s wall, s CPU) | {seconds:.2f}, {cpu:.2f} | |")
        plain = PRESET.replace("elbow = [1, -1, 1]\nkappa_max = 4\n", "")
        (folder / "dexterity.toml").write_text(plain, encoding="utf-8")
        process(command, cached, runs=1)
        seconds, cpu = process(command, cached)
        print(
            f"| baseline: the job without kappa_max (s wall, s CPU) | {seconds:.2f}, {cpu:.2f} | |"
        )
    print(f"load after: {load()}")


if __name__ == "__main__":
    import argparse

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--grid", type=float, default=0.01, help="grid step in cm")
    main(parser.parse_args().grid)

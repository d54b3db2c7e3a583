"""Benchmark of the orientation workspaces and the singularity paving (issue 12, parts 3-4):
``python benchmarks/bench_orientation.py``.

In process, kernels compiled and loaded first, paper B's Table 3 robot and limits; each
case's time is the median of 3 runs, with the ratio to the single-orientation
arc-distance paving at the same ε (the baseline, run in the same process):

* maximal and total workspaces over φ in [-10°, 10°] (boxes, certified bracket) and the
  certified sampled reference that checks them;
* the type II singularity paving at φ = 0 (elbow [1, -1, 1], centre: the centroid) with
  the singularity-free circle's bracket.

``--parallel``: the level-wise pavings on 1 and 2 threads (maximal and total over
[-10°, 10°] at ε = 0.05 cm, the arc-distance paving of φ = 0 at ε = 0.005 cm with
refinement to 0.0025 cm): best of 3 interleaved runs per thread count, the CPU time of the
2-thread run, the 1-minute load, and a check that the boxes and areas are identical.
"""

from __future__ import annotations

import math
import statistics
import sys
import time
from dataclasses import replace
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from planar_tui.runtime import prepare_kernels  # noqa: E402

prepare_kernels()  # before any kernel is imported

from planar_tui.jobkind import Job  # noqa: E402
from planar_tui.progress import Progress  # noqa: E402
from planar_tui.workspace.paving.levels import BoxBudget  # noqa: E402
from planar_tui.workspace.rrr.compute import compute_workspace  # noqa: E402
from planar_tui.workspace.rrr.job import WorkspaceSpec  # noqa: E402
from planar_tui.workspace.rrr.orientation import compute_orientation_workspace  # noqa: E402
from planar_tui.workspace.rrr.orientation_reference import reference_area  # noqa: E402
from planar_tui.workspace.rrr.robot import Robot3RRR  # noqa: E402
from planar_tui.workspace.rrr.singularity import compute_singularities  # noqa: E402

ROBOT = Robot3RRR()
LIMITS = ((20.0, 70.0), (110.0, 160.0), (245.0, 295.0))
#: The singularity paving's search box (holds Table 3's workspace at φ = 0), cm.
EXTENT = (28.0, 52.0, 0.0, 24.0)


class _Job:
    def __init__(self, spec):
        self.spec, self.preset_path, self.label = spec, "bench", "bench:workspace"
        self.key = "workspace"


def median_time(function, repeats=3):
    times, result = [], None
    for _ in range(repeats):
        started = time.perf_counter()
        result = function()
        times.append(time.perf_counter() - started)
    return statistics.median(times), result


def spec(**changes):
    base = WorkspaceSpec(
        joint_limits_deg=LIMITS, precision_cm=0.25, form="arc-distance", geometric_reference=False
    )
    return replace(base, **changes)


def main() -> None:
    from planar_tui.workspace.rrr.job import prepare_workspace

    rows = []
    for eps in (0.25, 0.125):
        single = spec(precision_cm=eps)
        base_s, base = median_time(
            lambda s=single: compute_workspace(ROBOT, s, BoxBudget(_Job(s), Progress()))
        )
        rows.append(("single φ = 0", eps, base_s, base.boxes_processed, base, 1.0))
        for mode in ("maximal", "total"):
            ranged = spec(precision_cm=eps, orientation_deg=(-10.0, 10.0), orientation_mode=mode)
            seconds, out = median_time(
                lambda s=ranged: compute_orientation_workspace(
                    ROBOT, s, BoxBudget(_Job(s), Progress())
                )
            )
            rows.append(
                (f"{mode} [-10, 10]°", eps, seconds, out.boxes_processed, out, seconds / base_s)
            )
        for precision in (eps, eps / 8):
            job = prepare_workspace(
                Job(
                    kind="workspace",
                    index=1,
                    label="bench:workspace",
                    robot=ROBOT,
                    spec=spec(
                        precision_cm=eps,
                        singularities=True,
                        elbow=(1, -1, 1),
                        singularity_precision_cm=precision,
                    ),
                    output="bench.csv",
                    preset_path=Path("bench"),
                )
            )
            seconds, out = median_time(
                lambda j=job: compute_singularities(
                    ROBOT, j.spec, EXTENT, BoxBudget(j, Progress()), j
                )
            )
            rows.append(
                (
                    f"singularities, ε_s = {precision:g}",
                    eps,
                    seconds,
                    out.boxes_processed,
                    out,
                    seconds / base_s,
                )
            )
    print("| case | ε (cm) | seconds | boxes | bracket | ratio to single φ |")
    print("|---|---:|---:|---:|---|---:|")
    for name, eps, seconds, boxes, out, ratio in rows:
        if hasattr(out, "radius_lo_cm"):
            bracket = f"r in [{out.radius_lo_cm:.4f}, {out.radius_hi_cm:.4f}] cm"
        else:
            bracket = f"[{out.area_inside_cm2:.2f}, {out.area_kept_cm2:.2f}] cm²"
        print(f"| {name} | {eps:g} | {seconds:.3f} | {boxes:,} | {bracket} | {ratio:.1f} |")
    limits_rad = tuple((math.radians(a), math.radians(b)) for a, b in LIMITS)
    for mode in ("maximal", "total"):
        seconds, ref = median_time(
            lambda m=mode: reference_area(ROBOT, limits_rad, (-10.0, 10.0), m), repeats=1
        )
        print(
            f"| sampled reference, {mode} (400 φ) | | {seconds:.3f} | | "
            f"[{ref.inner_cm2:.2f}, {ref.outer_cm2:.2f}] cm² | |"
        )


def parallel() -> None:
    import os

    import numba
    import numpy as np

    def orientation(mode):
        s = spec(precision_cm=0.05, orientation_deg=(-10.0, 10.0), orientation_mode=mode)
        return lambda: compute_orientation_workspace(ROBOT, s, BoxBudget(_Job(s), Progress()))

    single = spec(precision_cm=0.005, refine_precision_cm=0.0025)
    cases = {
        "maximal [-10, 10]°, ε = 0.05": orientation("maximal"),
        "total [-10, 10]°, ε = 0.05": orientation("total"),
        "arc-distance φ = 0, ε = 0.005 → 0.0025": lambda: compute_workspace(
            ROBOT, single, BoxBudget(_Job(single), Progress())
        ),
    }
    before = numba.get_num_threads()
    print("| case | boxes | 1 thread s | 2 threads s (CPU s) | speed-up | 1-min load |")
    print("|---|---:|---:|---:|---:|---:|")
    try:
        for name, run in cases.items():
            run()  # compiled and warm
            wall, cpu, outs = {1: [], 2: []}, {1: [], 2: []}, {}
            for _ in range(3):
                for threads in (1, 2):
                    numba.set_num_threads(threads)
                    started, cpu_started = time.perf_counter(), time.process_time()
                    outs[threads] = run()
                    wall[threads].append(time.perf_counter() - started)
                    cpu[threads].append(time.process_time() - cpu_started)
            one, two = outs[1], outs[2]
            assert np.array_equal(one.boxes, two.boxes) and np.array_equal(one.status, two.status)
            assert (one.area_inside_cm2, one.area_kept_cm2) == (
                two.area_inside_cm2,
                two.area_kept_cm2,
            )
            w1, w2 = min(wall[1]), min(wall[2])
            c2 = cpu[2][wall[2].index(w2)]
            print(
                f"| {name} | {len(one.boxes):,} | {w1:.3f} | {w2:.3f} ({c2:.2f}) | "
                f"{w1 / w2:.2f}× | {os.getloadavg()[0]:.1f} |",
                flush=True,
            )
    finally:
        numba.set_num_threads(before)


if __name__ == "__main__":
    parallel() if "--parallel" in sys.argv[1:] else main()

"""Cancel latency per stage: ``python benchmarks/bench_cancel.py [--runs 5]``.

For every stage of every runner (simulate integrating; sensitivity sampling, evaluation,
analysis; workspace bisection and leg-wise paving; compiling kernels), a run is started, a timer thread asks
it to cancel a moment after the stage began (``Progress.request_cancel``, as the app's
escape and the CLI's Ctrl-C do) and the time until the runner raises ``Cancelled`` is
measured. Prints the median, min and max of ``--runs`` runs per stage (goal: ≤ 0.2 s,
``planar_tui.progress.CHECK_INTERVAL_S``), with the machine and its load. The compiling
stage runs in a fresh process with an empty ``NUMBA_CACHE_DIR``. ``tests/test_cancel_latency.py``
uses the same probes with smaller sizes and a generous bound.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

#: Run in a fresh process with an empty kernel cache: cancel while kernels compile.
COMPILE_PROBE = """
import json, os, sys
from benchmarks.bench_cancel import cancel_latency, robot_job
from planar_tui import batch
job = robot_job("sensitivity", "samples = 8")
latency, stage = cancel_latency(lambda p: batch.run_job(job, p), "compiling", float(sys.argv[1]))
print(json.dumps({"latency_s": latency, "stage": stage}), flush=True)
os._exit(0)  # the compilation goes on in a daemon thread: do not wait for it
"""


def cancel_latency(run, stage: str, delay_s: float) -> tuple[float, str]:
    """Seconds from a cancel request ``delay_s`` after ``stage`` began (first update whose
    stage starts with ``stage``) until ``run(progress)`` raises ``Cancelled``, and the stage
    the run was in when asked. Raises ``RuntimeError`` if the run ends without a cancel."""
    from planar_tui.errors import Cancelled
    from planar_tui.progress import Progress

    requested: list[tuple[float, str]] = []
    timer: list[threading.Timer] = []

    def fire() -> None:
        requested.append((time.perf_counter(), progress.stage))
        progress.request_cancel()

    def on_update(state) -> None:
        if not timer and state.stage.startswith(stage):
            timer.append(threading.Timer(delay_s, fire))
            timer[0].start()

    progress = Progress(on_update=on_update)
    try:
        run(progress)
    except Cancelled:
        return time.perf_counter() - requested[0][0], requested[0][1]
    finally:
        for t in timer:
            t.cancel()
    raise RuntimeError(f"the run ended before a cancel in stage {stage!r}")


def robot_job(kind: str, body: str, robot: str = "6r"):
    """A job of ``kind`` from TOML ``body`` on paper A's 6R robot (or the 3-RRR)."""
    from planar_tui.presets import load_preset

    robots = {
        "6r": "[robot]\nlengths_m = [0.25, 0.25, 0.2, 0.2, 0.15, 0.15]\n"
        "masses_kg = [0.484, 0.484, 0.387, 0.387, 0.29, 0.29]\n",
        "3rrr": "[robot3rrr]\n",
    }
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "job.toml"
        path.write_text(f"{robots[robot]}[{kind}]\n{body}\n", encoding="utf-8")
        (job,) = load_preset(path).jobs_of(kind)
    return job


def in_process_cases(samples: int, precision_cm: float):
    """(job, stage, run, delay) per in-process stage; ``samples`` the Sobol' N of the
    sensitivity job, ``precision_cm`` the workspace's ε (mean-value, paper B Table 5, joint
    strategy); the leg-wise paving runs issue 12's 120° case at ε = 0.01 cm."""
    from planar_tui import batch
    from planar_tui.sensitivity import engine

    sensitivity = robot_job("sensitivity", f"samples = {samples}")
    sobol_only = dataclasses.replace(
        sensitivity, spec=dataclasses.replace(sensitivity.spec, methods=("sobol",))
    )
    simulate = robot_job("simulate", "duration_s = 200.0\nstep_s = 1e-4\nevery = 1000")
    motion = robot_job(
        "motion_uncertainty", 'duration_s = 1.0\nstep_s = 1e-4\nmethods = ["sobol"]\nsamples = 256'
    )
    workspace = robot_job(
        "workspace",
        "joint_limits_deg = [[50, 70], [140, 160], [260, 280]]\n"
        f'precision_cm = {precision_cm}\ngeometric_reference = false\nstrategy = "joint"',
        robot="3rrr",
    )
    legwise = robot_job(  # issue 12's 120° case: about 1 s of paving at ε = 0.01 cm
        "workspace",
        "joint_limits_deg = [[-30, 90], [90, 210], [210, 330]]\norientation_deg = -20\n"
        "precision_cm = 0.01\ngeometric_reference = false",
        robot="3rrr",
    )

    def orientation(precision_cm: float, refine: str = ""):  # 120° case, every orientation
        return robot_job(
            "workspace",
            "joint_limits_deg = [[-30, 90], [90, 210], [210, 330]]\n"
            'orientation_deg = [-180, 180]\norientation_mode = "maximal"\n'
            f"precision_cm = {precision_cm}\n{refine}geometric_reference = false",
            robot="3rrr",
        )

    # a fine paving's first, large boxes (each bisected Φ for seconds before pieces had a
    # floor from the box's size) and a fine refinement of coarse boundary boxes
    fine_range = orientation(0.0002)
    refined_range = orientation(0.5, "refine_precision_cm = 0.0005\n")

    def fresh_designs(job):
        def run(progress):
            engine.unit_design.cache_clear()
            return batch.run_job(job, progress)

        return run

    return [
        ("simulate", "integrating", lambda p: batch.run_job(simulate, p), 0.05),
        ("motion", "integrating", lambda p: batch.run_job(motion, p), 0.1),
        ("sensitivity", "sampling", fresh_designs(sensitivity), 0.02),
        ("sensitivity", "evaluation", lambda p: batch.run_job(sensitivity, p), 0.02),
        ("sensitivity, Sobol'", "analysis", lambda p: batch.run_job(sobol_only, p), 0.05),
        ("sensitivity, both", "analysis", lambda p: batch.run_job(sensitivity, p), 0.3),
        ("workspace", "mean-value bisection", lambda p: batch.run_job(workspace, p), 0.1),
        ("workspace", "mean-value leg-wise paving", lambda p: batch.run_job(legwise, p), 0.1),
        ("workspace, orientation range", "maximal", lambda p: batch.run_job(fine_range, p), 0.3),
        (
            "workspace, orientation range",
            "boundary refinement",
            lambda p: batch.run_job(refined_range, p),
            0.3,
        ),
    ]


def compile_latency(delay_s: float) -> tuple[float, str]:
    """Cancel latency while kernels compile: a fresh process, empty kernel cache."""
    with tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache, PLANAR_TUI_CACHE_DIR="")
        env["PYTHONPATH"] = str(REPO)
        out = subprocess.run(
            [sys.executable, "-c", COMPILE_PROBE, str(delay_s)],
            capture_output=True,
            text=True,
            env=env,
            cwd=REPO,
            timeout=300,
        )
        lines = out.stdout.strip().splitlines()
        if not lines:
            raise RuntimeError(out.stderr)
        found = json.loads(lines[-1])
        return found["latency_s"], found["stage"]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--samples", type=int, default=1 << 18)
    parser.add_argument("--precision", type=float, default=0.001953125)
    args = parser.parse_args()
    os.environ["PLANAR_TUI_CACHE_DIR"] = ""  # the sampling stage draws every time
    from planar_tui.runtime import prepare_kernels
    from planar_tui.warmup import warm_kernels

    prepare_kernels()
    from planar_tui.progress import Progress
    from planar_tui.registry import JOB_KINDS

    warm_kernels(JOB_KINDS, Progress())
    rows = []
    for job, stage, run, delay in in_process_cases(args.samples, args.precision):
        found = [cancel_latency(run, stage, delay) for _ in range(args.runs)]
        rows.append((f"{job}: {found[0][1]} (after {delay:g} s)", [f[0] for f in found]))
    compiled = [compile_latency(1.0) for _ in range(args.runs)]
    rows.append((f"sensitivity: {compiled[0][1]} (after 1 s)", [f[0] for f in compiled]))
    load = Path("/proc/loadavg").read_text().split()[:3] if Path("/proc/loadavg").exists() else []
    print(f"bench_cancel  {platform.machine()} {os.cpu_count()} CPUs  {platform.processor()}")
    print(f"Sobol' N = {args.samples} (6R, D = 12), workspace ε = {args.precision} cm")
    print("\n| stage | median s | min s | max s | runs |\n|---|---:|---:|---:|---:|")
    for name, values in rows:
        print(
            f"| {name} | {statistics.median(values):.3f} | {min(values):.3f} "
            f"| {max(values):.3f} | {len(values)} |"
        )
    print(f"\nload average after the runs: {' '.join(load)}")


if __name__ == "__main__":
    main()

"""Benchmark of a parallel robot's torque sensitivity along a path (``python
benchmarks/bench_path_sensitivity.py [--runs 3] [--against COMMIT]``): the bundled preset
``presets/path-3rrr-sensitivity.toml`` (3-RRR, 1 000 steps, ten inputs) with Sobol' (N = 256,
3 072 robots) and PCE (640 robots), the whole process

    planar-tui path3rrr_sensitivity presets/path-3rrr-sensitivity.toml -m sobol -m pce

warm: an unmeasured first run compiles the kernels, writes the byte-code and draws the
designs into their caches, the next ``--runs`` runs are timed (wall time from spawn to exit
and the child's user + system CPU time, which a machine loaded by other work inflates far
less; byte-code caching on as in a user's install, under a temporary
``PYTHONPYCACHEPREFIX``). Each run is printed with the 1-min load after it, then the
medians.

``--against COMMIT`` runs the same command with an earlier commit too (a ``git worktree``
of it, :func:`benchmarks.bench_startup.checkout_of`), the two sides alternating so both
see the same load, and prints the ratios of the medians (this checkout over the commit).

Goal (issue 35): a Sobol'/PCE torque-sensitivity study of a 3-RRR path (1 000 steps, 9+
inputs) <= 10 s whole process warm on 2 cores.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from benchmarks.bench_startup import checkout_of, children_cpu_s, median_of

ROOT = Path(__file__).resolve().parent.parent
PRESET = ROOT / "presets" / "path-3rrr-sensitivity.toml"
GOAL_S = 10.0


def command(out: Path) -> list[str]:
    """One ``planar-tui path3rrr_sensitivity`` run of the bundled preset, Sobol' and PCE."""
    return [
        sys.executable,
        "-m",
        "planar_tui",
        "path3rrr_sensitivity",
        str(PRESET),
        "--method",
        "sobol",
        "--method",
        "pce",
        "--out-dir",
        str(out),
    ]


def timed(command: list[str], env: dict[str, str], folder: Path) -> tuple[float, float]:
    """(wall s, CPU s) of one process running ``command`` in ``folder``: not in a checkout,
    whose ``planar_tui`` folder ``python -m`` would import before ``PYTHONPATH``'s."""
    cpu_before = children_cpu_s()
    started = time.perf_counter()
    subprocess.run(command, check=True, capture_output=True, env=env, cwd=folder)
    return time.perf_counter() - started, children_cpu_s() - cpu_before


def load() -> str:
    """The 1, 5 and 15 minute load averages."""
    return " ".join(f"{v:.2f}" for v in os.getloadavg())


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=3, help="timed processes per side")
    parser.add_argument("--against", metavar="COMMIT", help="alternate with COMMIT's runs")
    arguments = parser.parse_args()
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    with tempfile.TemporaryDirectory() as folder, contextlib.ExitStack() as stack:
        env["PYTHONPYCACHEPREFIX"] = str(Path(folder) / "pycache")
        sides = {"this checkout": env}
        if arguments.against:
            other = stack.enter_context(checkout_of(arguments.against, Path(folder) / "other"))
            sides[arguments.against] = dict(env, PYTHONPATH=str(other))
        print(
            f"{platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}; "
            f"load before {load()}"
        )
        out = Path(folder) / "out"
        for name, side_env in sides.items():
            wall, cpu = timed(command(out), side_env, Path(folder))
            print(f"{name}: first run (compiles, caches) {wall:.1f} s wall, {cpu:.1f} s CPU")
        samples: dict[str, list[tuple[float, float]]] = {name: [] for name in sides}
        for run in range(arguments.runs):  # the sides alternate: the same load
            for name, side_env in sides.items():
                samples[name].append(timed(command(out), side_env, Path(folder)))
                wall, cpu = samples[name][-1]
                print(f"{name} run {run + 1}: {wall:.1f} s wall, {cpu:.1f} s CPU, load {load()}")
    medians = {name: median_of(found) for name, found in samples.items()}
    wall, cpu = medians["this checkout"]
    verdict = "met" if wall <= GOAL_S else "NOT met"
    print(
        "whole process warm, Sobol' N=256 + PCE 640, 1 001 poses, 10 inputs, median of "
        f"{arguments.runs}: {wall:.1f} s wall, {cpu:.1f} s CPU (goal <= {GOAL_S:g} s wall: "
        f"{verdict})"
    )
    if arguments.against:
        their_wall, their_cpu = medians[arguments.against]
        print(
            f"{arguments.against}: {their_wall:.1f} s wall, {their_cpu:.1f} s CPU; ratio "
            f"(this / {arguments.against}): wall {wall / their_wall:.2f}, "
            f"CPU {cpu / their_cpu:.2f}"
        )
    print(f"load after: {load()}")


if __name__ == "__main__":
    main()

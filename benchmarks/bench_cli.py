"""Whole-process benchmark of the ``planar-tui`` command (``python benchmarks/bench_cli.py``).

Every row is a fresh process, timed from spawn to exit (median of several runs):

* ``planar-tui --help`` (must not import numba, SALib or Textual);
* ``planar-tui torques`` on the Table 1 preset with an empty Numba cache (the first run
  compiles the kernels) and again with the cache it left (``cache=True`` reuse);
* a 20 s simulation of the Table 1 6R robot (RK4, step 1e-4 s, every 10th step written)
  through ``planar-tui simulate``, against a Python process that steps MuJoCo's own RK4 over
  the same model for the same 200 000 steps and writes the same rows with ``numpy.savetxt``.

``--ab DIR`` (issue 21) instead times this checkout against the checkout DIR (e.g. main's),
each with its own ``.venv/bin/python``, in interleaved fresh processes (median of
``--runs``, default 5), with byte-code caching on (``PYTHONDONTWRITEBYTECODE`` removed: a
user's install writes ``.pyc``, here under a temporary ``PYTHONPYCACHEPREFIX``): ``python -c pass`` and ``python -S -c pass`` (the
interpreter alone, without and with ``site``: the difference is what the ``.pth`` files,
e.g. pin's ``cmeel.pth``, cost), ``planar-tui --help`` and a warm
``planar-tui run paper-b-table3``; with the 1-min load before and after.
"""

from __future__ import annotations

import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
PYTHON = sys.executable
TABLE1 = REPO / "presets" / "paper-a-table1.toml"

MUJOCO_SCRIPT = """
import sys
import numpy as np
import mujoco
sys.path.insert(0, {repo!r})
from benchmarks.mujoco_model import chain_model
lengths = [0.25, 0.25, 0.20, 0.20, 0.15, 0.15]
masses = [0.484, 0.484, 0.387, 0.387, 0.290, 0.290]
inertias = [2.54e-3, 2.54e-3, 1.31e-3, 1.31e-3, 5.61e-4, 5.61e-4]
model, data = chain_model(lengths, masses, inertias, 9.81, 1e-4)
data.qfrc_applied[:] = [2.0, 0.3, 0.1, 0.03, 0.03, 0.001]
steps, every = 200_000, 10
rows = np.empty((steps // every + 1, 13))
rows[0] = [0.0, *data.qpos, *data.qvel]
for k in range(1, steps + 1):
    mujoco.mj_step(model, data)
    if k % every == 0:
        rows[k // every] = [data.time, *data.qpos, *data.qvel]
np.savetxt({out!r}, rows, delimiter=",", fmt="%.17g")
"""


def wall_seconds(command: list[str], env: dict | None = None, runs: int = 3) -> float:
    """Median wall time of ``command`` over ``runs`` fresh processes (exit code checked)."""
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        subprocess.run(command, check=True, capture_output=True, env=env, cwd=REPO)
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def load() -> str:
    return Path("/proc/loadavg").read_text().split()[0]


def ab(other: Path, runs: int) -> None:
    """``--ab DIR``: this checkout against DIR's, interleaved (module docstring)."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    checkouts = {"this": REPO, "other": other.resolve()}
    with tempfile.TemporaryDirectory() as folder:
        env["PYTHONPYCACHEPREFIX"] = str(Path(folder) / "pycache")  # nothing written in DIR
        cases = {
            "python -S -c pass": ["-S", "-c", "pass"],
            "python -c pass": ["-c", "pass"],
            "planar-tui --help": ["-m", "planar_tui", "--help"],
            "run paper-b-table3 (warm)": [
                "-m",
                "planar_tui",
                "run",
                "paper-b-table3",
                "--out-dir",
                folder,
            ],
        }
        print(f"load before {load()}; this = {REPO}, other = {checkouts['other']}")
        for name, arguments in cases.items():
            times: dict[str, list[float]] = {key: [] for key in checkouts}
            for root in checkouts.values():  # warm the caches first
                subprocess.run(
                    [str(root / ".venv/bin/python"), *arguments],
                    check=True,
                    capture_output=True,
                    env=env,
                    cwd=root,
                )
            for _ in range(runs):
                for key, root in checkouts.items():
                    start = time.perf_counter()
                    subprocess.run(
                        [str(root / ".venv/bin/python"), *arguments],
                        check=True,
                        capture_output=True,
                        env=env,
                        cwd=root,
                    )
                    times[key].append(time.perf_counter() - start)
            this, theirs = (statistics.median(times[key]) for key in checkouts)
            print(
                f"{name:<28} this {this:7.3f} s  other {theirs:7.3f} s  "
                f"other/this {theirs / this:5.2f}  (load {load()})"
            )


def main() -> None:
    if "--ab" in sys.argv:
        runs = int(sys.argv[sys.argv.index("--runs") + 1]) if "--runs" in sys.argv else 5
        ab(Path(sys.argv[sys.argv.index("--ab") + 1]), runs)
        return
    env = dict(os.environ)
    cli = [PYTHON, "-m", "planar_tui"]
    rows: list[tuple[str, float, str]] = []
    with tempfile.TemporaryDirectory() as folder:
        folder = Path(folder)
        rows.append(("planar-tui --help", wall_seconds([*cli, "--help"], runs=5), ""))

        cold_env = dict(env, NUMBA_CACHE_DIR=str(folder / "numba-cache"))
        torques = [*cli, "torques", str(TABLE1), "--out-dir", str(folder)]
        cold = wall_seconds(torques, env=cold_env, runs=1)
        warm = wall_seconds(torques, env=cold_env, runs=3)
        rows.append(("torques, empty Numba cache (compiles)", cold, f"{cold / warm:.1f}x warm"))
        rows.append(("torques, cache reused (second process)", warm, "1.00"))

        preset = folder / "twenty.toml"
        preset.write_text(TABLE1.read_text().replace("duration_s = 1.0", "duration_s = 20.0", 1))
        ours = wall_seconds([*cli, "simulate", str(preset), "--out-dir", str(folder)])
        script = MUJOCO_SCRIPT.format(repo=str(REPO), out=str(folder / "mujoco.csv"))
        theirs = wall_seconds([PYTHON, "-c", script])
        note = "both 20 s runs (the preset also holds a 1 s free fall)"
        rows.append(("planar-tui simulate, 20 s 6R, step 1e-4 s", ours, "1.00"))
        rows.append(
            ("Python + MuJoCo RK4 mj_step, same 20 s", theirs, f"{theirs / ours:.1f}x ours")
        )

    width = max(len(name) for name, _, _ in rows)
    print(f"{'whole process':<{width}}  {'seconds':>8}  ratio")
    for name, seconds, ratio in rows:
        print(f"{name:<{width}}  {seconds:8.3f}  {ratio}")
    print(f"({note}; {os.cpu_count()} cores, {sys.version.split()[0]})")


if __name__ == "__main__":
    main()

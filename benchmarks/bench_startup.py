"""Start-up of whole ``planar-tui`` processes (issue 21): ``python benchmarks/bench_startup.py``.

Every row is the median of ``--runs`` fresh processes (default 7; one unmeasured run of
each first, so byte-code and the Numba kernel cache are warm), timed two ways: wall time
from spawn to exit, and the child's user + system CPU time
(``resource.getrusage(RUSAGE_CHILDREN)``), which a machine loaded by other work inflates
far less than the wall time. Byte-code caching is on as in a user's install
(``PYTHONDONTWRITEBYTECODE`` removed; the ``.pyc`` files go under a temporary
``PYTHONPYCACHEPREFIX``, nothing is written in the checkout).

Rows: the baselines ``python -c pass`` (the interpreter with ``site`` and the
environment's ``.pth`` files) and ``python -c "import numpy"``; then ``planar-tui --help``
and ``planar-tui run --help`` twice each: rendered (Typer and Rich imported, every command
built: the saved pages turned off, ``PLANAR_TUI_HELP_CACHE_DIR=""``) and printed from the
saved page (:mod:`planar_tui.helpcache`, in a temporary folder; the unmeasured first run
saves it), and a warm ``planar-tui run paper-b-table3 --out-dir TMP`` (its seven
workspace pavings computed). The ratio column is each row's CPU time over the bare
interpreter's. The 1-min load (``os.getloadavg()``) is printed before and after.
Goals of issue 21 (quiet machine): ``--help`` ≤ 0.15 s, warm ``run paper-b-table3``
≤ 2.0 s.
"""

from __future__ import annotations

import argparse
import os
import platform
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
PYTHON = sys.executable
#: The console script next to the interpreter (what a user runs), else ``python -m``.
SCRIPT = Path(PYTHON).parent / "planar-tui"
CLI = [str(SCRIPT)] if SCRIPT.exists() else [PYTHON, "-m", "planar_tui"]
GOALS_S = {"planar-tui --help": 0.15, "planar-tui run paper-b-table3 (warm)": 2.0}


def children_cpu_s() -> float:
    """User + system CPU seconds of every waited-for child so far."""
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def timed(command: list[str], env: dict[str, str]) -> tuple[float, float]:
    """(wall s, CPU s) of one fresh process running ``command`` (exit code checked)."""
    cpu_before = children_cpu_s()
    started = time.perf_counter()
    subprocess.run(command, check=True, capture_output=True, env=env, cwd=REPO)
    return time.perf_counter() - started, children_cpu_s() - cpu_before


def load() -> float:
    return os.getloadavg()[0]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=7, help="processes per row (median)")
    parser.add_argument("--skip-run", action="store_true", help="only the --help rows")
    arguments = parser.parse_args()
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    with tempfile.TemporaryDirectory() as folder:
        env["PYTHONPYCACHEPREFIX"] = str(Path(folder) / "pycache")
        env["PLANAR_TUI_HELP_CACHE_DIR"] = str(Path(folder) / "help-pages")
        rendered = dict(env, PLANAR_TUI_HELP_CACHE_DIR="")
        cases = {
            "python -c pass (baseline)": ([PYTHON, "-c", "pass"], env),
            'python -c "import numpy"': ([PYTHON, "-c", "import numpy"], env),
            "planar-tui --help (rendered)": ([*CLI, "--help"], rendered),
            "planar-tui --help": ([*CLI, "--help"], env),
            "planar-tui run --help (rendered)": ([*CLI, "run", "--help"], rendered),
            "planar-tui run --help": ([*CLI, "run", "--help"], env),
        }
        if not arguments.skip_run:
            out = str(Path(folder) / "out")
            cases["planar-tui run paper-b-table3 (warm)"] = (
                [*CLI, "run", "paper-b-table3", "--out-dir", out], env,
            )  # fmt: skip
        print(f"{platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}, "
              f"{' '.join(CLI)}; 1-min load before {load():.2f}")  # fmt: skip
        rows = []
        for name, (command, case_env) in cases.items():
            timed(command, case_env)  # warm: byte-code written, kernels cached, page saved
            samples = [timed(command, case_env) for _ in range(arguments.runs)]
            wall = statistics.median(s[0] for s in samples)
            cpu = statistics.median(s[1] for s in samples)
            rows.append((name, wall, cpu, load()))
    base_cpu = rows[0][2]
    width = max(len(name) for name, *_ in rows)
    print(f"{'command':<{width}}  {'wall s':>7}  {'CPU s':>7}  {'CPU/baseline':>12}  "
          f"{'goal s':>6}  load")  # fmt: skip
    for name, wall, cpu, after in rows:
        goal = GOALS_S.get(name)
        print(f"{name:<{width}}  {wall:7.3f}  {cpu:7.3f}  {cpu / base_cpu:12.1f}  "
              f"{'' if goal is None else f'{goal:.2f}':>6}  {after:.2f}")  # fmt: skip
    print(f"(median of {arguments.runs} processes each; 1-min load after {load():.2f})")


if __name__ == "__main__":
    main()

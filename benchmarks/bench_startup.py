"""Start-up of whole ``planar-tui`` processes: ``python benchmarks/bench_startup.py``.

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
Goals (quiet machine): ``--help`` ≤ 0.15 s, warm ``run paper-b-table3``
≤ 2.0 s.

``--against COMMIT`` pairs every row with the same command run by an earlier commit (a
``git worktree`` of it in a temporary folder, its ``package-dir`` folders linked into its
package, imported through ``PYTHONPATH``; both sides run as ``python -m planar_tui``): the
two sides' processes alternate, so both see the same load, and a ratio column (this
checkout's median CPU and wall time over the commit's) is added. ``--only TEXT`` keeps the
rows whose name contains TEXT; the row ``planar-tui run paper-b-table3 --job workspace[4]
(warm)`` is Table 3's mean-value job alone (1.007 s against 0.841 s at 6fe5bdb).
"""

from __future__ import annotations

import argparse
import contextlib
import os
import platform
import resource
import statistics
import subprocess
import sys
import tempfile
import time
import tomllib
from collections.abc import Iterator
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
    """(wall s, CPU s) of one fresh process running ``command`` (exit code checked), started
    in a neutral folder: ``python -m`` puts its working folder first on ``sys.path``, so in
    the repository it would import this checkout's package whatever ``PYTHONPATH`` says."""
    cpu_before = children_cpu_s()
    started = time.perf_counter()
    subprocess.run(command, check=True, capture_output=True, env=env, cwd=tempfile.gettempdir())
    return time.perf_counter() - started, children_cpu_s() - cpu_before


def load() -> float:
    return os.getloadavg()[0]


@contextlib.contextmanager
def checkout_of(commit: str, folder: Path) -> Iterator[Path]:
    """A detached ``git worktree`` of ``commit`` in ``folder`` whose ``package-dir`` folders
    (``kernels/``, ``presets/``) are linked where the package imports them, so that
    ``PYTHONPATH=folder`` imports that commit's planar-tui; removed after."""
    subprocess.run(
        ["git", "-C", str(REPO), "worktree", "add", "--detach", str(folder), commit],
        check=True,
        capture_output=True,
    )
    try:
        with (folder / "pyproject.toml").open("rb") as stream:
            mapped = tomllib.load(stream)["tool"]["setuptools"].get("package-dir", {})
        for package, source in mapped.items():
            (folder / package.replace(".", "/")).symlink_to(folder / source)
        yield folder
    finally:
        subprocess.run(
            ["git", "-C", str(REPO), "worktree", "remove", "--force", str(folder)],
            check=False,
            capture_output=True,
        )


def median_of(samples: list[tuple[float, float]]) -> tuple[float, float]:
    """(median wall s, median CPU s) of ``samples``."""
    return statistics.median(s[0] for s in samples), statistics.median(s[1] for s in samples)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=7, help="processes per row (median)")
    parser.add_argument("--skip-run", action="store_true", help="only the --help rows")
    parser.add_argument("--against", metavar="COMMIT", help="pair every row with COMMIT's")
    parser.add_argument("--only", metavar="TEXT", default="", help="rows whose name has TEXT")
    arguments = parser.parse_args()
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    with tempfile.TemporaryDirectory() as folder, contextlib.ExitStack() as stack:
        env["PYTHONPYCACHEPREFIX"] = str(Path(folder) / "pycache")
        env["PLANAR_TUI_HELP_CACHE_DIR"] = str(Path(folder) / "help-pages")
        rendered = dict(env, PLANAR_TUI_HELP_CACHE_DIR="")
        cli = [PYTHON, "-m", "planar_tui"] if arguments.against else CLI
        cases = {
            "python -c pass (baseline)": ([PYTHON, "-c", "pass"], env),
            'python -c "import numpy"': ([PYTHON, "-c", "import numpy"], env),
            "planar-tui --help (rendered)": ([*cli, "--help"], rendered),
            "planar-tui --help": ([*cli, "--help"], env),
            "planar-tui run --help (rendered)": ([*cli, "run", "--help"], rendered),
            "planar-tui run --help": ([*cli, "run", "--help"], env),
        }
        if not arguments.skip_run:
            out = str(Path(folder) / "out")
            cases["planar-tui run paper-b-table3 (warm)"] = (
                [*cli, "run", "paper-b-table3", "--out-dir", out],
                env,
            )
            cases["planar-tui run paper-b-table3 --job workspace[4] (warm)"] = (
                [*cli, "run", "paper-b-table3", "--job", "workspace[4]", "--out-dir", out],
                env,
            )
        cases = {name: case for name, case in cases.items() if arguments.only in name}
        other = None
        if arguments.against:
            other = stack.enter_context(checkout_of(arguments.against, Path(folder) / "other"))
        print(
            f"{platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}, "
            f"{' '.join(cli)}; 1-min load before {load():.2f}"
            + (f"; paired against {arguments.against}" if other else "")
        )
        rows = []
        for name, (command, case_env) in cases.items():
            theirs_env = dict(case_env, PYTHONPATH=str(other)) if other else None
            timed(command, case_env)  # warm: byte-code written, kernels cached, page saved
            if theirs_env is not None:
                timed(command, theirs_env)
            ours, theirs = [], []
            for _ in range(arguments.runs):  # the two sides alternate: the same load
                ours.append(timed(command, case_env))
                if theirs_env is not None:
                    theirs.append(timed(command, theirs_env))
            rows.append(
                (name, *median_of(ours), *(median_of(theirs) if theirs else (0, 0)), load())
            )
    base_cpu = next((row[2] for row in rows if "(baseline)" in row[0]), float("nan"))
    width = max(len(name) for name, *_ in rows)
    paired = f"  {'their wall':>10}  {'their CPU':>9}  {'CPU ratio':>9}  {'wall ratio':>10}"
    print(
        f"{'command':<{width}}  {'wall s':>7}  {'CPU s':>7}  {'CPU/baseline':>12}"
        f"{paired if other else ''}  {'goal s':>6}  load"
    )
    for name, wall, cpu, their_wall, their_cpu, after in rows:
        goal = GOALS_S.get(name)
        ratios = (
            (
                f"  {their_wall:10.3f}  {their_cpu:9.3f}  {cpu / their_cpu:9.3f}  "
                f"{wall / their_wall:10.3f}"
            )
            if other
            else ""
        )
        print(
            f"{name:<{width}}  {wall:7.3f}  {cpu:7.3f}  {cpu / base_cpu:12.1f}{ratios}  "
            f"{'' if goal is None else f'{goal:.2f}':>6}  {after:.2f}"
        )
    print(f"(median of {arguments.runs} processes each; 1-min load after {load():.2f})")


if __name__ == "__main__":
    main()

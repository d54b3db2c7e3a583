# ruff: noqa: E402  (the repository root goes on sys.path first)
"""Cold start: whole processes with an empty kernel cache, ``python benchmarks/bench_coldstart.py``.

Every row is one fresh process (``--runs`` of them, median) whose Numba kernel cache is a
new empty folder (``NUMBA_CACHE_DIR``) and whose Sobol'/eFAST design cache is off
(``PLANAR_TUI_CACHE_DIR=""``), so it compiles every kernel it calls: what a user's first
run after an install costs. Byte-code is warm (:func:`warm_byte_code`, as after an install). Rows:

* ``warmup KIND``: one job kind's kernels alone (:func:`planar_tui.warmup.warm_kernels`
  on that kind in a process of its own: its cold cost);
* ``planar-tui warmup``: every kind (as many compiling processes at once as cores);
* ``planar-tui simulate paper-a-table1``;
* ``planar-tui run PRESET`` for every bundled preset (its first run; sweeps and
  optimisations included, ``--workers 1``).

Each row gives the wall time, the CPU time of the process and its children
(``RUSAGE_CHILDREN``: less inflated by other work than the wall time on a shared machine)
and the 1-min load after it. Goals (a quiet 2-core machine): ``planar-tui
warmup`` ≤ 90 s, a bundled preset's first run ≤ 30 s, ``simulate paper-a-table1`` ≤ 10 s.

``--against COMMIT`` runs every row also with that commit (a ``git worktree``,
:func:`benchmarks.bench_startup.checkout_of`), the two sides alternating, and adds its
times and the ratios. ``--only TEXT`` keeps the rows whose name contains TEXT. A full
table takes long (tens of minutes on 2 cores): choose rows with ``--only``.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import platform
import subprocess
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from benchmarks.bench_startup import checkout_of, load, median_of, timed

PYTHON = sys.executable
CLI = [PYTHON, "-m", "planar_tui"]
GOALS_S = {"planar-tui warmup": 90.0, "planar-tui simulate paper-a-table1": 10.0}
PRESET_GOAL_S = 30.0
#: Warms one kind in this process (the kind is the argument).
WARM_KIND = (
    "import sys; from planar_tui.progress import Progress; "
    "from planar_tui.warmup import warm_kernels; warm_kernels([sys.argv[1]], Progress())"
)


def cases(out: Path) -> dict[str, list[str]]:
    """Every row's command (its output under ``out``)."""
    from planar_tui.registry import JOB_KINDS
    from planar_tui.resources import bundled_presets

    rows = {f"warmup {kind}": [PYTHON, "-c", WARM_KIND, kind] for kind in JOB_KINDS}
    rows["planar-tui warmup"] = [*CLI, "warmup"]
    rows["planar-tui simulate paper-a-table1"] = [
        *CLI,
        "simulate",
        "paper-a-table1",
        "--out-dir",
        str(out),
    ]
    for path in bundled_presets():
        rows[f"planar-tui run {path.stem}"] = [
            *CLI,
            "run",
            path.stem,
            "--out-dir",
            str(out / path.stem),
            "--workers",
            "1",
        ]
    return rows


def cold(command: list[str], env: dict[str, str], folder: Path) -> tuple[float, float]:
    """(wall s, CPU s) of ``command`` with a new, empty kernel cache under ``folder``."""
    cache = Path(tempfile.mkdtemp(prefix="kernels-", dir=folder))
    return timed(command, dict(env, NUMBA_CACHE_DIR=str(cache)))


def warm_byte_code(env: dict[str, str], checkout: Path) -> None:
    """Write the byte-code of every installed package and of ``checkout``'s sources where
    Python keeps it (``__pycache__``; unchanged files are skipped, so only a first run
    pays): else the first side of the first row compiles numba's, scipy's, rich's ...
    modules (seconds of CPU) and the other side finds them done."""
    import sysconfig

    folders = [sysconfig.get_paths()["purelib"], checkout / "planar_tui", checkout / "kernels"]
    subprocess.run(
        [PYTHON, "-m", "compileall", "-q", "-j", "0", *map(str, folders)],
        check=False,
        capture_output=True,
        env=env,
    )
    subprocess.run([*CLI, "--help"], check=True, capture_output=True, env=env)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=1, help="processes per row (median)")
    parser.add_argument("--against", metavar="COMMIT", help="pair every row with COMMIT's")
    parser.add_argument("--only", metavar="TEXT", default="", help="rows whose name has TEXT")
    arguments = parser.parse_args()
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    env["PLANAR_TUI_CACHE_DIR"] = ""
    with tempfile.TemporaryDirectory() as name, contextlib.ExitStack() as stack:
        folder = Path(name)
        other = None
        if arguments.against:
            other = stack.enter_context(checkout_of(arguments.against, folder / "other"))
        theirs_env = dict(env, PYTHONPATH=str(other)) if other else None
        chosen = {k: v for k, v in cases(folder / "out").items() if arguments.only in k}
        warm_byte_code(env, REPO)  # byte-code written first, by neither side's row
        if theirs_env is not None and other is not None:
            warm_byte_code(theirs_env, other)
        print(
            f"{platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}"
            f"; 1-min load before {load():.2f}"
            + (f"; paired against {arguments.against}" if other else ""),
            flush=True,
        )
        width = max(len(name) for name in chosen)
        header = f"{'cold':<{width}}  {'wall s':>7}  {'CPU s':>7}"
        if other:
            header += f"  {'their wall':>10}  {'their CPU':>9}  {'CPU ratio':>9}"
        print(f"{header}  {'goal s':>6}  load", flush=True)
        for row, command in chosen.items():
            ours, theirs = [], []
            for _ in range(arguments.runs):  # the two sides alternate: the same load
                ours.append(cold(command, env, folder))
                if theirs_env is not None:
                    theirs.append(cold(command, theirs_env, folder))
            wall, cpu = median_of(ours)
            line = f"{row:<{width}}  {wall:7.1f}  {cpu:7.1f}"
            if theirs:
                their_wall, their_cpu = median_of(theirs)
                line += f"  {their_wall:10.1f}  {their_cpu:9.1f}  {cpu / their_cpu:9.3f}"
            goal = GOALS_S.get(row, PRESET_GOAL_S if row.startswith("planar-tui run") else None)
            print(f"{line}  {'' if goal is None else f'{goal:.0f}':>6}  {load():.2f}", flush=True)
    print(f"(median of {arguments.runs} processes each; 1-min load after {load():.2f})")


if __name__ == "__main__":
    main()

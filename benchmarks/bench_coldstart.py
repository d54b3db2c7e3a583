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
table takes long (tens of minutes on 2 cores): choose rows with ``--only``. ``--warm``
runs each row's command a second time with the kernels its cold run cached (the run
itself: start, work, output) and adds its times and the difference of the CPU times (the
compilation). ``--timeout S`` stops a process after S s of wall time; its row then shows
the CPU time so far, marked ``>`` (a sweep's or an optimisation's long computation).
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

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from benchmarks.bench_startup import checkout_of, children_cpu_s, load, median_of

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


def timed(command: list[str], env: dict[str, str], timeout_s: float | None) -> tuple[float, float]:
    """(wall s, CPU s) of one fresh process running ``command`` (exit code checked) in a
    neutral folder (:func:`benchmarks.bench_startup.timed`); stopped after ``timeout_s``:
    then its CPU time so far, negated."""
    cpu_before = children_cpu_s()
    started = time.perf_counter()
    try:
        subprocess.run(
            command,
            check=True,
            capture_output=True,
            env=env,
            cwd=tempfile.gettempdir(),
            timeout=timeout_s,
        )
    except subprocess.TimeoutExpired:
        return time.perf_counter() - started, -(children_cpu_s() - cpu_before)
    return time.perf_counter() - started, children_cpu_s() - cpu_before


def cold(
    command: list[str], env: dict[str, str], folder: Path, warm: bool, timeout_s: float | None
) -> tuple[tuple[float, float], tuple[float, float] | None]:
    """(wall s, CPU s) of ``command`` with a new, empty kernel cache under ``folder``, and
    with ``warm`` of a second run on the kernels the first cached (else None)."""
    env = dict(env, NUMBA_CACHE_DIR=tempfile.mkdtemp(prefix="kernels-", dir=folder))
    first = timed(command, env, timeout_s)
    return first, timed(command, env, timeout_s) if warm and first[1] >= 0 else None


def seconds(value: float, width: int) -> str:
    """A CPU time, ``>`` before it when its process was stopped (negative)."""
    return f"{'>' if value < 0 else ''}{abs(value):.1f}".rjust(width)


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
    parser.add_argument("--warm", action="store_true", help="also a second, warm run")
    parser.add_argument("--timeout", type=float, metavar="S", help="stop a process after S s")
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
        if arguments.warm:
            header += f"  {'warm wall':>9}  {'warm CPU':>8}  {'compile CPU':>11}"
        print(f"{header}  {'goal s':>6}  load", flush=True)
        for row, command in chosen.items():
            ours, theirs, warm = [], [], []
            for _ in range(arguments.runs):  # the two sides alternate: the same load
                first, second = cold(command, env, folder, arguments.warm, arguments.timeout)
                ours.append(first)
                warm += [second] if second else []
                if theirs_env is not None:
                    theirs.append(cold(command, theirs_env, folder, False, arguments.timeout)[0])
            wall, cpu = median_of(ours)
            line = f"{row:<{width}}  {wall:7.1f}  {seconds(cpu, 7)}"
            if theirs:
                their_wall, their_cpu = median_of(theirs)
                line += f"  {their_wall:10.1f}  {seconds(their_cpu, 9)}  {cpu / their_cpu:9.3f}"
            if warm:
                warm_wall, warm_cpu = median_of(warm)
                line += f"  {warm_wall:9.1f}  {seconds(warm_cpu, 8)}  {cpu - warm_cpu:11.1f}"
            elif arguments.warm:
                line += f"  {'':>9}  {'':>8}  {'':>11}"
            goal = GOALS_S.get(row, PRESET_GOAL_S if row.startswith("planar-tui run") else None)
            print(f"{line}  {'' if goal is None else f'{goal:.0f}':>6}  {load():.2f}", flush=True)
    print(f"(median of {arguments.runs} processes each; 1-min load after {load():.2f})")


if __name__ == "__main__":
    main()

# ruff: noqa: E402  (the repository root goes on sys.path first)
"""Compile cost per kernel: ``python benchmarks/bench_kernels.py [UNIT...]``.

Each warm-up unit (``kind`` or ``kind:part``, :func:`planar_tui.warmup.units`; default
every unit) runs its example in a fresh process with an empty kernel cache
(``NUMBA_CACHE_DIR``) while numba's ``numba:compile`` events are timed: each kernel
signature's own compile CPU seconds (``time.process_time``, its callees' compilations
excluded), then the unit's whole process CPU (children included). A kernel listed under
two units is compiled by both when they run in separate processes; one with several
signatures is compiled once per signature. Prints the 1-min load before and after:
CPU seconds are less inflated than wall seconds by other work on a shared machine.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from benchmarks.bench_startup import load, timed

#: Runs one unit's example in this process, printing one JSON line of
#: ``[kernel, signature, own CPU s]`` per compiled signature.
TIMED_UNIT = """
import json, sys, time
from pathlib import Path
from numba.core import event
from planar_tui import warmup
from planar_tui.runtime import prepare_kernels

stack, rows = [], []

class Listener(event.Listener):
    def on_start(self, ev):
        stack.append([time.process_time(), 0.0])

    def on_end(self, ev):
        started_s, inner_s = stack.pop()
        spent_s = time.process_time() - started_s
        if stack:
            stack[-1][1] += spent_s
        name = getattr(ev.data.get("dispatcher"), "__name__", "?")
        rows.append([name, str(ev.data.get("args")), spent_s - inner_s])

prepare_kernels()
warmup.marker = lambda unit: prepare_kernels() / "never-warm"
with event.install_listener("numba:compile", Listener()):
    warmup._run_example(sys.argv[1])
Path(sys.argv[2]).write_text(json.dumps(rows))
"""


def main() -> None:
    from planar_tui import warmup
    from planar_tui.registry import JOB_KINDS

    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("units", nargs="*", help="warm-up units (default: every one)")
    arguments = parser.parse_args()
    chosen = arguments.units or [u for kind in JOB_KINDS for u in warmup.units(kind)]
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    env["PLANAR_TUI_CACHE_DIR"] = ""
    print(f"{platform.machine()}, {os.cpu_count()} cores; 1-min load before {load():.2f}")
    with tempfile.TemporaryDirectory() as folder:
        for unit in chosen:
            cache = tempfile.mkdtemp(prefix="kernels-", dir=folder)
            out = Path(folder) / "rows.json"
            command = [sys.executable, "-c", TIMED_UNIT, unit, str(out)]
            wall_s, cpu_s = timed(command, dict(env, NUMBA_CACHE_DIR=cache))
            rows = json.loads(out.read_text()) if out.exists() else []
            own_s = sum(row[2] for row in rows if row[0] != "impl")
            print(
                f"\n{unit}: process {cpu_s:.1f} s CPU ({wall_s:.1f} s wall), "
                f"kernels {own_s:.1f} s, load {load():.2f}",
                flush=True,
            )
            for name, args, spent_s in sorted(rows, key=lambda row: -row[2]):
                if spent_s >= 0.2:
                    print(f"  {spent_s:6.2f}  {name}  {args[:110]}", flush=True)


if __name__ == "__main__":
    main()

"""Timing helpers shared by the workspace benchmarks (``bench_workspace.py`` and
``bench_workspace5r.py``, which import this module, never each other)."""

from __future__ import annotations

import statistics
import subprocess
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent


def load() -> str:
    """The 1, 5 and 15 minute load averages, recorded beside every figure."""
    return " ".join(Path("/proc/loadavg").read_text().split()[:3])


def wall(command, runs=3):
    """The median wall time (s) of ``runs`` runs of ``command`` in the repository."""
    times = []
    for _ in range(runs):
        started = time.perf_counter()
        subprocess.run(command, check=True, capture_output=True, cwd=REPO)
        times.append(time.perf_counter() - started)
    return statistics.median(times)

"""What a sweep run may ask for, checked before anything runs: worker processes, memory
and computing time (the limits of :mod:`planar_tui.limits`, as single jobs are held to).

* ``--workers``: at most :data:`WORKERS_PER_CORE` per usable core (more only queue for
  the cores and use memory), and the local cluster's memory, workers × (a worker's
  footprint :data:`WORKER_FOOTPRINT_BYTES` + the largest point's estimate), within the
  memory limit.
* Time: the points' estimated computing (a sample of points' estimates, by the job kind's
  ``estimate``, times the point count), shared among the workers, at most
  :data:`~planar_tui.limits.MAX_JOB_SECONDS` (one day). With ``--scheduler``, ``--workers``
  says how many workers the scheduler has (the machine's cores when not given).

Estimates are taken from :func:`estimate_indices` points (the first, the last and points
spread evenly), not from every point: a sweep of 100 000 points is checked in
milliseconds. They are rough, like the jobs' own (:mod:`planar_tui.limits`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from planar_tui.errors import PresetError
from planar_tui.limits import (
    MAX_JOB_SECONDS,
    duration_text,
    memory_limit_bytes,
    size_text,
)
from planar_tui.registry import JOB_KINDS
from planar_tui.sweep.execute import default_workers, scheduler_timeout_s
from planar_tui.sweep.points import Point
from planar_tui.sweep.spec import Sweep

#: Most local worker processes per usable core.
WORKERS_PER_CORE = 4
#: Memory planned for one local worker process with NumPy, Numba and the kernels loaded
#: (a generous round figure: issue 19 saw 116 starting workers take 6.1 GiB, 54 MiB
#: each, before any kernel was loaded).
WORKER_FOOTPRINT_BYTES = 300 * 2**20
#: Points whose estimates stand for the whole sweep.
ESTIMATE_POINTS = 64


def usable_cores() -> int:
    """The machine's cores available to this process."""
    return default_workers()


def check_workers(workers: int | None) -> None:
    """Refuse ``--workers`` below 1 or above :data:`WORKERS_PER_CORE` × the usable cores
    (:class:`PresetError`, exit code 2, one line)."""
    if workers is None:
        return
    most = WORKERS_PER_CORE * usable_cores()
    if workers < 1:
        problem = f"is {workers}, below 1"
    elif workers > most:
        shown = f"{workers:,}" if workers < 10**12 else f"{workers:.3g}"
        problem = f"is {shown}, more than {WORKERS_PER_CORE} per usable core ({usable_cores()})"
    else:
        return
    raise PresetError(
        "command line",
        "--workers",
        problem,
        f"an integer from 1 to {most} (1 runs the points in this process)",
    )


@dataclass(frozen=True)
class SweepEstimate:
    """A sweep's rough needs: the largest point's ``memory_bytes`` and all points'
    ``seconds`` of computing (``None`` where the job kind gives no estimate)."""

    memory_bytes: float
    seconds: float


def estimate_indices(count: int) -> list[int]:
    """The 0-based points whose estimates stand for the sweep: evenly spread, the first
    and last included."""
    spread = min(count, ESTIMATE_POINTS)
    return sorted({round(k * (count - 1) / max(1, spread - 1)) for k in range(spread)})


def estimate_sweep(sweep: Sweep, points: Sequence[Point]) -> SweepEstimate | None:
    """The sweep's needs from its sample points' estimates (mean seconds × count, largest
    memory), or ``None`` when its job kind gives none. A sample point that cannot be made
    is skipped (its run fails alone)."""
    estimate = JOB_KINDS[sweep.job.kind].estimate
    if estimate is None or not len(points):
        return None
    figures = []
    for index in estimate_indices(len(points)):
        try:
            figures.append(estimate(points[index].job))
        except PresetError:
            continue
    if not figures:
        return None
    memory = max(m for m, _ in figures)
    seconds = sum(s for _, s in figures) / len(figures) * len(points)
    return SweepEstimate(memory, seconds)


def check_sweep_budget(
    prepared: Sequence[tuple[Sweep, Sequence[Point]]], workers: int | None, scheduler: str | None
) -> None:
    """Refuse, before anything runs, sweeps whose workers or points exceed the limits
    (:class:`PresetError`, exit code 2, one line with the estimate)."""
    check_workers(workers)
    if scheduler is not None:
        scheduler_timeout_s()  # a bad PLANAR_TUI_SCHEDULER_TIMEOUT_S refused now
    for sweep, points in prepared:
        check_needs(
            sweep.preset_path,
            sweep.name,
            sweep.label,
            f"{len(points):,} points",
            estimate_sweep(sweep, points),
            workers,
            scheduler,
        )


def check_needs(
    preset_path: Path | str,
    name: str,
    label: str,
    counted: str,
    found: SweepEstimate | None,
    workers: int | None,
    scheduler: str | None,
) -> None:
    """Refuse a study (a sweep, an optimisation) whose local workers' memory (workers ×
    (:data:`WORKER_FOOTPRINT_BYTES` + the largest evaluation's memory)) exceeds the memory
    limit, or whose computing ``found.seconds`` shared among the workers exceeds
    :data:`~planar_tui.limits.MAX_JOB_SECONDS` (:class:`PresetError`, one line naming
    ``counted``, e.g. ``"1,000 points"``, and the estimate)."""
    count = workers or usable_cores()
    local = scheduler is None and count > 1
    point_memory = 0.0 if found is None else found.memory_bytes
    if local:
        needed = count * (WORKER_FOOTPRINT_BYTES + point_memory)
        if needed > memory_limit_bytes():
            raise PresetError(
                "command line",
                "--workers",
                f"{count} local workers for {label} need about {size_text(needed)} "
                f"of memory (limit {size_text(memory_limit_bytes())})",
                "fewer workers",
            )
    if found is None:
        return
    wall = found.seconds / count
    if wall > MAX_JOB_SECONDS:
        raise PresetError(
            preset_path,
            name,
            f"{counted} need about {duration_text(found.seconds)} of "
            f"computing, about {duration_text(wall)} on {count} worker(s) (limit 1 day)",
            "fewer points, shorter points or more workers",
        )

"""What one job may ask for: memory and computing time, estimated when a preset is
validated so that a job that cannot run is refused (exit code 2, with the estimate)
instead of failing after minutes or exhausting the machine.

* Memory: half the physical memory (``os.sysconf``), or :data:`FALLBACK_MEMORY_BYTES`
  where the system does not say.
* Time: :data:`MAX_JOB_SECONDS` (one day) of estimated computing.

Estimates are deliberately rough (within a few times the truth): they exist to refuse
what cannot finish, not to predict a run's duration.
"""

from __future__ import annotations

import functools
import os

#: Share of the physical memory one job may plan to use.
MEMORY_FRACTION = 0.5
#: The memory limit where the physical memory cannot be read.
FALLBACK_MEMORY_BYTES = 8 * 2**30
#: Longest estimated computing time of one job (seconds): one day.
MAX_JOB_SECONDS = 86_400.0


@functools.cache
def memory_limit_bytes() -> int:
    """Most memory one job may plan to use: :data:`MEMORY_FRACTION` of the physical memory."""
    try:
        physical = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (AttributeError, OSError, ValueError):
        return FALLBACK_MEMORY_BYTES
    return int(physical * MEMORY_FRACTION) if physical > 0 else FALLBACK_MEMORY_BYTES


def size_text(n_bytes: float) -> str:
    """``48 GiB``, ``512 MiB``: a size for messages (three significant digits)."""
    for unit, scale in (("TiB", 2**40), ("GiB", 2**30), ("MiB", 2**20)):
        if n_bytes >= scale:
            return f"{n_bytes / scale:.3g} {unit}"
    return f"{n_bytes / 2**10:.3g} KiB"


def duration_text(seconds: float) -> str:
    """``3.2 days``, ``5 hours``: a duration for messages."""
    for unit, scale in (("years", 365.25 * 86_400), ("days", 86_400), ("hours", 3_600)):
        if seconds >= scale:
            return f"{seconds / scale:.3g} {unit}"
    return f"{seconds:.3g} s"


def memory_problem(n_bytes: float) -> str | None:
    """``needs about 48 GiB of memory (limit 8 GiB)`` when over the limit, else ``None``."""
    limit = memory_limit_bytes()
    if n_bytes <= limit:
        return None
    return f"needs about {size_text(n_bytes)} of memory (limit {size_text(limit)})"


def time_problem(seconds: float) -> str | None:
    """``needs about 3 days of computing (limit 1 day)`` when over the limit, else ``None``."""
    if seconds <= MAX_JOB_SECONDS:
        return None
    return f"needs about {duration_text(seconds)} of computing (limit 1 day)"

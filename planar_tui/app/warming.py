"""The app's background warm-up: the kernels of every job kind not cached yet, compiled in
a worker thread at start (:func:`warm_in_background`), so a later first F5 starts at once.

A new user's first job must not wait behind other kinds' kernels (168 s at ``0% 0/2`` while
kinds the preset does not use compiled): the preset's own kinds are warmed
first, the current tab's kind first of all (:func:`warm_order`), one warm-up unit at a
time, and no unit is started while a job runs (the job compiles its own kernels, in its
own stage :data:`planar_tui.warmup.STAGE`; Numba compiles one function at a time, so a
background unit compiling alongside would only slow it down). A unit already compiling
cannot be interrupted (it finishes in the background; the job waits for it at most).
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from typing import Any

from planar_tui import warmup
from planar_tui.errors import Cancelled
from planar_tui.progress import Progress
from planar_tui.registry import JOB_KINDS
from planar_tui.runtime import prepare_kernels

#: Seconds between two looks at whether the job that paused the warm-up has ended.
PAUSE_POLL_S = 0.05


def warm_order(units: Sequence[str], first_kinds: Sequence[str]) -> list[str]:
    """``units`` (``kind`` or ``kind:part``) with those of ``first_kinds`` first, in that
    order, the others after in their own order."""
    rank = {kind: k for k, kind in enumerate(first_kinds)}
    return sorted(units, key=lambda unit: rank.get(unit.partition(":")[0], len(rank)))


def warm_in_background(
    notify: Callable[[str], None],
    first_kinds: Sequence[str],
    job_running: Callable[[], bool],
    cancelled: Callable[[], bool],
) -> None:
    """Compile the kernels not cached yet (:func:`planar_tui.warmup.warm_kernels`), unit
    by unit in :func:`warm_order` of ``first_kinds``, waiting while ``job_running()``;
    ``notify`` says so at the start and at the end; returns within 0.05 s of
    ``cancelled()``."""
    prepare_kernels()
    todo = warmup.missing(JOB_KINDS)
    if not todo:
        return
    todo = warm_order(todo, first_kinds)
    kinds = dict.fromkeys(unit.partition(":")[0] for unit in todo)
    notify(f"Compiling the kernels of {', '.join(kinds)} in the background (first run only).")
    try:
        for unit in todo:
            while job_running():  # the job's own kernels first
                if cancelled():
                    return
                time.sleep(PAUSE_POLL_S)
            warmup.warm_kernels([unit], Progress(should_stop=cancelled))
    except Cancelled:
        return
    notify("Kernels compiled: jobs start at once.")


def preset_kinds(app: Any) -> list[str]:
    """The job kinds of ``app``'s preset, the current tab's first (then in tab order)."""
    current = getattr(app.current_pane(), "kind", None)
    kinds = [name for _, name in app.tabs() if name != "robot" and app.workbench.has(name)]
    return sorted(kinds, key=lambda kind: kind != current)

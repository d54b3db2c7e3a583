"""Which warm-up process compiles which warm-up unit: :func:`schedule`.

``planar-tui warmup`` compiles every kind's kernels in as many processes as cores
(:func:`planar_tui.warmup.warm_kernels_in_processes`). On 2 cores its wall time is at
least the larger of the longest process's CPU time and half the total, so the units
(``kind`` or ``kind:part``, :func:`planar_tui.warmup.units`) are shared out by their known
costs, longest first, and units whose kernels overlap run in one process, where the shared
kernels compile once.
"""

from __future__ import annotations

from collections.abc import Iterable

#: Estimated CPU seconds of each warm-up unit's example compiling into an empty kernel cache
#: (a unit that :data:`SHARES` kernels: its remainder after that unit), from
#: ``benchmarks/bench_kernels.py`` (each unit alone in a fresh process, per-kernel compile
#: times; docs/performance.md, "Cold start"): relative costs for :func:`schedule`, not
#: promises. A unit not listed counts :data:`DEFAULT_COST_S`.
UNIT_COST_S: dict[str, float] = {
    "motion_uncertainty:fused": 45.5,  # the fused 6-link step 22.5 s (load 9.3)
    "motion_uncertainty:general": 6.4,  # 21.6 alone, less the lane kernels (12.7), a start
    "workspace:legwise": 23.7,
    "workspace5r": 22.0,
    "path3rrr": 20.7,
    "path5r": 16.7,
    "workspace:joint": 16.5,  # 22.5 alone, less the interval forms (legwise)
    "path3prr": 15.2,
    "path3rpr": 13.9,
    "workspace:accuracy": 14.0,  # 19.4 alone, less the arc-distance parts and a start
    "workspace:dexterity": 12.8,  # after arc-distance
    "sensitivity": 5.2,  # 15.1 alone, less the estimators (7.4) and a start
    "workspace3prr": 9.9,
    "path3rrr_sensitivity": 9.5,  # after path3rrr
    "path5r_sensitivity": 9.1,  # after path5r
    "workspace:interference": 9.0,  # not measured alone: as the other arc-distance parts
    "path3rpr_sensitivity": 9.0,  # not measured alone: as the other path sensitivities
    "path3prr_sensitivity": 9.0,
    "workspace:orientation": 8.6,
    "workspace:arc-distance": 7.4,
    "workspace3rpr": 7.4,
    "workspace:singularities": 7.2,  # after arc-distance
    "simulate": 6.4,
    "torques": 3.4,
}
DEFAULT_COST_S = 10.0
#: Units whose example compiles many of another unit's kernels (measured: the kernels both
#: compile when alone): the key runs after the value in the same process, where those
#: kernels are compiled once (two processes side by side would both compile them).
SHARES: dict[str, str] = {
    "motion_uncertainty:general": "motion_uncertainty:fused",  # the general lane kernels
    "sensitivity": "motion_uncertainty:general",  # the Sobol'/eFAST estimators
    "workspace:joint": "workspace:legwise",  # the interval forms, the refinement
    "workspace:singularities": "workspace:arc-distance",  # their jobs' arc-distance form
    "workspace:dexterity": "workspace:arc-distance",
    "workspace:interference": "workspace:arc-distance",
    "workspace:accuracy": "workspace:arc-distance",
    "path3rrr_sensitivity": "path3rrr",  # the path and its efforts
    "path5r_sensitivity": "path5r",
    "path3rpr_sensitivity": "path3rpr",
    "path3prr_sensitivity": "path3prr",
}


def chains(todo: Iterable[str]) -> list[list[str]]:
    """``todo``'s units in groups that run in one process, in order: each unit after the
    unit it :data:`SHARES` kernels with (when that one is in ``todo`` too), so that every
    shared kernel is compiled once."""
    todo = list(dict.fromkeys(todo))
    groups: dict[str, list[str]] = {}

    def root(unit: str) -> str:
        while unit in SHARES and SHARES[unit] in todo:
            unit = SHARES[unit]
        return unit

    for unit in sorted(todo, key=depth):
        groups.setdefault(root(unit), []).append(unit)
    return list(groups.values())


def depth(unit: str) -> int:
    """How many :data:`SHARES` links lead from ``unit`` to a unit sharing nothing."""
    count = 0
    while unit in SHARES:
        unit, count = SHARES[unit], count + 1
    return count


def cost_s(units_: Iterable[str]) -> float:
    """The estimated compile CPU seconds of ``units_`` run in one process (:data:`UNIT_COST_S`)."""
    return sum(UNIT_COST_S.get(unit, DEFAULT_COST_S) for unit in units_)


def schedule(todo: Iterable[str], processes: int) -> list[list[str]]:
    """The units of ``todo`` shared among at most ``processes`` warm-up processes, as each
    process runs them: longest processing time first (:func:`chains` sorted by
    :func:`cost_s`, longest first, each given to the process with the least estimated work so
    far), so the processes finish close together; a process's chains longest first. No empty
    process. With costs c and p processes the longest process is within
    ``max(c) + sum(c) / p`` of the ideal (Graham's bound for list scheduling)."""
    groups = sorted(chains(todo), key=cost_s, reverse=True)
    bins: list[list[str]] = [[] for _ in range(max(1, min(processes, len(groups))))]
    for group in groups:
        min(bins, key=cost_s).extend(group)
    return [units_ for units_ in bins if units_]

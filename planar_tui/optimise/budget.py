"""What an optimisation will ask for, estimated and checked before anything runs, as a
sweep's is (:mod:`planar_tui.sweep.budget`).

Its evaluations are ``budget`` designs at the coarse settings, then the certified re-run
of the optimum at the job's own settings: one design for one objective, a Pareto set for
several (estimated at ``min(budget, population)`` designs: NSGA-II keeps a front about a
generation wide). A design's needs are the job kind's ``estimate`` at the designs
:func:`~planar_tui.optimise.spec.corner_designs` names (the variables' lower ends, upper
ends and middles), the mean for time and the largest for memory:

    seconds ≈ budget · mean(coarse) + reruns · mean(own), memory = max over both.
"""

from __future__ import annotations

from collections.abc import Sequence

from planar_tui.errors import PresetError
from planar_tui.optimise.problem import Optimisation
from planar_tui.optimise.spec import corner_designs
from planar_tui.registry import JOB_KINDS
from planar_tui.sweep.budget import SweepEstimate, check_needs, check_workers
from planar_tui.sweep.points import make_point


def reruns(opt: Optimisation) -> int:
    """Designs of the certified re-run (estimated)."""
    return 1 if len(opt.objectives) == 1 else min(opt.budget, opt.population)


def estimate_optimisation(opt: Optimisation) -> SweepEstimate | None:
    """The optimisation's rough needs (module docstring), or ``None`` when its job kind
    gives no estimate."""
    estimate = JOB_KINDS[opt.job.kind].estimate
    if estimate is None:
        return None
    seconds = 0.0
    memory = 0.0
    for coarse, count in ((True, opt.budget), (False, reruns(opt))):
        sweep = opt.sweep(coarse)
        figures = []
        for number, values in enumerate(corner_designs(opt), start=1):
            try:
                point = make_point(sweep, number, opt.point_values(values, coarse))
                figures.append(estimate(point.job))
            except PresetError:  # refused by the table's own checks already
                continue
        if not figures:
            return None
        memory = max(memory, *(m for m, _ in figures))
        seconds += count * sum(s for _, s in figures) / len(figures)
    return SweepEstimate(memory, seconds)


def check_optimise_budget(
    optimisations: Sequence[Optimisation], workers: int | None, scheduler: str | None
) -> None:
    """Refuse, before anything runs, optimisations whose workers' memory or computing time
    exceed the limits (:func:`planar_tui.sweep.budget.check_needs`: one line, exit 2)."""
    check_workers(workers)
    for opt in optimisations:
        counted = f"{opt.budget:,} evaluations and {reruns(opt):,} certified re-run(s)"
        found = estimate_optimisation(opt)
        check_needs(opt.preset_path, opt.name, opt.label, counted, found, workers, scheduler)

"""The columns a sensitivity job's sweep row (or optimisation evaluation) reports, named
without running it (``JobKind.figure_names``: a resumed sweep checks its checkpoint
against them; an optimisation refuses a column not among them)."""

from __future__ import annotations

from typing import Any

from planar_tui.jobkind import Job


def figure_names(job: Job[Any, Any]) -> tuple[str, ...]:
    """The columns :func:`planar_tui.sensitivity.job.point_figures` reports for ``job``."""
    groups = (
        "dominant",
        "dominant_percent",
        "lengths_percent",
        "masses_percent",
        "sobol_halfwidth_max",
        "variance_Nm2",
    )
    names: list[str] = []
    for k in range(1, len(job.spec.speeds_rad_s) + 1):
        suffix = "" if k == 1 else f"_w{k}"
        names += [
            f"tau{i}_{group}{suffix}" for i in range(1, job.robot.n_links + 1) for group in groups
        ]
        names.append(f"tau_variance_max_Nm2{suffix}")
    return tuple(names)

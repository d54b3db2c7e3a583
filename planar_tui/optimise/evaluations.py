"""An optimisation's record: its evaluations (design, generation, outcome) and the
certified re-runs, what they mean to pymoo (``F = sense · value``, feasibility under the
constraints), the optimum or Pareto set, the convergence, the CSV tables and the figure's
data. :mod:`planar_tui.optimise.run` fills it."""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from planar_tui.csvio import CsvTable
from planar_tui.errors import PresetError
from planar_tui.optimise.problem import Optimisation
from planar_tui.sweep.worker import FAILED, INFEASIBLE, OK, PointOutcome


@dataclass(frozen=True)
class Evaluation:
    """Evaluation ``number`` (1-based, in the order asked) of ``generation``: the design's
    ``values`` (one per variable) and its outcome."""

    number: int
    generation: int
    values: tuple[Any, ...]
    outcome: PointOutcome


@dataclass
class OptimiseRun:
    """The evaluations so far (``resumed`` of them from the checkpoint), the certified
    re-runs of the optimum or Pareto set (evaluation, outcome at the job's own settings)
    and where the files went. A ``cancelled`` run (stopped part-way) keeps every finished
    evaluation, those of its last generation included."""

    optimisation: Optimisation
    evaluations: list[Evaluation] = field(default_factory=list)
    certified: list[tuple[Evaluation, PointOutcome]] = field(default_factory=list)
    resumed: int = 0
    generations: int = 0
    output: Path | None = None
    pareto: Path | None = None
    figure: Path | None = None
    figure_error: str | None = None
    checkpoint: Path | None = None
    cancelled: bool = False
    #: When the run started (epoch s), for the CSVs' provenance sidecars.
    started_s: float = field(default_factory=time.time)

    @property
    def failed(self) -> int:
        """Evaluations whose job broke (status ``failed``)."""
        return sum(1 for e in self.evaluations if e.outcome.status == FAILED)

    @property
    def infeasible(self) -> int:
        """Evaluations whose design the job refuses (status ``infeasible``: a centre its
        working mode cannot reach)."""
        return sum(1 for e in self.evaluations if e.outcome.status == INFEASIBLE)

    @property
    def table(self) -> CsvTable:
        """Every evaluation: number, generation, variables, the objectives' and
        constraints' columns, ``feasible``, ``status``, ``message``."""
        opt = self.optimisation
        header = (
            "evaluation",
            "generation",
            *(v.path.text for v in opt.variables),
            *opt.columns,
            "feasible",
            "status",
            "message",
        )
        rows = []
        for e in self.evaluations:
            figures = [e.outcome.figures.get(c, "") for c in opt.columns]
            rows.append(
                [
                    e.number,
                    e.generation,
                    *e.values,
                    *figures,
                    str(feasible(opt, e.outcome)).lower(),
                    e.outcome.status,
                    e.outcome.message,
                ]
            )
        return CsvTable(header, rows)

    def best(self) -> list[Evaluation]:
        """The optimum (one objective: the feasible evaluation of least ``F``, the first
        one on a tie) or the Pareto set (several: the feasible evaluations no other
        dominates, one per distinct design), in evaluation order."""
        return best_of(self.optimisation, self.evaluations)

    @property
    def optimum_table(self) -> CsvTable:
        """The certified optimum or Pareto set: evaluation, variables, the objectives as
        evaluated (``coarse_COLUMN``), then every column of the job's summary at its own
        settings (the certified bracket among them), ``status``, ``message``."""
        opt = self.optimisation
        columns: dict[str, None] = {}
        for _, outcome in self.certified:
            columns.update(dict.fromkeys(outcome.figures))
        names = [n for n in columns if n not in {v.path.text for v in opt.variables}]
        header = (
            "evaluation",
            *(v.path.text for v in opt.variables),
            *(f"coarse_{o.column}" for o in opt.objectives),
            *names,
            "status",
            "message",
        )
        rows = [
            [
                e.number,
                *e.values,
                *(e.outcome.figures[o.column] for o in opt.objectives),
                *(outcome.figures.get(n, "") for n in names),
                outcome.status,
                outcome.message,
            ]
            for e, outcome in self.certified
        ]
        return CsvTable(header, rows)


def number_of(opt: Optimisation, outcome: PointOutcome, column: str) -> float:
    """An evaluation's figure ``column`` as a float; a column the job does not report, or
    one that is no number, is a :class:`PresetError` naming the table (exit 2)."""
    value = outcome.figures.get(column)
    if value is None:
        raise PresetError(
            opt.preset_path,
            opt.name,
            f"names the column {column!r}, not one of the job's",
            "one of " + ", ".join(outcome.figures),
        )
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise PresetError(
            opt.preset_path,
            opt.name,
            f"names the column {column!r}, which is not a number ({value!r})",
            "a numeric column",
        )
    return float(value)


def feasible(opt: Optimisation, outcome: PointOutcome) -> bool:
    """Whether an evaluation succeeded and holds every constraint (its own operator)."""
    return outcome.status == OK and all(
        c.holds(number_of(opt, outcome, c.column)) for c in opt.constraints
    )


def objectives_of(opt: Optimisation, outcome: PointOutcome) -> tuple[float, ...]:
    """pymoo's ``F``: ``sense · value`` per objective."""
    return tuple(o.sense * number_of(opt, outcome, o.column) for o in opt.objectives)


def best_of(opt: Optimisation, evaluations: Sequence[Evaluation]) -> list[Evaluation]:
    """See :meth:`OptimiseRun.best`. ``a`` dominates ``b`` when ``F(a) ≤ F(b)`` in every
    objective and ``<`` in one."""
    candidates: dict[str, Evaluation] = {}
    for e in evaluations:
        if feasible(opt, e.outcome):
            candidates.setdefault(repr(e.values), e)  # choices may be lists
    scored = [(objectives_of(opt, e.outcome), e) for e in candidates.values()]
    if len(opt.objectives) == 1:
        return [min(scored, key=lambda s: (s[0], s[1].number))[1]] if scored else []

    def dominates(a: tuple[float, ...], b: tuple[float, ...]) -> bool:
        return all(x <= y for x, y in zip(a, b, strict=True)) and a != b

    front = [e for f, e in scored if not any(dominates(g, f) for g, _ in scored)]
    return sorted(front, key=lambda e: e.number)


def convergence(opt: Optimisation, evaluations: Sequence[Evaluation]) -> list[float]:
    """The best objective value (as the column's value) after each evaluation, ``nan``
    before the first feasible one (one objective)."""
    best, sense, history = math.inf, opt.objectives[0].sense, []
    for e in evaluations:
        if feasible(opt, e.outcome):
            best = min(best, sense * number_of(opt, e.outcome, opt.objectives[0].column))
        history.append(sense * best if math.isfinite(best) else math.nan)
    return history


def figure_data(run: OptimiseRun) -> dict[str, Any]:
    """What the figure draws: the objectives' names, every feasible evaluation's
    objective values, the best-so-far (one objective) and the optimum or front."""
    opt = run.optimisation
    ok = [e for e in run.evaluations if feasible(opt, e.outcome)]
    names = [o.column for o in opt.objectives]

    def values(evaluations: Sequence[Evaluation]) -> list[list[float]]:
        return [[number_of(opt, e.outcome, n) for n in names] for e in evaluations]

    return {
        "title": opt.label,
        "names": names,
        "numbers": [e.number for e in ok],
        "points": values(ok),
        "best": values(run.best()),
        "history": convergence(opt, run.evaluations) if len(names) == 1 else [],
    }

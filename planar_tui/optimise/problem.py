"""One optimisation, checked: its variables (how the optimiser's reals decode to TOML
values), its objectives and constraints (pymoo's signs), and the sweep whose points are its
evaluations. :mod:`planar_tui.optimise.spec` reads it from a preset's ``[[optimise]]``
table."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from planar_tui.jobkind import Job
from planar_tui.optimise import TABLE
from planar_tui.sweep.paths import KeyPath
from planar_tui.sweep.spec import Sweep, study_fingerprint


@dataclass(frozen=True)
class Variable:
    """One varied key path: a number in ``[low, high]``, an integer in it, or one of
    ``choices``. The optimiser sees every variable as a real ``x``: a number is ``x``
    itself, an integer ``round(x)`` with ``x ∈ [low − ½, high + ½]`` and a choice the
    ``round(x)``-th with ``x ∈ [−½, n − ½]``, clipped at the ends. ``fixed_sum``: key paths
    that take ``total −`` the sum of the (number or integer) variables naming them."""

    path: KeyPath
    low: float = 0.0
    high: float = 0.0
    integer: bool = False
    choices: tuple[Any, ...] | None = None
    fixed_sum: tuple[tuple[KeyPath, float], ...] = ()

    @property
    def bounds(self) -> tuple[float, float]:
        """The optimiser's real interval."""
        if self.choices is not None:
            return -0.5, len(self.choices) - 0.5
        if self.integer:
            return self.low - 0.5, self.high + 0.5
        return self.low, self.high

    def decode(self, x: float) -> Any:
        """The TOML value of the optimiser's ``x``."""
        if self.choices is not None:
            return self.choices[min(len(self.choices) - 1, max(0, round(x)))]
        if self.integer:
            return int(min(self.high, max(self.low, round(x))))
        return float(min(self.high, max(self.low, x)))


@dataclass(frozen=True)
class Objective:
    """A column to maximise (``sense`` −1: pymoo minimises ``−value``) or minimise (+1)."""

    column: str
    sense: int

    @property
    def verb(self) -> str:
        return "maximise" if self.sense < 0 else "minimise"


@dataclass(frozen=True)
class Constraint:
    """``column OP bound`` as pymoo's ``G ≤ 0``: ``bound − value`` for ``>=``/``>``,
    ``value − bound`` for ``<=``/``<``; :meth:`holds` applies the operator itself."""

    text: str
    column: str
    operator: str
    bound: float

    def g(self, value: float) -> float:
        return self.bound - value if self.operator[0] == ">" else value - self.bound

    def holds(self, value: float) -> bool:
        return {
            ">=": value >= self.bound,
            "<=": value <= self.bound,
            ">": value > self.bound,
            "<": value < self.bound,
        }[self.operator]


@dataclass(frozen=True)
class Optimisation:
    """One optimisation, checked: the job and its raw tables (as a sweep's), the variables,
    objectives and constraints, the coarse settings (key path → value) of its evaluations,
    the optimiser's settings and the files (relative to the output folder)."""

    preset_path: Path
    name: str
    job: Job
    document: Mapping[str, Any]
    tables: Mapping[str, Mapping[str, Any]]
    defaults: Mapping[str, Mapping[str, Any]]
    variables: tuple[Variable, ...]
    objectives: tuple[Objective, ...]
    constraints: tuple[Constraint, ...] = ()
    coarse: tuple[tuple[KeyPath, Any], ...] = ()
    algorithm: str = "auto"
    population: int = 20
    budget: int = 200
    seed: int = 1
    output: str = ""
    pareto_output: str = ""
    plot: str | None = None
    source: Mapping[str, Any] = field(default_factory=dict)

    @property
    def label(self) -> str:
        """``PRESET:optimise[1]`` for progress bars and summaries."""
        return f"{self.preset_path.stem}:{self.name}"

    @property
    def columns(self) -> tuple[str, ...]:
        """The summary columns an evaluation must report (objectives, then constraints)."""
        names = [o.column for o in self.objectives] + [c.column for c in self.constraints]
        return tuple(dict.fromkeys(names))

    def sweep(self, coarse: bool) -> Sweep:
        """The sweep whose points are the evaluations (the variables, then with ``coarse``
        the coarse settings): :func:`planar_tui.sweep.points.point_job` makes their jobs."""
        paths = [v.path for v in self.variables] + [p for p, _, _ in self.sums]
        paths += [p for p, _ in self.coarse if coarse]
        return Sweep(
            preset_path=self.preset_path,
            name=self.name,
            job=self.job,
            document=self.document,
            tables=self.tables,
            defaults=self.defaults,
            values=tuple((path, (None,)) for path in paths),
        )

    def point_values(self, values: tuple[Any, ...], coarse: bool) -> tuple[Any, ...]:
        """A design's values for :meth:`sweep`'s points: the variables', the fixed sums'
        (``total − Σ values``), then with ``coarse`` the coarse settings."""
        sums = [total - sum(values[k] for k in which) for _, total, which in self.sums]
        return (*values, *sums, *(value for _, value in self.coarse if coarse))

    @property
    def sums(self) -> tuple[tuple[KeyPath, float, tuple[int, ...]], ...]:
        """Each fixed sum: its key path, its total and the variables (0-based) it
        subtracts."""
        found: dict[tuple, tuple[KeyPath, float, list[int]]] = {}
        for k, variable in enumerate(self.variables):
            for path, total in variable.fixed_sum:
                found.setdefault((path.table, path.key, path.indices), (path, total, []))[2].append(
                    k
                )
        return tuple((path, total, tuple(which)) for path, total, which in found.values())

    def fingerprint(self) -> str:
        """A SHA-256 of what an evaluation depends on (job and robot tables, the table but
        its ``plot``, planar-tui's version): a checkpoint of another is never resumed."""
        return study_fingerprint(self.job, self.tables, TABLE, self.source)

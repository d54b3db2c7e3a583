"""A sweep's points: the design (grid, zip or a random sample), made lazily, point by
point, and a sample of them validated as preset jobs before anything runs.

Grid points run through the lists like nested loops, the first key slowest; zip takes the
i-th value of every list; a sample draws ``count`` points in the unit cube (scipy's
scrambled Sobol' or Latin hypercube, or NumPy's uniform generator, all seeded) scaled to
the ranges, ``low + u·(high − low)``.

:func:`make_points` returns a :class:`SweepPoints`, a sequence that makes each point (its
values, its job parsed and checked) when asked: a sweep of 100 000 points starts at once
instead of parsing every point first. Before anything runs it checks a sample of points
(:func:`check_indices`: the first and last, points spread evenly over the design and, for
a grid, every value of every list at least once); a point outside that sample that turns
out invalid when it is made fails alone (its row says why).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from planar_tui.errors import PresetError
from planar_tui.jobkind import Job
from planar_tui.presets import parse_job
from planar_tui.registry import JOB_KINDS
from planar_tui.schema import shown
from planar_tui.sweep.paths import apply_values
from planar_tui.sweep.spec import Sample, Sweep


@dataclass(frozen=True)
class Point:
    """One point: its 1-based ``number``, its ``values`` (one per varied key path, in
    column order) and the job it runs (parsed and checked like a preset's)."""

    number: int
    values: tuple[Any, ...]
    job: Job


def unit_sample(sample: Sample, dimensions: int) -> Any:
    """``count`` points in ``[0, 1)^dimensions`` by the sample's method and seed (a
    ``(count, dimensions)`` NumPy array)."""
    import numpy as np

    if sample.method == "uniform":
        return np.random.default_rng(sample.seed).random((sample.count, dimensions))
    from scipy.stats import qmc

    engine = qmc.Sobol if sample.method == "sobol" else qmc.LatinHypercube
    options = {"scramble": True} if sample.method == "sobol" else {}
    try:
        sampler = engine(dimensions, rng=np.random.default_rng(sample.seed), **options)
    except TypeError:  # scipy < 1.15 names it seed
        sampler = engine(dimensions, seed=np.random.default_rng(sample.seed), **options)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # Sobol' balance warning for counts not 2^k
        return sampler.random(sample.count)


#: Points spread evenly over the design that :func:`check_indices` includes.
SPREAD_CHECKS = 64
#: Most points :func:`check_indices` names (a grid's every value included while it fits).
MAX_CHECKS = 500


class SweepPoints(Sequence[Point]):
    """A sweep's points in point order, each made (values, job parsed and checked) when
    asked for; :meth:`values` gives a point's values alone (cheap)."""

    def __init__(self, sweep: Sweep):
        self.sweep = sweep
        self._count = sweep.point_count
        self._lists = [values for _, values in sweep.values]
        self._unit: Any = None

    def __len__(self) -> int:
        return self._count

    def values(self, index: int) -> tuple[Any, ...]:
        """The values of the point at 0-based ``index`` (grid: the first key slowest)."""
        sweep = self.sweep
        if sweep.sample is not None:
            if self._unit is None:
                self._unit = unit_sample(sweep.sample, len(sweep.ranges))
            row = self._unit[index]
            return tuple(
                low + float(u) * (high - low)
                for u, (_, low, high) in zip(row, sweep.ranges, strict=True)
            )
        if sweep.combine == "zip":
            return tuple(values[index] for values in self._lists)
        picked = []
        for values in reversed(self._lists):
            index, k = divmod(index, len(values))
            picked.append(values[k])
        return tuple(reversed(picked))

    def __getitem__(self, index):  # type: ignore[override]
        if isinstance(index, slice):
            return [self[i] for i in range(*index.indices(self._count))]
        if index < 0:
            index += self._count
        if not 0 <= index < self._count:
            raise IndexError(index)
        return make_point(self.sweep, index + 1, self.values(index))

    def __iter__(self) -> Iterator[Point]:
        for index in range(self._count):
            yield self[index]

    def all_values(self) -> Iterator[tuple[Any, ...]]:
        """Every point's values, in point order."""
        for index in range(self._count):
            yield self.values(index)


def design(sweep: Sweep) -> Iterator[tuple[Any, ...]]:
    """Every point's values, in point order."""
    return SweepPoints(sweep).all_values()


def values_text(sweep: Sweep, values: tuple[Any, ...]) -> str:
    """``orientation_deg = 10, robot3rrr.distal_cm = 25.0`` for messages."""
    return ", ".join(
        f"{path.text} = {shown(value)}" for path, value in zip(sweep.paths, values, strict=True)
    )


def point_job(sweep: Sweep, values: tuple[Any, ...]) -> Job:
    """The job of one point: the values written into the job's and robot's TOML tables,
    which the preset loader then parses (every check of a preset applies). Raises the
    loader's :class:`PresetError`."""
    job = sweep.job
    robot_kind = JOB_KINDS[job.kind].robot_kind
    tables = apply_values(sweep.tables, sweep.defaults, list(zip(sweep.paths, values, strict=True)))
    table, robot = tables[""], tables[robot_kind]
    original = sweep.document[job.kind]
    entry = original[job.index - 1] if isinstance(original, list) else original
    own_robot = isinstance(entry.get(robot_kind), Mapping)
    document: dict[str, Any] = {}
    if own_robot:
        table[robot_kind] = robot
    else:
        document[robot_kind] = robot
    if isinstance(original, list):
        document[job.kind] = [*original[: job.index - 1], table, *original[job.index :]]
    else:
        document[job.kind] = table
    return parse_job(sweep.preset_path, document, job.kind, job.index)


def make_point(sweep: Sweep, number: int, values: tuple[Any, ...]) -> Point:
    """Point ``number`` with ``values``, parsed like a preset job, then the job kind's
    ``check`` (e.g. a motion point's device usable here); an invalid point is a
    :class:`PresetError` naming the sweep, the point's values and the key."""
    check = JOB_KINDS[sweep.job.kind].check
    try:
        job = point_job(sweep, values)
        if check is not None:
            check(job)
    except PresetError as error:
        raise PresetError(
            sweep.preset_path,
            f"{sweep.name}: point {number} ({values_text(sweep, values)}): {error.key}",
            error.problem,
            error.expected,
        ) from None
    return Point(number, values, job)


def check_indices(sweep: Sweep) -> list[int]:
    """The 0-based points checked before anything runs: the first and the last,
    :data:`SPREAD_CHECKS` spread evenly and, for a grid, every value of every list (with
    the other keys at their first value) while at most :data:`MAX_CHECKS` points."""
    count = sweep.point_count
    chosen = dict.fromkeys([0, count - 1])
    spread = min(count, SPREAD_CHECKS)
    chosen.update(dict.fromkeys(round(k * (count - 1) / max(1, spread - 1)) for k in range(spread)))
    if sweep.sample is None:
        lengths = [len(values) for _, values in sweep.values]
        if sweep.combine == "zip":
            chosen.update(dict.fromkeys(range(min(count, MAX_CHECKS))))
        elif sum(lengths) <= MAX_CHECKS:
            for j, length in enumerate(lengths):
                stride = math.prod(lengths[j + 1 :])
                chosen.update(dict.fromkeys(k * stride for k in range(length)))
    return sorted(chosen)[:MAX_CHECKS]


def make_points(sweep: Sweep) -> SweepPoints:
    """The sweep's points (:class:`SweepPoints`, made lazily), a sample of them checked
    now (:func:`check_indices`): the first invalid one is a :class:`PresetError` naming
    the sweep, the point's values and the key, before anything runs."""
    points = SweepPoints(sweep)
    for index in check_indices(sweep):
        points[index]
    return points

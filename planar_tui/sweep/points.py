"""A sweep's points: the design (grid, zip or a random sample) and every point validated
as a preset job before anything runs.

Grid points run through the lists like nested loops, the first key slowest; zip takes the
i-th value of every list; a sample draws ``count`` points in the unit cube (scipy's
scrambled Sobol' or Latin hypercube, or NumPy's uniform generator, all seeded) scaled to
the ranges, ``low + u·(high − low)``.
"""

from __future__ import annotations

import itertools
import warnings
from collections.abc import Iterator, Mapping
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


def unit_sample(sample: Sample, dimensions: int) -> list[list[float]]:
    """``count`` points in ``[0, 1)^dimensions`` by the sample's method and seed."""
    import numpy as np

    if sample.method == "uniform":
        return np.random.default_rng(sample.seed).random((sample.count, dimensions)).tolist()
    from scipy.stats import qmc

    engine = qmc.Sobol if sample.method == "sobol" else qmc.LatinHypercube
    options = {"scramble": True} if sample.method == "sobol" else {}
    try:
        sampler = engine(dimensions, rng=np.random.default_rng(sample.seed), **options)
    except TypeError:  # scipy < 1.15 names it seed
        sampler = engine(dimensions, seed=np.random.default_rng(sample.seed), **options)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # Sobol' balance warning for counts not 2^k
        return sampler.random(sample.count).tolist()


def design(sweep: Sweep) -> Iterator[tuple[Any, ...]]:
    """Every point's values, in point order."""
    if sweep.sample is not None:
        for unit in unit_sample(sweep.sample, len(sweep.ranges)):
            yield tuple(low + u * (high - low) for u, (_, low, high) in zip(unit, sweep.ranges,
                                                                              strict=True))  # fmt: skip
        return
    lists = [values for _, values in sweep.values]
    yield from itertools.product(*lists) if sweep.combine == "grid" else zip(*lists, strict=True)


def values_text(sweep: Sweep, values: tuple[Any, ...]) -> str:
    """``orientation_deg = 10, robot3rrr.distal_cm = 25.0`` for messages."""
    return ", ".join(f"{path.text} = {shown(value)}" for path, value in
                     zip(sweep.paths, values, strict=True))  # fmt: skip


def point_job(sweep: Sweep, values: tuple[Any, ...]) -> Job:
    """The job of one point: the values written into the job's and robot's TOML tables,
    which the preset loader then parses (every check of a preset applies). Raises the
    loader's :class:`PresetError`."""
    job = sweep.job
    robot_kind = JOB_KINDS[job.kind].robot_kind
    tables = apply_values(sweep.tables, sweep.defaults,
                          list(zip(sweep.paths, values, strict=True)))  # fmt: skip
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


def make_points(sweep: Sweep) -> list[Point]:
    """Every point, validated before anything runs (:func:`make_point`): the first invalid
    point is a :class:`PresetError` naming the sweep, the point's values and the key."""
    return [make_point(sweep, number, values)
            for number, values in enumerate(design(sweep), start=1)]  # fmt: skip

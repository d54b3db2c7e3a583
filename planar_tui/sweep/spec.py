"""The ``[[sweep]]`` table of a preset, read and checked: which job, which key paths, which
values (lists, ``{from, to, count}`` ranges or a Sobol'/LHS/uniform sample), how they
combine, where the CSV goes.

A sweep is checked in two steps: :func:`parse_sweeps` (or :func:`build_sweep`, the same
checks for a sweep made by the app without a file) reads the table and counts the points
without making them; :func:`planar_tui.sweep.points.make_points` then builds and validates
every point like a preset job.
"""

from __future__ import annotations

import hashlib
import json
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from planar_tui import __version__
from planar_tui.errors import PresetError
from planar_tui.jobkind import Job
from planar_tui.presets import Preset
from planar_tui.registry import JOB_KINDS, ROBOT_KINDS
from planar_tui.schema import TableReader, figure_path, shown, suggest, type_name
from planar_tui.sweep import TABLE
from planar_tui.sweep.paths import (
    KeyPath,
    current_value,
    index_problem,
    overlap_problem,
    parse_key_path,
)

#: Most points a sweep may have unless its ``max_points`` says more.
DEFAULT_MAX_POINTS = 100_000
#: The largest ``max_points`` (a sweep's values and CSV rows are held in memory).
MAX_POINTS = 1_000_000
COMBINE = ("grid", "zip")
SAMPLE_METHODS = ("sobol", "lhs", "uniform")
SWEEP_KEYS = (
    "job",
    "values",
    "combine",
    "ranges",
    "sample",
    "output",
    "point_outputs",
    "plot",
    "max_points",
)


@dataclass(frozen=True)
class Sample:
    """A random design over ``ranges``: ``count`` points by ``method``, seeded."""

    method: str
    count: int
    seed: int


@dataclass(frozen=True)
class Sweep:
    """One sweep, checked: the base ``job`` (parsed), the raw TOML ``tables`` the points
    start from (``""``: the job's own table; the robot kind's name: the robot table it runs
    on) and their parsed values as TOML (``defaults``), the varied key paths with their
    values (``values``, combined by ``combine``) or ranges (``ranges`` sampled by
    ``sample``), the CSV ``output``, the optional ``point_outputs`` folder and ``plot``
    figure (all relative to the output folder), and ``source``, the sweep's table as
    written (for the fingerprint).
    """

    preset_path: Path
    name: str
    job: Job
    document: Mapping[str, Any]
    tables: Mapping[str, Mapping[str, Any]]
    defaults: Mapping[str, Mapping[str, Any]]
    values: tuple[tuple[KeyPath, tuple[Any, ...]], ...] = ()
    ranges: tuple[tuple[KeyPath, float, float], ...] = ()
    sample: Sample | None = None
    combine: str = "grid"
    output: str = ""
    point_outputs: str | None = None
    plot: str | None = None
    max_points: int = DEFAULT_MAX_POINTS
    source: Mapping[str, Any] = field(default_factory=dict)

    @property
    def label(self) -> str:
        """``PRESET:sweep[1]`` for progress bars and summaries."""
        return f"{self.preset_path.stem}:{self.name}"

    @property
    def paths(self) -> tuple[KeyPath, ...]:
        """The varied key paths, in column order."""
        if self.sample is not None:
            return tuple(path for path, _, _ in self.ranges)
        return tuple(path for path, _ in self.values)

    @property
    def point_count(self) -> int:
        """How many points the sweep has (without making them)."""
        if self.sample is not None:
            return self.sample.count
        lengths = [len(values) for _, values in self.values]
        return math.prod(lengths) if self.combine == "grid" else lengths[0]

    def fingerprint(self) -> str:
        """A SHA-256 of everything a point's result depends on: the job's and robot's
        tables, the sweep table and planar-tui's version. A checkpoint with another
        fingerprint belongs to another sweep and is never resumed."""
        return study_fingerprint(self.job, self.tables, TABLE, self.source)


def study_fingerprint(
    job: Job, tables: Mapping[str, Any], table: str, source: Mapping[str, Any]
) -> str:
    """A SHA-256 of what the points of a study (a ``table``, e.g. ``sweep``, written as
    ``source``) over ``job`` depend on: the job's and robot's raw ``tables``, the study's
    table but its ``plot`` and planar-tui's version."""
    text = json.dumps(
        {
            "version": __version__,
            "kind": job.kind,
            "key": job.key,
            "tables": tables,
            table: {k: v for k, v in source.items() if k != "plot"},
        },
        sort_keys=True,
        default=repr,
    )
    return hashlib.sha256(text.encode()).hexdigest()


def plain_toml(value: Any) -> Any:
    """A TOML value as plain Python (tomlkit's items, as the app edits them, included)."""
    if isinstance(value, Mapping):
        return {str(k): plain_toml(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [plain_toml(v) for v in value]
    for kind in (bool, int, float, str):
        if isinstance(value, kind):
            return kind(value)
    return value


def _quoted(path: str) -> str:
    return f'"{path}"' if any(c in path for c in ".[]") else path


def _job_tables(preset: Preset, job: Job) -> tuple[dict, dict]:
    """The job's raw table and the raw robot table it runs on, as plain Python."""
    document = preset.raw
    value = document[job.kind]
    table = plain_toml(value[job.index - 1] if isinstance(value, list) else value)
    robot_kind = JOB_KINDS[job.kind].robot_kind
    own = table.pop(robot_kind, None)
    robot = own if own is not None else plain_toml(document.get(robot_kind, {}))
    return table, robot


def find_job(preset: Preset, text: Any, reader: TableReader) -> Job:
    """The job a sweep's ``job`` names: a kind (its only or first table) or ``kind[k]``."""
    valid = [job.key for job in preset.jobs]
    expected = "one of the preset's jobs: " + (", ".join(valid) or "(none)")
    if not isinstance(text, str):
        raise reader.error("job", f"is {type_name(text)}", expected)
    kind, _, rest = text.partition("[")
    index = 1
    if rest:
        digits = rest[:-1]
        if not rest.endswith("]") or not (digits.isascii() and digits.isdigit()) or len(digits) > 9:
            raise reader.error("job", f"is {shown(text)}", expected)
        index = int(digits)
    for job in preset.jobs:
        if job.kind == kind and job.index == index:
            return job
    raise reader.error("job", f"is {shown(text)}, no such job", expected + suggest(text, valid))


def job_context(preset: Preset, reader: TableReader) -> tuple[Job, dict, dict]:
    """The job a table's ``job`` key names, the raw TOML tables its points start from
    (``""``: the job's own; the robot kind's name: its robot's) and their parsed values
    as TOML (see :class:`Sweep`): what a sweep, or an optimisation, varies."""
    job = find_job(
        preset, reader.raw("job", expected="a job of the preset, e.g. workspace[2]"), reader
    )
    kind = JOB_KINDS[job.kind]
    robot_kind = kind.robot_kind
    own, robot = _job_tables(preset, job)
    tables = {"": own, robot_kind: robot}
    defaults = {"": kind.dump(job.spec), robot_kind: ROBOT_KINDS[robot_kind].dump(job.robot)}
    return job, tables, defaults


def read_key_path(
    reader: TableReader,
    job: Job,
    tables: Mapping[str, Mapping[str, Any]],
    defaults: Mapping[str, Mapping[str, Any]],
    key: str,
    text: str,
) -> KeyPath:
    """The key path ``text`` of ``job`` (written under the table's ``key``), checked: a
    key of the job or of its robot, an index within the list it names."""
    kind = JOB_KINDS[job.kind]
    robot_kind = kind.robot_kind

    def error(problem: str, expected: str) -> PresetError:
        return reader.error(key, problem, expected)

    parsed = parse_key_path(text, kind.keys, robot_kind, ROBOT_KINDS[robot_kind].keys, error)
    if parsed.indices:
        base = current_value(KeyPath(text, parsed.table, parsed.key), tables)
        if base is None:
            base = current_value(KeyPath(text, parsed.table, parsed.key), defaults)
        problem = index_problem(parsed, base)
        if problem is not None:
            raise error(problem, "an index within the list, counted from 1")
    return parsed


def _values_count(reader: TableReader, name: str, entry: Any) -> int:
    """How many values a ``values`` entry has (checked, nothing built): a non-empty list's
    length, or ``{from, to, count}``'s ``count``."""
    key = f"values.{_quoted(name)}"
    expected = "a non-empty array of values, or { from = A, to = B, count = N }"
    if isinstance(entry, list):
        if not entry:
            raise reader.error(key, "is empty", expected)
        return len(entry)
    if not isinstance(entry, dict):
        raise reader.error(key, f"is {type_name(entry)}", expected)
    spaced = TableReader(reader.path, entry, reader.key(key), ("from", "to", "count"))
    spaced.number("from"), spaced.number("to")
    count = spaced.raw("count", expected="an integer >= 1")
    if isinstance(count, int) and not isinstance(count, bool) and count < 1:
        raise spaced.error("count", f"is {count}, below 1", "an integer >= 1")
    return spaced.integer("count", minimum=1)


def _read_values(reader: TableReader, name: str, entry: Any) -> tuple[Any, ...]:
    """A ``values`` entry (checked by :func:`_values_count` first): a non-empty list, or
    ``{from, to, count}`` evenly spaced with both ends included
    (``from + (to − from)·i/(count − 1)``)."""
    if isinstance(entry, list):
        return tuple(entry)
    spaced = TableReader(
        reader.path, entry, reader.key(f"values.{_quoted(name)}"), ("from", "to", "count")
    )
    start, stop, count = spaced.number("from"), spaced.number("to"), spaced.integer("count")
    if count == 1:
        return (start,)
    return (*(start + (stop - start) * i / (count - 1) for i in range(count - 1)), stop)


def _read_sample(reader: TableReader) -> Sample:
    value = reader.raw("sample", expected='{ method = "sobol", count = N, seed = S }')
    if not isinstance(value, dict):
        raise reader.error("sample", f"is {type_name(value)}", '{ method = "sobol", count = N }')
    sample = TableReader(reader.path, value, reader.key("sample"), ("method", "count", "seed"))
    method = sample.string("method", choices=SAMPLE_METHODS)
    count = sample.raw("count", expected="an integer >= 1")
    if isinstance(count, int) and not isinstance(count, bool) and count < 1:
        raise sample.error("count", f"is {count}, below 1", "an integer >= 1")
    count = sample.integer("count", minimum=1)
    seed = sample.integer("seed", 1, minimum=0, maximum=2**32 - 1)
    return Sample(method, count, seed)


def parse_sweep_table(preset: Preset, table: Any, name: str, number: int = 1) -> Sweep:
    """One sweep table (``name`` in messages, e.g. ``sweep[2]``), checked against the
    preset's jobs; the points are counted, not made (see
    :func:`planar_tui.sweep.points.make_points`)."""
    path = preset.path
    if not isinstance(table, Mapping):
        raise PresetError(path, name, f"is {type_name(table)}", "a table [[sweep]]")
    table = plain_toml(table)
    reader = TableReader(path, table, name, SWEEP_KEYS)
    job, tables, defaults = job_context(preset, reader)

    def key_path(group: str, text: str) -> KeyPath:
        return read_key_path(reader, job, tables, defaults, f"{group}.{_quoted(text)}", text)

    has_values, has_ranges = reader.has("values"), reader.has("ranges")
    if has_values == has_ranges:
        raise reader.error(
            "values" if has_values else "(table)",
            "both values and ranges are given" if has_values else "no values and no ranges",
            "values = { KEY = [...] }, or ranges = { KEY = [low, high] } with sample = {...}",
        )
    max_points = reader.integer("max_points", DEFAULT_MAX_POINTS, minimum=1, maximum=MAX_POINTS)
    values: list[tuple[KeyPath, tuple[Any, ...]]] = []
    ranges: list[tuple[KeyPath, float, float]] = []
    sample = None
    combine = "grid"
    group = "values" if has_values else "ranges"
    entries = reader.raw(group)
    if not isinstance(entries, dict) or not entries:
        what = "empty" if entries == {} else type_name(entries)
        raise reader.error(
            group, f"is {what}", "a table of key paths, e.g. { orientation_deg = [...] }"
        )
    seen: dict[tuple, str] = {}
    lengths: dict[KeyPath, int] = {}
    for text, entry in entries.items():
        parsed = key_path(group, text)
        place = (parsed.table, parsed.key, parsed.indices)
        problem = overlap_problem(parsed, seen)
        if problem is not None:
            raise reader.error(
                f"{group}.{_quoted(text)}", problem, "each value once, by one key path"
            )
        seen[place] = text
        if has_values:
            lengths[parsed] = _values_count(reader, text, entry)
        else:
            ranges.append((parsed, *_read_range(reader, text, entry)))
    if has_values:
        if reader.has("sample"):
            raise reader.error("sample", "is given with values", "sample only with ranges")
        combine = reader.string("combine", "grid", choices=COMBINE)
        if combine == "zip" and len(set(lengths.values())) > 1:
            listed = ", ".join(f"{p.text}: {n}" for p, n in lengths.items())
            raise reader.error(
                "combine",
                f'is "zip" but the lists differ in length ({listed})',
                'lists of one length, or combine = "grid"',
            )
        counts = list(lengths.values())
        count = math.prod(counts) if combine == "grid" else counts[0]
    else:
        if reader.has("combine"):
            raise reader.error("combine", "is given with ranges", "combine only with values")
        sample = _read_sample(reader)
        count = sample.count
    # counted before any value is made: a count of 10^9 is refused, not built
    if count > max_points:
        raise reader.error(
            "max_points" if reader.has("max_points") else group,
            f"the sweep has {count:,} points, more than max_points = {max_points:,}",
            f"at most {max_points:,} points, or a larger max_points",
        )
    values = [(path, _read_values(reader, path.text, entries[path.text])) for path in lengths]
    output = reader.relative_path("output", f"{path.stem}-sweep-{number}.csv")
    point_outputs = reader.relative_path("point_outputs", None)
    plot = figure_path()(reader, "plot", None, None, {})
    return Sweep(
        preset_path=path,
        name=name,
        job=job,
        document=preset.raw,
        tables=tables,
        defaults=defaults,
        values=tuple(values),
        ranges=tuple(ranges),
        sample=sample,
        combine=combine,
        output=output,
        point_outputs=point_outputs,
        plot=plot,
        max_points=max_points,
        source=table,
    )


def _read_range(reader: TableReader, text: str, entry: Any) -> tuple[float, float]:
    key = f"ranges.{_quoted(text)}"
    expected = "[low, high] with low <= high"
    if not isinstance(entry, list) or len(entry) != 2:
        raise reader.error(
            key,
            f"is {type_name(entry)}"
            + (f" of {len(entry)} items" if isinstance(entry, list) else ""),
            expected,
        )
    low, high = _two_numbers(reader, key, entry)
    if low > high:
        raise reader.error(key, f"is [{low:g}, {high:g}], low above high", expected)
    return low, high


def _two_numbers(reader: TableReader, key: str, entry: list) -> tuple[float, float]:
    low, high = (
        reader._check_number(
            key, item, positive=False, minimum=None, maximum=None, where=f"item {i} "
        )
        for i, item in enumerate(entry, start=1)
    )
    return low, high


def parse_sweeps(preset: Preset) -> tuple[Sweep, ...]:
    """The preset's ``[[sweep]]`` tables (or one ``[sweep]`` table), checked."""
    value = preset.raw.get(TABLE)
    if value is None:
        return ()
    if isinstance(value, list):
        return tuple(
            parse_sweep_table(preset, table, f"{TABLE}[{k}]", k)
            for k, table in enumerate(value, start=1)
        )
    return (parse_sweep_table(preset, value, TABLE, 1),)


def build_sweep(
    preset: Preset,
    job: str,
    *,
    values: Mapping[str, Sequence[Any] | Mapping[str, Any]] | None = None,
    ranges: Mapping[str, Sequence[float]] | None = None,
    sample: Mapping[str, Any] | None = None,
    combine: str = "grid",
    output: str | None = None,
    point_outputs: str | None = None,
    max_points: int = DEFAULT_MAX_POINTS,
    name: str = TABLE,
) -> Sweep:
    """A sweep made without a file (the app's dialog), checked exactly like a
    ``[[sweep]]`` table with these keys (:class:`PresetError` otherwise)."""
    table: dict[str, Any] = {"job": job}
    if values is not None:
        table["values"] = {
            k: (dict(v) if isinstance(v, Mapping) else list(v)) for k, v in values.items()
        }
        table["combine"] = combine
    if ranges is not None:
        table["ranges"] = {k: list(v) for k, v in ranges.items()}
    if sample is not None:
        table["sample"] = dict(sample)
    if output is not None:
        table["output"] = output
    if point_outputs is not None:
        table["point_outputs"] = point_outputs
    if max_points != DEFAULT_MAX_POINTS:
        table["max_points"] = max_points
    return parse_sweep_table(preset, table, name)

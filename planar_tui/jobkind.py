"""What a robot kind and a job kind are, what a job is and what running one returns.

A job kind lives in one module of its domain package (``planar_tui/dynamics/simulate.py``,
``planar_tui/sensitivity/job.py``, ``planar_tui/workspace/job.py`` ...), which holds its
settings dataclass (the preset keys, declared once with :func:`planar_tui.schema.setting`),
its runner, its result dataclass and its terminal view, and ends with one
:class:`JobKind`; :mod:`planar_tui.registry` lists the kinds, one line each.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from planar_tui.csvio import CsvTable
from planar_tui.progress import Progress
from planar_tui.schema import TableReader, dump_settings, parse_settings, setting_keys


@dataclass(frozen=True)
class RobotKind:
    """A robot table of a preset (``[robot]``, ``[robot3rrr]``): its model dataclass,
    whose fields declare the table's keys."""

    name: str
    model: type

    @property
    def keys(self) -> tuple[str, ...]:
        return setting_keys(self.model)

    def parse(self, reader: TableReader) -> Any:
        return parse_settings(self.model, reader)

    def dump(self, robot: Any) -> dict[str, Any]:
        return dump_settings(robot)


@dataclass(frozen=True)
class Job:
    """One job of a preset, ready to run.

    ``kind`` names the registered job kind, ``spec`` is that kind's parsed settings,
    ``robot`` the robot model it runs on, ``output`` the CSV file name relative to the
    output folder, ``label`` a short name for progress bars and summaries (``preset:key``),
    ``key`` the job's table in the preset (``simulate``, ``simulate[2]``); ``variant`` is
    what command-line overrides changed (``--form-mean-value``), appended to the stem of
    every output file the preset names (see :func:`planar_tui.batch.apply_overrides`).
    """

    kind: str
    index: int
    label: str
    robot: Any
    spec: Any
    output: str
    preset_path: Path
    variant: str = ""

    @property
    def key(self) -> str:
        """The job's table in its preset: ``simulate`` or ``simulate[2]``."""
        return self.label.rsplit(":", 1)[-1]


@dataclass(frozen=True, kw_only=True)
class JobResult:
    """What every runner returns; each kind subclasses it with its typed payload.

    ``table`` is the job's main CSV (the preset's ``output``); ``extra_tables`` holds
    further CSVs by name (e.g. ``"boxes"``); ``summary`` is one line for the summary table.
    """

    table: CsvTable
    summary: str
    extra_tables: Mapping[str, CsvTable] = field(default_factory=dict)


def _no_extra_outputs(spec: Any) -> dict[str, str]:
    return {}


@dataclass(frozen=True)
class JobKind:
    """A job table of a preset (``[simulate]``, ``[[torques]]`` ...).

    ``settings`` is the settings dataclass (its declared keys are the table's keys;
    ``output`` and the robot sub-table are added by the loader); ``run(job, progress)``
    computes a :class:`JobResult` and writes nothing; ``render(job, result, console)``
    prints it on a rich console (optional); ``extra_outputs(spec)`` names the extra
    tables the preset asks to write, relative to the output folder (e.g.
    ``{"boxes": "boxes.csv"}``); ``overrides(spec, options)`` applies and checks
    command-line options (``None`` values keep the preset's); ``prepare(job)`` does the
    costly part of validation that parsing skips so that it stays cheap enough for every
    keystroke (e.g. solving the sensitivity's isotropic posture): it returns the job
    ready to run or raises :class:`~planar_tui.errors.PresetError`; the batch service
    calls it for every job before the first one runs (:func:`planar_tui.batch.prepare_jobs`).
    ``check(job)`` is the part of ``prepare`` that computes nothing (a device usable
    here, say): a sweep runs it on every point before the first one runs
    (:func:`planar_tui.sweep.points.make_points`), so a point that cannot run is refused
    up front rather than failing (:class:`~planar_tui.errors.PresetError`).
    ``point_figures(job, result)`` gives the kind's summary figures of one result as
    ordered columns (name with unit -> number or text): one sweep row per point;
    ``figure_names(job)``, where a kind declares it, names those columns without running
    the job (a resumed sweep checks its checkpoint's records against them);
    ``estimate(job)``, where a kind declares it, is the job's rough ``(memory_bytes,
    seconds)`` (the ones its checks hold against :mod:`planar_tui.limits`): a sweep sums
    its points' to refuse what cannot finish.
    """

    name: str
    robot_kind: str
    settings: type
    run: Callable[[Job, Progress], JobResult]
    summary: str
    render: Callable[[Job, JobResult, Any], None] | None = None
    extra_outputs: Callable[[Any], dict[str, str]] = _no_extra_outputs
    overrides: Callable[[Any, Mapping[str, Any]], Any] | None = None
    prepare: Callable[[Job], Job] | None = None
    check: Callable[[Job], None] | None = None
    point_figures: Callable[[Job, JobResult], dict[str, Any]] | None = None
    figure_names: Callable[[Job], tuple[str, ...]] | None = None
    estimate: Callable[[Job], tuple[float, float]] | None = None

    @property
    def keys(self) -> tuple[str, ...]:
        """The job table's own keys, in declaration order."""
        return setting_keys(self.settings)

    def parse(self, reader: TableReader, robot: Any) -> Any:
        """The table's settings, checked against the job's robot."""
        return parse_settings(self.settings, reader, robot)

    def dump(self, spec: Any) -> dict[str, Any]:
        """The settings as a TOML table."""
        return dump_settings(spec)

    def prepared(self, job: Job) -> Job:
        """The job ready to run (see ``prepare``); :class:`PresetError` if it cannot run."""
        return job if self.prepare is None else self.prepare(job)

    def with_overrides(self, spec: Any, options: Mapping[str, Any]) -> Any:
        """The settings with command-line options applied (and checked)."""
        if self.overrides is None or all(value is None for value in options.values()):
            return spec
        return self.overrides(spec, options)

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
from typing import Any, Generic, TypeVar

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


#: A kind's settings dataclass, its robot model and what its ``prepare`` resolves.
SpecT = TypeVar("SpecT", covariant=True)
RobotT = TypeVar("RobotT", covariant=True)
PreparedT = TypeVar("PreparedT", covariant=True)


@dataclass(frozen=True)
class Job(Generic[SpecT, RobotT]):
    """One job of a preset, as parsed (and overridden on the command line).

    ``kind`` names the registered job kind, ``spec`` is that kind's parsed settings (the
    preset's keys, nothing derived), ``robot`` the robot model it runs on, ``output`` the
    CSV file name relative to the output folder, ``label`` a short name for progress bars
    and summaries (``preset:key``), ``key`` the job's table in the preset (``simulate``,
    ``simulate[2]``); ``variant`` is what command-line overrides changed
    (``--form-mean-value``), appended to the stem of every output file the preset names
    (see :func:`planar_tui.batch.apply_overrides`); ``overridden`` maps the settings a
    command-line option set to that option (``{"samples": "--samples"}``), so that a
    problem they cause names the option (``command line: --samples``), not the preset.
    """

    kind: str
    index: int
    label: str
    robot: RobotT
    spec: SpecT
    output: str
    preset_path: Path
    variant: str = ""
    overridden: Mapping[str, str] = field(default_factory=dict)

    @property
    def key(self) -> str:
        """The job's table in its preset: ``simulate`` or ``simulate[2]``."""
        return self.label.rsplit(":", 1)[-1]


@dataclass(frozen=True)
class PreparedJob(Generic[SpecT, RobotT, PreparedT]):
    """A job ready to run: the :class:`Job` and what its kind's ``prepare`` resolved from
    it, once (a sensitivity's solved posture, a motion job's device, a workspace's
    singularity-free circle; ``None`` for a kind without ``prepare``). The job's fields
    are read through (``spec``, ``robot``, ``label`` ...)."""

    job: Job[SpecT, RobotT]
    prepared: PreparedT

    @property
    def kind(self) -> str:
        return self.job.kind

    @property
    def index(self) -> int:
        return self.job.index

    @property
    def label(self) -> str:
        return self.job.label

    @property
    def key(self) -> str:
        return self.job.key

    @property
    def robot(self) -> RobotT:
        return self.job.robot

    @property
    def spec(self) -> SpecT:
        return self.job.spec

    @property
    def output(self) -> str:
        return self.job.output

    @property
    def preset_path(self) -> Path:
        return self.job.preset_path

    @property
    def variant(self) -> str:
        return self.job.variant

    @property
    def overridden(self) -> Mapping[str, str]:
        return self.job.overridden


def option_or_key(job: Job[object, object], key: str, *causes: str) -> tuple[Path | str, str]:
    """Where a problem of the job's setting ``key`` comes from, as :class:`PresetError`'s
    first two arguments: ``("command line", "--samples")`` when a command-line option set
    ``key`` (or one of ``causes``, the settings that change it), else the preset and its
    key (``(path, "sensitivity[2].samples")``)."""
    for name in (key, *causes):
        if name in job.overridden:
            return "command line", job.overridden[name]
    return job.preset_path, f"{job.key}.{key}"


@dataclass(frozen=True, kw_only=True)
class JobResult:
    """What every runner returns; each kind subclasses it with its typed payload.

    ``table`` is the job's main CSV (the preset's ``output``); ``extra_tables`` holds
    further CSVs by name (e.g. ``"boxes"``); ``summary`` is one line for the summary table.
    """

    table: CsvTable
    summary: str
    extra_tables: Mapping[str, CsvTable] = field(default_factory=dict)


def _no_extra_outputs(job: Job[object, object]) -> dict[str, str]:
    return {}


@dataclass(frozen=True)
class JobKind:
    """A job table of a preset (``[simulate]``, ``[[torques]]`` ...).

    ``settings`` is the settings dataclass (its declared keys are the table's keys;
    ``output`` and the robot sub-table are added by the loader); ``run(job, progress)``
    computes a :class:`JobResult` and writes nothing; ``render(job, result, console)``
    prints it on a rich console (optional); ``extra_outputs(job)`` names the extra
    tables the preset asks to write, relative to the output folder (e.g.
    ``{"boxes": "boxes.csv"}``); ``overrides(spec, options)`` applies and checks
    command-line options (``None`` values keep the preset's); ``prepare(job)`` does the
    costly part of validation that parsing skips so that it stays cheap enough for every
    keystroke (e.g. solving the sensitivity's isotropic posture): it returns what it
    resolved (the kind's typed prepared payload, carried by a :class:`PreparedJob` to
    ``run``) or raises :class:`~planar_tui.errors.PresetError`; the batch service
    prepares every job once, before the first one runs
    (:func:`planar_tui.batch.prepare_jobs`).
    ``check(job)`` is the part of ``prepare`` that computes nothing (a device usable
    here, say): a sweep runs it on every point before the first one runs
    (:func:`planar_tui.sweep.points.make_points`), so a point that cannot run is refused
    up front rather than failing (:class:`~planar_tui.errors.PresetError`).
    ``point_figures(job, result)`` gives the kind's summary figures of one result as
    ordered columns (name with unit -> number or text): one sweep row per point.
    """

    name: str
    robot_kind: str
    settings: type
    run: Callable[[PreparedJob[Any, Any, Any], Progress], JobResult]
    summary: str
    render: Callable[[Job[Any, Any], JobResult, Any], None] | None = None
    extra_outputs: Callable[[Job[Any, Any]], dict[str, str]] = _no_extra_outputs
    overrides: Callable[[Any, Mapping[str, Any]], Any] | None = None
    prepare: Callable[[Job[Any, Any]], object] | None = None
    check: Callable[[Job], None] | None = None
    point_figures: Callable[[Job, JobResult], dict[str, Any]] | None = None

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

    def prepare_job(self, job: Job[Any, Any]) -> PreparedJob[Any, Any, object]:
        """The job ready to run (see ``prepare``, called once here); :class:`PresetError`
        if it cannot run."""
        return PreparedJob(job, None if self.prepare is None else self.prepare(job))

    def with_overrides(self, spec: Any, options: Mapping[str, Any]) -> Any:
        """The settings with command-line options applied (and checked)."""
        if self.overrides is None or all(value is None for value in options.values()):
            return spec
        return self.overrides(spec, options)

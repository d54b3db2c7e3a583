"""What a robot kind and a job kind are, what a job is and what running one returns.

A job kind lives in one module of its domain package (``planar_tui/dynamics/simulate.py``,
``planar_tui/sensitivity/job.py``, ``planar_tui/workspace/rrr/job.py`` ...), which holds its
settings dataclass (the preset keys, declared once with :func:`planar_tui.schema.setting`),
its runner, its result dataclass and its terminal view, and ends with one
:class:`JobKind` that declares the rest as data: its CLI command and options
(:class:`Command`, :class:`Option`), its app tab (:class:`Tab`), its figure and its
warm-up example. :mod:`planar_tui.registry` lists the kinds, one line each; the CLI's
commands, the app's tabs, ``run``, sweeps, figures and warm-up are generated from it.
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
    #: A small robot table in TOML (``[robot]`` and its keys) for the job kinds' warm-up
    #: examples (:data:`JobKind.warmup`).
    example: str = ""
    #: The table the app shows when the open preset has none of this kind (its keys and
    #: values; empty: the app shows the keys' defaults).
    app_default: Mapping[str, Any] = field(default_factory=dict)

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
    (see :func:`planar_tui.overrides.apply_overrides`); ``overridden`` maps the settings a
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
class Option:
    """A command-line option of a kind's command that overrides one preset key.

    ``name`` is the option (``--precision``), ``key`` the settings key it sets
    (``precision_cm``); the value is read with the key's own reader, so it is checked
    exactly as the preset's value is (:func:`planar_tui.overrides.apply_overrides`). ``type``
    is what Typer converts the text to (``str``, ``int``, ``float``); ``many`` makes it
    repeatable (a list); ``short`` is a one-letter alias (``-m``). In the names of the
    files it changes the option appears without its dashes (``--precision-0.5``).
    """

    name: str
    key: str
    help: str
    type: type = str
    many: bool = False
    short: str | None = None

    @property
    def label(self) -> str:
        """How the option appears in the file names it changes (``precision``)."""
        return self.name.lstrip("-")


@dataclass(frozen=True)
class OutputOption:
    """A command-line option naming where one of the kind's extra tables goes
    (``--boxes FILE`` for a workspace's ``boxes`` table)."""

    name: str
    table: str
    help: str


@dataclass(frozen=True)
class Command:
    """A job kind's CLI command (``planar-tui NAME PRESET``), generated by the CLI.

    ``help`` is its help text (first sentence: its line in ``planar-tui --help``);
    ``options`` its overriding options, ``outputs`` its extra-table options, ``view`` a
    flag (``--map/--no-map``) with its help that turns the kind's terminal view off.
    Every command also has ``--job``, ``--out``, ``--out-dir`` and ``--plot``.
    """

    name: str
    help: str
    options: tuple[Option, ...] = ()
    outputs: tuple[OutputOption, ...] = ()
    view: tuple[str, str] | None = None


@dataclass(frozen=True)
class Tab:
    """A job kind's tab in the app: its title, its place (tabs sorted by ``order``; the
    Robot tab is first) and its pane as an import path (``module:Class``), so that the core
    never imports Textual; without one the app's generic job pane shows the kind. A pane
    that steps through views (its ``action_toggle_view``, key ``ctrl+t``) declares the
    key's label in the footer (``view``, ``"S1/ST/%"``) and what it steps through, for the
    help and the palette (``view_help``)."""

    title: str
    order: int = 100
    pane: str | None = None
    view: str | None = None
    view_help: str = ""


@dataclass(frozen=True)
class JobKind:
    """A job table of a preset (``[simulate]``, ``[[torques]]`` ...).

    ``settings`` is the settings dataclass (its declared keys are the table's keys;
    ``output`` and the robot sub-table are added by the loader); ``run(job, progress)``
    computes a :class:`JobResult` and writes nothing; ``render(job, result, console)``
    prints it on a rich console (optional); ``extra_outputs(job)`` names the extra
    tables the preset asks to write, relative to the output folder (e.g.
    ``{"boxes": "boxes.csv"}``); ``prepare(job)`` does the
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
    ordered columns (name with unit -> number or text): one sweep row per point;
    ``figure_names(job)``, where a kind declares it, names those columns without running
    the job (a resumed sweep checks its checkpoint's records against them);
    ``estimate(job)``, where a kind declares it, is the job's rough ``(memory_bytes,
    seconds)`` (the ones its checks hold against :mod:`planar_tui.limits`): a sweep sums
    its points' to refuse what cannot finish.

    Declared as data for the front ends: ``command`` (its CLI command, :class:`Command`),
    ``tab`` (its app tab, :class:`Tab`), ``figure`` (the function drawing a finished job's
    figure, as an import path ``module:function`` taking ``(job, result)``; ``None``: the
    kind draws no figure, and a ``--plot`` or ``plot`` key for it is refused before
    anything runs) and ``warmup`` (a tiny example job table in TOML, run with its robot
    kind's ``example`` to compile the kind's kernels, :mod:`planar_tui.warmup`; or such
    examples by part, ``{"joint": ..., "orientation": ...}``, with ``warmup_parts(job)``
    naming the parts a job's run needs, so that a cold run compiles only their kernels).
    ``app_default`` is the table the app's tab shows when the open preset has none of
    this kind (small and quick; its per-link arrays sized to the preset's robot, an empty
    one left out).
    ``overrides(table, given)`` adjusts the keys that follow an overridden one in the TOML
    table the command-line options are applied to (e.g. a workspace's refinement
    precision capped by a new precision): see :func:`planar_tui.overrides.apply_overrides`.
    """

    name: str
    robot_kind: str
    settings: type
    run: Callable[[PreparedJob[Any, Any, Any], Progress], JobResult]
    summary: str
    render: Callable[[Job[Any, Any], Any, Any], None] | None = None
    extra_outputs: Callable[[Job[Any, Any]], dict[str, str]] = _no_extra_outputs
    overrides: Callable[[dict[str, Any], Mapping[str, Any]], dict[str, Any]] | None = None
    prepare: Callable[[Job[Any, Any]], object] | None = None
    check: Callable[[Job[Any, Any]], None] | None = None
    point_figures: Callable[[Job[Any, Any], Any], dict[str, Any]] | None = None
    command: Command | None = None
    tab: Tab | None = None
    figure: str | None = None
    warmup: str | Mapping[str, str] | None = None
    warmup_parts: Callable[[Job[Any, Any]], tuple[str, ...]] | None = None
    figure_names: Callable[[Job[Any, Any]], tuple[str, ...]] | None = None
    estimate: Callable[[Job[Any, Any]], tuple[float, float]] | None = None
    app_default: Mapping[str, Any] = field(default_factory=dict)

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


def resolve(path: str) -> Any:
    """The object an import path names: ``"package.module:attribute"`` (the attribute of
    that module, imported then) or ``"package.module"`` (the module). The one resolver of
    the ``module:attr`` strings the kinds declare (a tab's pane, a figure function, a
    registry line) and of the modules imported on demand; ``ImportError`` or
    ``AttributeError`` when it names nothing."""
    import importlib

    module, _, attribute = path.partition(":")
    found = importlib.import_module(module)
    return getattr(found, attribute) if attribute else found

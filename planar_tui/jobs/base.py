"""What a robot kind and a job kind are: one small schema plus one runner."""

from __future__ import annotations

import importlib
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

from planar_tui.csvio import CsvTable
from planar_tui.presets import Job, TableReader
from planar_tui.progress import Progress


@dataclass(frozen=True)
class RobotKind:
    """A robot table of a preset: its allowed keys, a parser and a writer."""

    name: str
    keys: tuple[str, ...]
    parse: Callable[[TableReader], Any]
    dump: Callable[[Any], dict] = lambda robot: robot.to_table()


@dataclass
class JobResult:
    """What a runner returns.

    ``table`` is the job's main CSV (the preset's ``output``); ``extra_tables`` holds
    further CSVs by name (e.g. ``"boxes"``); ``summary`` is one line for the summary
    table; ``data`` is a kind-specific payload for renderers (tables, maps, plots).
    """

    table: CsvTable
    summary: str
    extra_tables: dict[str, CsvTable] = field(default_factory=dict)
    data: Any = None


@dataclass(frozen=True)
class JobKind:
    """A job table of a preset (``[simulate]``, ``[[torques]]`` ...).

    ``keys`` are the job's own keys (``output`` and the robot sub-table are added by the
    loader); ``parse(reader, robot)`` returns the job's settings; ``dump(spec)`` turns
    them back into a TOML table (for saving presets from the app); ``runner`` is
    ``"module:function"``, imported only when a job runs, with signature
    ``run(job: Job, progress: Progress) -> JobResult``; ``render`` optionally names
    ``"module:function"`` printing the result in the terminal (``(job, result, console)``);
    ``extra_outputs(spec)`` names the result's extra tables the preset asks to write, with
    their file names relative to the output folder (e.g. ``{"boxes": "boxes.csv"}``).
    """

    name: str
    robot_kind: str
    keys: tuple[str, ...]
    parse: Callable[[TableReader, Any], Any]
    dump: Callable[[Any], Mapping[str, Any]]
    runner: str
    summary: str
    render: str | None = None
    extra_outputs: Callable[[Any], dict[str, str]] = lambda spec: {}

    def _load(self, target: str) -> Callable[..., Any]:
        module_name, function_name = target.split(":")
        return getattr(importlib.import_module(module_name), function_name)

    def run(self, job: Job, progress: Progress | None = None) -> JobResult:
        """Import the runner lazily and run ``job``."""
        return self._load(self.runner)(job, progress or Progress())

    def show(self, job: Job, result: JobResult, console: Any) -> None:
        """Print the kind's terminal view of a result (tables, maps) on a rich console;
        ``render`` is ``"module:function"`` taking ``(job, result, console)``."""
        if self.render is not None:
            self._load(self.render)(job, result, console)

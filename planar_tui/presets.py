"""Preset files: strict TOML reading with one clear error per problem.

A preset holds robot tables (``[robot]``, ``[robot3rrr]``) and job tables
(``[simulate]``, ``[[simulate]]``, ``[torques]``, ...). A job may carry its own robot
(``[simulate.robot]`` after a ``[[simulate]]``) that replaces the preset's robot of that
kind for that job. Each robot kind and job kind is registered in :mod:`planar_tui.jobs`
as a small schema (allowed keys and a parse function using :class:`TableReader`).
"""

from __future__ import annotations

import difflib
import math
import tomllib
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from planar_tui.errors import PresetError

_MISSING: Any = object()


def _type_name(value: Any) -> str:
    return {
        bool: "a boolean",
        int: "an integer",
        float: "a number",
        str: "a string",
        list: "an array",
        dict: "a table",
    }.get(type(value), type(value).__name__)


def _suggest(name: str, allowed: Iterable[str]) -> str:
    close = difflib.get_close_matches(name, list(allowed), n=1, cutoff=0.6)
    return f"; did you mean {close[0]}?" if close else ""


class TableReader:
    """Typed, validated access to one TOML table of a preset.

    Unknown keys are rejected as soon as the reader is made, so a typo is reported as
    such rather than as a missing key. Every getter raises :class:`PresetError` naming
    the file, the dotted key and what was expected.

    Parameters
    ----------
    path
        The preset file (for messages).
    table
        The parsed TOML table.
    prefix
        Dotted name of the table (``"robot"``, ``"simulate[2]"``), prefixed to keys.
    allowed
        Every key the table may hold.
    """

    def __init__(
        self, path: Path | str, table: Mapping[str, Any], prefix: str, allowed: Sequence[str]
    ):
        self.path = Path(path)
        self.table = table
        self.prefix = prefix
        self.allowed = tuple(allowed)
        for name in table:
            if name not in self.allowed:
                raise self.error(
                    name,
                    "unknown key",
                    "one of " + ", ".join(self.allowed) + _suggest(name, self.allowed),
                )

    # -- plumbing -----------------------------------------------------------------
    def key(self, name: str) -> str:
        """The dotted key of ``name`` in this table."""
        return f"{self.prefix}.{name}" if self.prefix else name

    def error(self, name: str, problem: str, expected: str | None = None) -> PresetError:
        """A :class:`PresetError` about key ``name`` of this table."""
        return PresetError(self.path, self.key(name), problem, expected)

    def has(self, name: str) -> bool:
        """Whether the table holds key ``name``."""
        return name in self.table

    def raw(self, name: str, default: Any = _MISSING, expected: str = "a value") -> Any:
        """The value of ``name``, ``default`` if absent, or a 'missing key' error."""
        if name in self.table:
            return self.table[name]
        if default is _MISSING:
            raise self.error(name, "missing key", expected)
        return default

    # -- scalars ------------------------------------------------------------------
    def _check_number(
        self,
        name: str,
        value: Any,
        *,
        positive: bool,
        minimum: float | None,
        maximum: float | None,
        where: str = "",
    ) -> float:
        wanted = "a positive number" if positive else "a number"
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise self.error(name, f"{where}is {_type_name(value)}", wanted)
        number = float(value)
        if not math.isfinite(number):
            raise self.error(name, f"{where}is {value!r}, not a finite number", wanted)
        if positive and number <= 0:
            raise self.error(name, f"{where}is {value!r}, must be > 0", wanted)
        if minimum is not None and number < minimum:
            raise self.error(name, f"{where}is {value!r}, below the minimum", f">= {minimum:g}")
        if maximum is not None and number > maximum:
            raise self.error(name, f"{where}is {value!r}, above the maximum", f"<= {maximum:g}")
        return number

    def number(
        self,
        name: str,
        default: Any = _MISSING,
        *,
        positive: bool = False,
        minimum: float | None = None,
        maximum: float | None = None,
    ) -> float:
        """A finite float (TOML integer or float), optionally > 0 or within bounds."""
        value = self.raw(name, default, "a positive number" if positive else "a number")
        if value is default and default is not _MISSING:
            return value
        return self._check_number(name, value, positive=positive, minimum=minimum, maximum=maximum)

    def integer(self, name: str, default: Any = _MISSING, *, minimum: int | None = None) -> int:
        """A TOML integer, optionally >= ``minimum``."""
        wanted = "an integer" if minimum is None else f"an integer >= {minimum}"
        value = self.raw(name, default, wanted)
        if value is default and default is not _MISSING:
            return value
        if isinstance(value, bool) or not isinstance(value, int):
            raise self.error(name, f"is {_type_name(value)}", wanted)
        if minimum is not None and value < minimum:
            raise self.error(name, f"is {value}", wanted)
        return value

    def string(
        self, name: str, default: Any = _MISSING, *, choices: Sequence[str] | None = None
    ) -> str:
        """A TOML string, optionally one of ``choices``."""
        wanted = "one of " + ", ".join(choices) if choices else "a string"
        value = self.raw(name, default, wanted)
        if value is default and default is not _MISSING:
            return value
        if not isinstance(value, str):
            raise self.error(name, f"is {_type_name(value)}", wanted)
        if choices is not None and value not in choices:
            raise self.error(name, f"is {value!r}", wanted + _suggest(value, choices))
        return value

    def relative_path(self, name: str, default: Any = _MISSING) -> str:
        """A file name relative to the output folder (not absolute, no ``..``)."""
        value = self.string(name, default)
        if value is default and default is not _MISSING:
            return value
        if not value or Path(value).is_absolute() or ".." in Path(value).parts:
            raise self.error(name, f"is {value!r}", "a file name relative to the output folder")
        return value

    def boolean(self, name: str, default: Any = _MISSING) -> bool:
        """A TOML boolean."""
        value = self.raw(name, default, "true or false")
        if not isinstance(value, bool):
            raise self.error(name, f"is {_type_name(value)}", "true or false")
        return value

    # -- arrays -------------------------------------------------------------------
    def numbers(
        self,
        name: str,
        default: Any = _MISSING,
        *,
        length: int | None = None,
        positive: bool = False,
        minimum: float | None = None,
        maximum: float | None = None,
        non_empty: bool = True,
    ) -> tuple[float, ...]:
        """An array of finite numbers, optionally of a given length and > 0."""
        kind = "positive numbers" if positive else "numbers"
        wanted = f"an array of {length} {kind}" if length is not None else f"an array of {kind}"
        value = self.raw(name, default, wanted)
        if value is default and default is not _MISSING:
            return value
        if not isinstance(value, list):
            raise self.error(name, f"is {_type_name(value)}", wanted)
        if length is not None and len(value) != length:
            raise self.error(name, f"has {len(value)} values", f"{length}, one per link")
        if non_empty and not value:
            raise self.error(name, "is empty", wanted)
        return tuple(
            self._check_number(
                name,
                item,
                positive=positive,
                minimum=minimum,
                maximum=maximum,
                where=f"item {i + 1} ",
            )
            for i, item in enumerate(value)
        )

    def number_rows(
        self, name: str, default: Any = _MISSING, *, columns: int | None = None
    ) -> tuple[tuple[float, ...], ...]:
        """A non-empty array of arrays of finite numbers, each with ``columns`` values."""
        wanted = f"an array of arrays of {columns} numbers" if columns else "an array of arrays"
        value = self.raw(name, default, wanted)
        if value is default and default is not _MISSING:
            return value
        if not isinstance(value, list) or not value:
            raise self.error(name, f"is {_type_name(value) if value != [] else 'empty'}", wanted)
        rows = []
        for r, row in enumerate(value):
            if not isinstance(row, list):
                raise self.error(name, f"row {r + 1} is {_type_name(row)}", wanted)
            if columns is not None and len(row) != columns:
                raise self.error(
                    name, f"row {r + 1} has {len(row)} values", f"{columns}, one per link"
                )
            rows.append(
                tuple(
                    self._check_number(
                        name,
                        item,
                        positive=False,
                        minimum=None,
                        maximum=None,
                        where=f"row {r + 1} ",
                    )
                    for item in row
                )
            )
        return tuple(rows)


@dataclass(frozen=True)
class Job:
    """One job of a preset, ready to run.

    ``kind`` names the registered job kind, ``spec`` is that kind's parsed settings,
    ``robot`` the robot model it runs on, ``output`` the CSV file name relative to the
    output folder, ``label`` a short name for progress bars and summaries.
    """

    kind: str
    index: int
    label: str
    robot: Any
    spec: Any
    output: str
    preset_path: Path


@dataclass(frozen=True)
class Preset:
    """A parsed preset: its robots by kind and its jobs in file order."""

    path: Path
    robots: dict[str, Any] = field(default_factory=dict)
    jobs: tuple[Job, ...] = ()
    raw: Mapping[str, Any] = field(default_factory=dict)

    def jobs_of(self, kind: str) -> tuple[Job, ...]:
        """The jobs of one kind, in file order."""
        return tuple(job for job in self.jobs if job.kind == kind)


def read_toml(path: Path | str) -> dict[str, Any]:
    """Parse a TOML file; unreadable files and syntax errors become :class:`PresetError`."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise PresetError(
            path, "(file)", "no such file", "a preset path or a bundled preset name"
        ) from None
    except (OSError, UnicodeDecodeError) as exc:
        raise PresetError(
            path, "(file)", f"cannot be read: {exc}", "a readable UTF-8 TOML file"
        ) from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise PresetError(path, "(syntax)", f"invalid TOML: {exc}", "valid TOML") from None


def parse_preset(path: Path | str, document: Mapping[str, Any]) -> Preset:
    """Validate a parsed TOML document against the registered robot and job kinds."""
    from planar_tui.jobs import JOB_KINDS, ROBOT_KINDS

    path = Path(path)
    top_level = list(ROBOT_KINDS) + list(JOB_KINDS)
    for name, value in document.items():
        if name not in top_level:
            raise PresetError(
                path,
                name,
                "unknown table",
                "one of " + ", ".join(top_level) + _suggest(name, top_level),
            )
        if name in ROBOT_KINDS and not isinstance(value, dict):
            raise PresetError(path, name, f"is {_type_name(value)}", f"a table [{name}]")
        if name in JOB_KINDS and not (
            isinstance(value, dict)
            or (isinstance(value, list) and all(isinstance(v, dict) for v in value))
        ):
            raise PresetError(
                path, name, f"is {_type_name(value)}", f"a table [{name}] or tables [[{name}]]"
            )

    robots = {
        name: ROBOT_KINDS[name].parse(
            TableReader(path, document[name], name, ROBOT_KINDS[name].keys)
        )
        for name in ROBOT_KINDS
        if name in document
    }
    jobs: list[Job] = []
    for kind_name, value in document.items():
        if kind_name not in JOB_KINDS:
            continue
        kind = JOB_KINDS[kind_name]
        tables = value if isinstance(value, list) else [value]
        for index, table in enumerate(tables, start=1):
            prefix = f"{kind_name}[{index}]" if isinstance(value, list) else kind_name
            reader = TableReader(path, table, prefix, (*kind.keys, "output", kind.robot_kind))
            robot_kind = ROBOT_KINDS[kind.robot_kind]
            if reader.has(kind.robot_kind):
                own = reader.raw(kind.robot_kind)
                if not isinstance(own, dict):
                    raise reader.error(kind.robot_kind, f"is {_type_name(own)}", "a table")
                robot = robot_kind.parse(
                    TableReader(path, own, reader.key(kind.robot_kind), robot_kind.keys)
                )
            elif kind.robot_kind in robots:
                robot = robots[kind.robot_kind]
            else:
                raise PresetError(
                    path,
                    prefix,
                    "no robot for this job",
                    f"a [{kind.robot_kind}] table or a [{kind_name}.{kind.robot_kind}] table",
                )
            spec = kind.parse(reader, robot)
            default_output = f"{path.stem}-{kind_name}-{index}.csv"
            output = reader.relative_path("output", default_output)
            jobs.append(Job(kind_name, index, f"{path.stem}:{prefix}", robot, spec, output, path))
    return Preset(path, robots, tuple(jobs), document)


def load_preset(path: Path | str) -> Preset:
    """Read, parse and validate a preset file (see :func:`parse_preset`)."""
    return parse_preset(path, read_toml(path))

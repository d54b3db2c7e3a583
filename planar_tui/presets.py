"""Preset files: strict TOML reading with one clear error per problem.

A preset holds robot tables (``[robot]``, ``[robot3rrr]``) and job tables
(``[simulate]``, ``[[simulate]]``, ``[torques]``, ...). A job may carry its own robot
(``[simulate.robot]`` after a ``[[simulate]]``) that replaces the preset's robot of that
kind for that job. Each robot kind and job kind is registered in :mod:`planar_tui.registry`
with its keys declared once (:mod:`planar_tui.schema`).
"""

from __future__ import annotations

import tomllib
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from planar_tui.csvio import write_new_text
from planar_tui.errors import PresetError
from planar_tui.jobkind import Job
from planar_tui.reader import read_bounded_text
from planar_tui.registry import JOB_KINDS, ROBOT_KINDS
from planar_tui.resources import bundled_preset
from planar_tui.schema import TableReader, suggest, type_name

#: The top-level table of sweeps (``[[sweep]]``): accepted here as tables, read and
#: checked by :mod:`planar_tui.sweep.spec` (a layer above).
SWEEP_TABLE = "sweep"
#: The top-level tables of studies over a preset's jobs, accepted here as tables and read
#: by the layers above: sweeps, and optimisations (:mod:`planar_tui.optimise.spec`).
STUDY_TABLES = (SWEEP_TABLE, "optimise")


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


#: Largest preset read (bytes): bundled presets are a few kB; TOML of 4 MiB parses into
#: about 0.3 GiB of Python values (a preset of 100 MB took over 6 GiB).
MAX_PRESET_BYTES = 4 * 2**20


def read_toml(path: Path | str) -> dict[str, Any]:
    """Parse a TOML file; unreadable files (anything but a regular file, a file larger
    than :data:`MAX_PRESET_BYTES`: neither is read) and syntax errors become
    :class:`PresetError`."""
    path = Path(path)
    try:
        text = read_bounded_text(path, MAX_PRESET_BYTES, "a preset")
    except FileNotFoundError:
        raise PresetError(
            path, "(file)", "no such file", "a preset path or a bundled preset name"
        ) from None
    except (OSError, UnicodeDecodeError) as exc:
        raise PresetError(
            path, "(file)", f"cannot be read: {exc}", "a readable UTF-8 TOML file"
        ) from None
    return parse_toml(path, text)


def parse_toml(path: Path | str, text: str) -> dict[str, Any]:
    """Parse TOML text; every way it can fail is a :class:`PresetError` about ``path``.

    Besides syntax errors, the standard parser raises ``RecursionError`` on arrays or
    inline tables nested hundreds of levels deep and ``ValueError`` on an integer longer
    than Python's integer-parsing limit (4300 digits); both are refused here.
    """
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise PresetError(path, "(syntax)", f"invalid TOML: {exc}", "valid TOML") from None
    except RecursionError:
        raise PresetError(
            path,
            "(syntax)",
            "arrays or tables nested too deeply to read",
            "at most a few levels of nesting",
        ) from None
    except ValueError as exc:  # an integer beyond int()'s digit limit
        raise PresetError(
            path,
            "(syntax)",
            f"a value cannot be read: {str(exc).split(':')[0]}",
            "integers of at most 4300 digits",
        ) from None


def parse_preset(path: Path | str, document: Mapping[str, Any]) -> Preset:
    """Validate a parsed TOML document against the registered robot and job kinds."""
    path = Path(path)
    top_level = list(ROBOT_KINDS) + list(JOB_KINDS) + list(STUDY_TABLES)
    for name, value in document.items():
        if name not in top_level:
            raise PresetError(
                path,
                name,
                "unknown table",
                "one of " + ", ".join(top_level) + suggest(name, top_level),
            )
        if name in ROBOT_KINDS and not isinstance(value, dict):
            raise PresetError(path, name, f"is {type_name(value)}", f"a table [{name}]")
        if name in (*JOB_KINDS, *STUDY_TABLES) and not (
            isinstance(value, dict)
            or (isinstance(value, list) and all(isinstance(v, dict) for v in value))
        ):
            raise PresetError(
                path, name, f"is {type_name(value)}", f"a table [{name}] or tables [[{name}]]"
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
        tables = value if isinstance(value, list) else [value]
        for index, table in enumerate(tables, start=1):
            prefix = f"{kind_name}[{index}]" if isinstance(value, list) else kind_name
            jobs.append(_parse_job_table(path, kind_name, table, prefix, index, robots))
    return Preset(path, robots, tuple(jobs), document)


def _parse_job_table(
    path: Path, kind_name: str, table: Any, prefix: str, index: int, robots: Mapping[str, Any]
) -> Job:
    """One job table (``prefix`` names it in messages) on its own robot or the preset's
    robot of its kind in ``robots``."""
    kind = JOB_KINDS[kind_name]
    reader = TableReader(path, table, prefix, (*kind.keys, "output", kind.robot_kind))
    robot_kind = ROBOT_KINDS[kind.robot_kind]
    if reader.has(kind.robot_kind):
        own = reader.raw(kind.robot_kind)
        if not isinstance(own, dict):
            raise reader.error(kind.robot_kind, f"is {type_name(own)}", "a table")
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
    output = reader.relative_path("output", f"{path.stem}-{kind_name}-{index}.csv")
    return Job(kind_name, index, f"{path.stem}:{prefix}", robot, spec, output, path)


def parse_job(path: Path | str, document: Mapping[str, Any], kind: str, index: int) -> Job:
    """Validate one job of a document, job ``index`` (1-based) of ``kind``, and only what
    it needs: its table and the robot it runs on (its own, or the preset's of its kind).

    A problem elsewhere in the document (another job, a robot this job does not use) does
    not stop it; the messages are :func:`parse_preset`'s.
    """
    path = Path(path)
    value = document.get(kind)
    tables = value if isinstance(value, list) else [value]
    if kind not in JOB_KINDS or value is None or not 1 <= index <= len(tables):
        raise PresetError(path, f"{kind}[{index}]", "no such job", f"a [{kind}] table")
    table = tables[index - 1]
    prefix = f"{kind}[{index}]" if isinstance(value, list) else kind
    if not isinstance(table, dict):
        raise PresetError(path, prefix, f"is {type_name(table)}", f"a table [{kind}]")
    robot_name = JOB_KINDS[kind].robot_kind
    robots = {}
    if robot_name not in table and robot_name in document:
        robot_table = document[robot_name]
        if not isinstance(robot_table, dict):
            raise PresetError(
                path, robot_name, f"is {type_name(robot_table)}", f"a table [{robot_name}]"
            )
        robot_kind = ROBOT_KINDS[robot_name]
        robots[robot_name] = robot_kind.parse(
            TableReader(path, robot_table, robot_name, robot_kind.keys)
        )
    return _parse_job_table(path, kind, table, prefix, index, robots)


def load_preset(path: Path | str) -> Preset:
    """Read, parse and validate a preset file (see :func:`parse_preset`)."""
    return parse_preset(path, read_toml(path))


def copy_bundled_preset(name: str, target: Path) -> Path:
    """Write bundled preset ``name`` to ``target`` to start from; an existing ``target``
    is never overwritten (:class:`PresetError`)."""
    text = bundled_preset(name).read_text(encoding="utf-8")
    try:
        return write_new_text(target, text)
    except FileExistsError:
        raise PresetError(
            "command line",
            "--copy",
            f"{target} exists (it is never overwritten)",
            "a new file name",
        ) from None
    except OSError as error:
        raise PresetError(
            "command line",
            "--copy",
            f"{target} cannot be written: {error.strerror or error}",
            "a writable new file path",
        ) from None

"""Writing presets back to TOML (what the app saves, the CLI runs unchanged).

Every robot kind and job kind registered in :mod:`planar_tui.registry` turns its parsed
settings back into a TOML table (``dump``, from the declared keys); this module assembles those tables
into a preset document and prints it. Scalars are printed by ``tomli_w`` (exact float
round trip); arrays are kept on one line so a saved preset reads like a hand-written one.
Round trip: ``load_preset(dump_preset(load_preset(p)))`` has the same robots and jobs.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import tomli_w

from planar_tui.presets import STUDY_TABLES
from planar_tui.registry import JOB_KINDS, ROBOT_KINDS


def format_value(value: Any) -> str:
    """One TOML value on one line: scalars via ``tomli_w``, arrays ``[a, b]``,
    tables as inline tables ``{k = v}``."""
    if isinstance(value, Mapping):
        inner = ", ".join(f"{_key(k)} = {format_value(v)}" for k, v in value.items())
        return "{" + inner + "}"
    if isinstance(value, list | tuple):
        return "[" + ", ".join(format_value(item) for item in value) + "]"
    if hasattr(value, "item"):  # NumPy scalar
        value = value.item()
    return tomli_w.dumps({"v": value})[4:].rstrip("\n")


def _key(name: str) -> str:
    """A bare key when possible, else a quoted one (through ``tomli_w``)."""
    return tomli_w.dumps({name: 0}).split(" = ")[0]


def _table_lines(header: str, table: Mapping[str, Any]) -> list[str]:
    """``[header]`` then ``key = value`` lines; sub-tables follow as ``[header.key]``."""
    lines = [header]
    nested = []
    for name, value in table.items():
        if isinstance(value, Mapping):
            nested.append((name, value))
        else:
            lines.append(f"{_key(name)} = {format_value(value)}")
    base = header.strip("[]")
    for name, value in nested:
        lines.append("")
        lines.extend(_table_lines(f"[{base}.{_key(name)}]", value))
    return lines


def preset_document(preset: Any) -> dict[str, Any]:
    """The TOML document of a parsed preset (robots first, then jobs in file order).

    A job whose robot differs from the preset's robot of its kind carries its own robot
    table (``[[sensitivity]]`` + ``[sensitivity.robot]``). A kind with several jobs, or
    written as ``[[kind]]`` in the original document, becomes an array of tables.
    """
    document: dict[str, Any] = {
        name: dict(ROBOT_KINDS[name].dump(robot)) for name, robot in preset.robots.items()
    }
    jobs_by_kind: dict[str, list[dict[str, Any]]] = {}
    for job in preset.jobs:
        kind = JOB_KINDS[job.kind]
        table = dict(kind.dump(job.spec))
        table["output"] = job.output
        if preset.robots.get(kind.robot_kind) != job.robot:
            table[kind.robot_kind] = dict(ROBOT_KINDS[kind.robot_kind].dump(job.robot))
        jobs_by_kind.setdefault(job.kind, []).append(table)
    raw = getattr(preset, "raw", {}) or {}
    for name, tables in jobs_by_kind.items():
        as_array = len(tables) > 1 or isinstance(raw.get(name), list)
        document[name] = tables if as_array else tables[0]
    for name in STUDY_TABLES:  # read by planar_tui.sweep and .optimise; kept as written
        if name in raw:
            document[name] = raw[name]
    return document


def dump_document(document: Mapping[str, Any], description: str = "") -> str:
    """Print a preset document as TOML; ``description`` becomes the first comment line."""
    lines = [f"# {line}".rstrip() for line in description.splitlines()] if description else []
    for name, value in document.items():
        tables = value if isinstance(value, list) else [value]
        header = f"[[{_key(name)}]]" if isinstance(value, list) else f"[{_key(name)}]"
        for table in tables:
            if lines:
                lines.append("")
            lines.extend(_table_lines(header, table))
    return "\n".join(lines) + "\n"


def dump_preset(preset: Any, description: str = "") -> str:
    """A parsed :class:`~planar_tui.presets.Preset` as TOML text the CLI can run."""
    return dump_document(preset_document(preset), description)

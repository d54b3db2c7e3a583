"""Key paths of a sweep and how a point's values reach the job's TOML tables.

A key path names one value the sweep varies: a key of the job's own table
(``orientation_deg``), a key of its robot's table prefixed by the robot kind
(``robot.lengths_m``, ``robot3rrr.distal_cm``), optionally followed by list indices
``[k]``, 1-based like the joints (``robot.lengths_m[2]``, ``joint_limits_deg[1][2]``).
Values are written into copies of the raw TOML tables, which the preset loader then
parses, so a point is checked exactly like a preset.
"""

from __future__ import annotations

import copy
import re
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from planar_tui.errors import PresetError
from planar_tui.schema import suggest

_PATH = re.compile(
    r"^(?:(?P<table>[A-Za-z_][A-Za-z0-9_]*)\.)?(?P<key>[A-Za-z_][A-Za-z0-9_]*)"
    r"(?P<indices>(?:\[\d+\])*)$"
)
#: Keys a sweep may not vary: the job's output is the sweep's own business.
NOT_VARIED = ("output",)


@dataclass(frozen=True)
class KeyPath:
    """A parsed key path: ``table`` is ``""`` for the job's own table or the robot kind's
    name; ``indices`` are 1-based list positions."""

    text: str
    table: str
    key: str
    indices: tuple[int, ...] = ()


def overlap_problem(path: KeyPath, seen: Mapping[tuple[Any, ...], str]) -> str | None:
    """Why ``path`` cannot be varied beside the key paths ``seen`` (by ``(table, key,
    indices)``), or ``None``: one names the same value, or a value within the other's
    list (``robot.masses_kg`` and ``robot.masses_kg[1]``: one index list a prefix of the
    other), so a point's values would overwrite each other."""
    for (table, key, indices), text in seen.items():
        shared = min(len(indices), len(path.indices))
        if (table, key) == (path.table, path.key) and indices[:shared] == path.indices[:shared]:
            if indices == path.indices:
                return f"names the same value as {text}"
            return f"overlaps {text}: one names a value within the other"
    return None


def allowed_paths(job_keys: Sequence[str], robot_kind: str, robot_keys: Sequence[str]) -> list[str]:
    """Every key path a sweep of such a job may name (without indices)."""
    own = [key for key in job_keys if key not in NOT_VARIED]
    return own + [f"{robot_kind}.{key}" for key in robot_keys]


def parse_key_path(
    text: str,
    job_keys: Sequence[str],
    robot_kind: str,
    robot_keys: Sequence[str],
    error: Callable[[str, str], PresetError],
) -> KeyPath:
    """``text`` as a :class:`KeyPath`, or ``error(problem, expected)`` for an unknown key
    (with a "did you mean" suggestion) or a malformed path."""
    allowed = allowed_paths(job_keys, robot_kind, robot_keys)
    match = _PATH.match(text)
    if match is None:
        raise error(
            "is not a key path",
            "KEY, KEY[k] or ROBOT.KEY[k] with k >= 1" + suggest(text, allowed),
        )
    table, key = match["table"] or "", match["key"]
    indices = tuple(int(k) for k in re.findall(r"\[(\d+)\]", match["indices"]))
    plain = f"{table}.{key}" if table else key
    if plain not in allowed:
        raise error(
            "unknown key path",
            f"a key of the job or of its {robot_kind}"
            + (suggest(plain, allowed) or f" (one of {', '.join(allowed)})"),
        )
    if any(k < 1 for k in indices):
        raise error("has an index below 1", "list indices [k] counted from 1")
    return KeyPath(text, table, key, indices)


def current_value(path: KeyPath, tables: Mapping[str, Mapping[str, Any]]) -> Any:
    """The value at ``path`` in ``tables`` (``""``: the job's table, else the robot's),
    ``None`` when the key is absent or an index is beyond the list."""
    value: Any = tables[path.table].get(path.key)
    for k in path.indices:
        if not isinstance(value, list) or k > len(value):
            return None
        value = value[k - 1]
    return value


def index_problem(path: KeyPath, base: Any) -> str | None:
    """Why ``path``'s indices do not fit the key's current value ``base``, or ``None``."""
    value = base
    for depth, k in enumerate(path.indices):
        if not isinstance(value, list):
            where = path.key + "".join(f"[{i}]" for i in path.indices[:depth])
            return f"{where} is not a list, so [{k}] names nothing"
        if k > len(value):
            where = path.key + "".join(f"[{i}]" for i in path.indices[:depth])
            return f"index {k} is beyond the {len(value)} items of {where}"
        value = value[k - 1]
    return None


def apply_values(
    tables: Mapping[str, Mapping[str, Any]],
    defaults: Mapping[str, Mapping[str, Any]],
    assignments: Sequence[tuple[KeyPath, Any]],
) -> dict[str, dict[str, Any]]:
    """Copies of ``tables`` (the job's raw table under ``""``, its robot's under the robot
    kind) with every ``(path, value)`` assigned. An indexed key absent from the raw table
    starts from its parsed value in ``defaults`` (e.g. ``theta0_deg``'s zeros)."""
    result = {name: copy.deepcopy(dict(table)) for name, table in tables.items()}
    for path, value in assignments:
        table = result[path.table]
        if not path.indices:
            table[path.key] = copy.deepcopy(value)
            continue
        if path.key not in table:
            table[path.key] = copy.deepcopy(defaults[path.table][path.key])
        target = table[path.key]
        for k in path.indices[:-1]:
            target = target[k - 1]
        target[path.indices[-1] - 1] = copy.deepcopy(value)
    return result

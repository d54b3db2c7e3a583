"""Where a preset problem lives on screen, and its message written for the app's line.

A :class:`~planar_tui.errors.PresetError` names its place by a dotted key
(``workspace.precision_cm``, ``simulate[2].step_s``, ``sensitivity[2].robot.lengths_m``);
:func:`locate` turns it into the table it belongs to and the field inside it, which the
tabs mark (a red border and the message under the field) and ``ctrl+g`` jumps to. No
Textual here.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from planar_tui.errors import PresetError

_KEY = re.compile(r"^(?P<table>[A-Za-z_][\w-]*)(?:\[(?P<index>\d+)\])?(?:\.(?P<rest>.+))?$")
_ITEM = re.compile(r"\bitem (\d+)\b")


@dataclass(frozen=True)
class Location:
    """A problem's place: ``table`` (a robot or job kind) and its 0-based ``index``;
    ``robot`` is the robot kind when the key is inside a job's own robot table; ``field``
    is the key inside the (robot) table (``""`` for the table itself) and ``item`` the
    1-based list item the message names, if any."""

    table: str
    index: int
    field: str
    robot: str = ""
    item: int | None = None


def locate(error: PresetError, robot_kinds: tuple[str, ...]) -> Location | None:
    """The place of ``error`` in the document; ``None`` for ``(file)``, ``(syntax)`` and
    other keys that name no table."""
    match = _KEY.match(error.key)
    if match is None:
        return None
    index = int(match["index"]) - 1 if match["index"] else 0
    rest = (match["rest"] or "").split(".")
    robot = ""
    if match["table"] not in robot_kinds and rest[0] in robot_kinds:
        robot, rest = rest[0], rest[1:]
    field = rest[0].split("[", 1)[0] if rest else ""
    item = _ITEM.search(error.problem)
    return Location(match["table"], index, field, robot, int(item[1]) if item else None)


def reason(error: PresetError) -> str:
    """The problem without the file: ``key: problem (expected …)``."""
    text = f"{error.key}: {error.problem}"
    return f"{text} (expected {error.expected})" if error.expected else text


def status_line(problems: list[PresetError], preset_name: str) -> str:
    """The app's validation line: the first problem, reason first, the preset by name, the
    count of further problems and the key that jumps to them."""
    first = f"error: {reason(problems[0])} · {preset_name}"
    more = len(problems) - 1
    return first + (f" · {more} more" if more else "") + " · ctrl+g: go to it"

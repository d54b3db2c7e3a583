"""The workbench's undo stack and per-link resizing (plain data, no Textual here)."""

from __future__ import annotations

import copy
import time
from collections.abc import Hashable, Mapping
from typing import Any

from planar_tui.registry import JOB_KINDS
from planar_tui.schema import per_link_keys

#: Edits of the same table within this many seconds of the last are one undo step
#: (typing a number into a field is one step, not one per key).
COALESCE_S = 1.5

#: Undo steps kept.
MAX_STEPS = 200


class EditHistory:
    """Document states before each edit, newest last (undo pops one)."""

    def __init__(self) -> None:
        self.states: list[dict[str, Any]] = []
        self._last_group: Hashable = None
        self._last_time_s = 0.0

    def record(self, document: Mapping[str, Any], group: Hashable) -> None:
        """Remember ``document`` as it is before an edit of ``group`` (a table); a further
        edit of the same group right after the last is folded into the same step."""
        now = time.monotonic()
        same_step = group == self._last_group and now - self._last_time_s < COALESCE_S
        self._last_group, self._last_time_s = group, now
        if same_step and self.states:
            return
        try:
            self.states.append(copy.deepcopy(dict(document)))
        except RecursionError:  # a value nested too deep to copy: this step is not kept
            return
        del self.states[:-MAX_STEPS]

    def pop(self) -> dict[str, Any] | None:
        """The state before the latest edit, or ``None`` when there is nothing to undo."""
        self._last_group = None
        return self.states.pop() if self.states else None

    def __len__(self) -> int:
        return len(self.states)


def link_count(robot: Any) -> int | None:
    """The number of links of a ``[robot]`` table (its ``lengths_m``), if it is a list."""
    lengths = robot.get("lengths_m") if isinstance(robot, Mapping) else None
    return len(lengths) if isinstance(lengths, list) else None


def resized(values: list[Any], n: int) -> list[Any]:
    """``values`` cut or padded with zeros to ``n`` items."""
    return list(values[:n]) + [0.0] * max(0, n - len(values))


def resize_per_link(table: dict[str, Any], kind: str, n: int) -> list[str]:
    """Resize the per-link arrays of a ``kind`` job table (the keys its settings declare
    per link, :func:`planar_tui.schema.per_link_keys`) to ``n`` links in place (new links
    get zeros); the keys changed."""
    changed = []
    for key, shape in per_link_keys(JOB_KINDS[kind].settings).items():
        value = table.get(key)
        if not isinstance(value, list):
            continue  # absent (the default fits any robot) or a word ("singular")
        if shape == "rows":
            new = [resized(row, n) if isinstance(row, list) else row for row in value]
        else:
            new = resized(value, n)
        if new != value:
            table[key] = new
            changed.append(key)
    return changed

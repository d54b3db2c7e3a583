"""Figs 5/6 in the terminal, shared by the CLI and the Textual app.

:func:`sensitivity_bars`: one stacked 100 % bar per torque and speed, drawn with block
characters; each parameter has its own glyph (readable without colour) and colour,
explained by a legend. (The index tables are :mod:`planar_tui.sensitivity.tables`.)
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from rich.columns import Columns
from rich.console import Group
from rich.text import Text

GLYPHS = "█▓▒░▚▞▙▟▛▜▀▄"
COLOURS = (
    "red",
    "green",
    "blue",
    "yellow",
    "magenta",
    "cyan",
    "bright_red",
    "bright_green",
    "bright_blue",
    "bright_yellow",
    "bright_magenta",
    "bright_cyan",
)


def _segment_widths(percent: Sequence[float], width: int) -> list[int]:
    """Integer cell counts summing to ``width`` (largest-remainder rounding)."""
    total = sum(percent) or 1.0
    exact = [p * width / total for p in percent]
    cells = [math.floor(e) for e in exact]
    order = sorted(range(len(exact)), key=lambda k: cells[k] - exact[k])
    for k in order[: width - sum(cells)]:
        cells[k] += 1
    return cells


def sensitivity_bars(analyses, method: str = "sobol", width: int = 50) -> Group:
    """Fig 5/6: a stacked 100 % bar per torque and speed for ``method``."""
    chosen = [a for a in analyses if a.method == method] or list(analyses)
    names = chosen[0].names
    lines = []
    for torque in range(chosen[0].percent.shape[0]):
        for a in chosen:
            bar = Text(f"τ{torque + 1} {a.speed_rad_s:4.2f} rad/s ")
            for j, cells in enumerate(_segment_widths(list(a.percent[torque]), width)):
                bar.append(GLYPHS[j % len(GLYPHS)] * cells, style=COLOURS[j % len(COLOURS)])
            lines.append(bar)
    # one unbreakable entry per parameter, so a narrow terminal wraps between entries
    entries = [Text("legend:")]
    for j, name in enumerate(names):
        entry = Text(GLYPHS[j % len(GLYPHS)] * 2, style=COLOURS[j % len(COLOURS)])
        entry.append(f" {name}")
        entries.append(entry)
    legend = Columns(entries, padding=(0, 2))
    title = Text(f"{method} sensitivity percent, stacked to 100 % ({chosen[0].posture})")
    return Group(title, *lines, legend)

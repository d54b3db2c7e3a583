"""Terminal views of sensitivity results, shared by the CLI and the Textual app.

* :func:`sensitivity_table`: shaped like paper A's Table 4 — rows torque × posture,
  columns l1…ln, m1…mn, cells "Sobol' (eFAST)" percentages.
* :func:`sensitivity_bars`: Figs 5/6 — one stacked 100 % bar per torque and speed, drawn
  with block characters; each parameter has its own glyph (readable without colour) and
  colour, explained by a legend.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from rich.columns import Columns
from rich.console import Group
from rich.table import Table
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


def _cell(values: dict[str, float], methods: Sequence[str]) -> str:
    shown = [f"{values[m]:.2f}" for m in methods if m in values]
    if len(shown) == 2:
        return f"{shown[0]} ({shown[1]})"
    return shown[0] if shown else "-"


def sensitivity_table(analyses, speed_rad_s: float | None = None, title: str = "") -> Table:
    """Table-4-shaped percentages of ``analyses`` (from one robot; several postures allowed)
    at ``speed_rad_s`` (default: the first speed present)."""
    if speed_rad_s is None:
        speed_rad_s = analyses[0].speed_rad_s
    chosen = [a for a in analyses if a.speed_rad_s == speed_rad_s]
    methods = list(dict.fromkeys(a.method for a in chosen))
    names = chosen[0].names
    heading = " (".join(m.replace("sobol", "Sobol'").replace("efast", "eFAST") for m in methods)
    table = Table(
        title=title
        or f"sensitivity percent, {heading}{')' if len(methods) == 2 else ''}, "
        f"speed {speed_rad_s:g} rad/s",
        title_justify="left",
    )
    table.add_column("torque")
    table.add_column("posture")
    for name in names:
        table.add_column(name, justify="right")
    postures = list(dict.fromkeys(a.posture for a in chosen))
    for torque in range(chosen[0].percent.shape[0]):
        for posture in postures:
            here = [a for a in chosen if a.posture == posture]
            cells = [
                _cell({a.method: float(a.percent[torque, j]) for a in here}, methods)
                for j in range(len(names))
            ]
            table.add_row(f"τ{torque + 1}", posture, *cells)
    return table


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


def show_sensitivity(job, result, console) -> None:
    """The CLI view of one job: its Table-4-shaped table, and bars when speeds are swept."""
    analyses = result.data["analyses"]
    console.print(sensitivity_table(analyses, title=f"{result.data['robot']}: {job.label}"))
    if len({a.speed_rad_s for a in analyses}) > 1:
        console.print(sensitivity_bars(analyses, analyses[0].method))

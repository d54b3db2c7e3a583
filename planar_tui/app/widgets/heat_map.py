"""A character-cell heat map: a figure over a grid of two varied keys, in shades.

Each cell of the grid (a value of the first key across, of the second key down, the
largest at the top as on a plot) is drawn as ``cell_width`` copies of one shade of
:data:`SHADES`, the level of value ``v`` being ``round((v - lo) / (hi - lo) · (L - 1))``
for ``L`` shades over the grid's finite range ``[lo, hi]`` (all cells the middle shade
when ``hi == lo``). A cell with no value (a failed point, or a combination the sweep did
not run) is drawn as :data:`MISSING`. Plain text, so it reads the same in any terminal
and in 16 colours.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

#: Shades from the smallest value to the largest (6 levels).
SHADES = " ·░▒▓█"
#: A cell without a value (failed point or combination not run).
MISSING = "×"


def shade_level(value: float, lo: float, hi: float, levels: int = len(SHADES)) -> int:
    """The shade index of ``value`` on ``[lo, hi]`` (0 … ``levels - 1``)."""
    if hi <= lo:
        return (levels - 1) // 2
    fraction = (value - lo) / (hi - lo)
    return min(levels - 1, max(0, round(fraction * (levels - 1))))


def _label(value: float) -> str:
    return f"{value:.4g}"


def heat_map_lines(
    across: Sequence[float],
    down: Sequence[float],
    grid: Sequence[Sequence[float | None]],
    *,
    across_name: str,
    down_name: str,
    figure_name: str,
    width: int = 80,
) -> list[str]:
    """The heat map as lines of text.

    ``grid[j][i]`` is the figure at ``across[i]`` and ``down[j]`` (``None`` or NaN: no
    value). The first lines name the figure and its range with the shade ramp; then one
    line per value of ``down`` (largest first) with its label, the cells, and last the
    labels of ``across`` (first and last) under the cells.
    """
    finite = [float(v) for row in grid for v in row if v is not None and math.isfinite(float(v))]
    lo, hi = (min(finite), max(finite)) if finite else (0.0, 0.0)
    labels = [_label(value) for value in down]
    label_width = max([len(text) for text in labels] + [len(down_name)])
    room = max(len(across), width - label_width - 3)
    cell_width = max(1, min(6, room // max(1, len(across))))
    ramp = " ".join(f"{shade}" for shade in SHADES)
    lines = [
        f"{figure_name}: {_label(lo)} [{ramp}] {_label(hi)}   {MISSING} no value",
        f"{down_name:>{label_width}} ↑",
    ]
    for j in reversed(range(len(down))):
        cells = []
        for i in range(len(across)):
            value = grid[j][i]
            if value is None or not math.isfinite(float(value)):
                cells.append(MISSING * cell_width)
            else:
                cells.append(SHADES[shade_level(float(value), lo, hi)] * cell_width)
        lines.append(f"{labels[j]:>{label_width}} │{''.join(cells)}│")
    span = cell_width * len(across)
    first, last = (_label(across[0]), _label(across[-1])) if len(across) else ("", "")
    ticks = first + last.rjust(max(1, span - len(first)))
    lines.append(f"{'':>{label_width}}  {ticks}")
    lines.append(f"{'':>{label_width}}  {across_name} →")
    return lines

"""A braille canvas: 2 × 4 dots per terminal cell (Unicode U+2800 … U+28FF), pure Python.

Dot ``(x, y)`` (x to the right, y downwards, both from 0) lies in cell
``(x // 2, y // 4)``; within a cell the Unicode braille pattern numbers its dots

    1 4
    2 5
    3 6
    7 8

and the character is ``chr(0x2800 + Σ 2^(k-1))`` over the raised dots ``k``. A terminal
cell is about twice as tall as wide, so a dot is about square and a line keeps its
slope. Lines are rasterised with Bresenham's integer algorithm. A cell may instead hold a
*glyph* (a joint's ``o``, a label) that hides its dots. Each cell keeps the style of the
last thing drawn in it (a rich style string), so the canvas reads as plain text (every
glyph distinct) and in colour.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

#: ``DOT_BITS[y][x]``: the bit of the dot at ``(x, y)`` inside its cell.
DOT_BITS = ((0x01, 0x08), (0x02, 0x10), (0x04, 0x20), (0x40, 0x80))
BRAILLE_BLANK = 0x2800


def bresenham(x0: int, y0: int, x1: int, y1: int) -> list[tuple[int, int]]:
    """The dots of the segment from ``(x0, y0)`` to ``(x1, y1)``, both ends included
    (Bresenham, all octants: the error term ``e = dx + dy`` with ``dy ≤ 0``)."""
    dx, dy = abs(x1 - x0), -abs(y1 - y0)
    sx, sy = (1 if x0 < x1 else -1), (1 if y0 < y1 else -1)
    error = dx + dy
    points = []
    while True:
        points.append((x0, y0))
        if x0 == x1 and y0 == y1:
            return points
        double = 2 * error
        if double >= dy:
            error += dy
            x0 += sx
        if double <= dx:
            error += dx
            y0 += sy


class Canvas:
    """``columns × rows`` cells of braille dots, glyphs and styles."""

    def __init__(self, columns: int, rows: int):
        self.columns, self.rows = max(1, columns), max(1, rows)
        self.bits = [[0] * self.columns for _ in range(self.rows)]
        self.styles = [[""] * self.columns for _ in range(self.rows)]
        self.glyphs: dict[tuple[int, int], str] = {}

    @property
    def width_dots(self) -> int:
        return 2 * self.columns

    @property
    def height_dots(self) -> int:
        return 4 * self.rows

    def dot(self, x: int, y: int, style: str = "") -> None:
        """Raise dot ``(x, y)`` (ignored outside the canvas)."""
        if 0 <= x < self.width_dots and 0 <= y < self.height_dots:
            column, row = x // 2, y // 4
            self.bits[row][column] |= DOT_BITS[y % 4][x % 2]
            if (column, row) not in self.glyphs:
                self.styles[row][column] = style

    def line(self, x0: int, y0: int, x1: int, y1: int, style: str = "") -> None:
        """A straight line of dots (clipped to the canvas)."""
        for x, y in bresenham(x0, y0, x1, y1):
            self.dot(x, y, style)

    def glyph(self, column: int, row: int, char: str, style: str = "") -> None:
        """Put ``char`` in a cell (it hides the cell's dots)."""
        if 0 <= column < self.columns and 0 <= row < self.rows:
            self.glyphs[(column, row)] = char
            self.styles[row][column] = style

    def text(self, column: int, row: int, text: str, style: str = "") -> None:
        """Write ``text`` from a cell rightwards (cut at the edge)."""
        for offset, char in enumerate(text):
            self.glyph(column + offset, row, char, style)

    def char(self, column: int, row: int) -> str:
        """The character of a cell: its glyph, else its braille pattern (blank: a space)."""
        glyph = self.glyphs.get((column, row))
        if glyph is not None:
            return glyph
        bits = self.bits[row][column]
        return chr(BRAILLE_BLANK + bits) if bits else " "

    def lines(self) -> list[str]:
        """The canvas as plain text, one string per row (trailing blanks kept)."""
        return ["".join(self.char(c, r) for c in range(self.columns)) for r in range(self.rows)]

    def to_text(self):
        """The canvas as a rich ``Text`` with each cell's style."""
        from rich.text import Text

        text = Text(no_wrap=True, overflow="crop")
        for row in range(self.rows):
            if row:
                text.append("\n")
            for column in range(self.columns):
                text.append(self.char(column, row), self.styles[row][column] or None)
        return text


@dataclass(frozen=True)
class Viewport:
    """A uniform map from the plane (y up) to a canvas's dots (y down): the extent
    ``(x_lo, x_hi, y_lo, y_hi)`` fitted into ``W × H`` dots and centred,
    ``dot = (⌊W/2 + (x - x_mid)·s⌋, ⌊H/2 - (y - y_mid)·s⌋)`` with
    ``s = min((W - 1)/(x_hi - x_lo), (H - 1)/(y_hi - y_lo))`` dots per unit (so the extent's
    corners fall on the first and last dots)."""

    x_mid: float
    y_mid: float
    scale: float
    width_dots: int
    height_dots: int

    @classmethod
    def fit(
        cls, extent: tuple[float, float, float, float], width_dots: int, height_dots: int
    ) -> Viewport:
        x_lo, x_hi, y_lo, y_hi = extent
        span_x = max(x_hi - x_lo, 1e-12)
        span_y = max(y_hi - y_lo, 1e-12)
        scale = min((width_dots - 1) / span_x, (height_dots - 1) / span_y)
        return cls(0.5 * (x_lo + x_hi), 0.5 * (y_lo + y_hi), scale, width_dots, height_dots)

    def to_dot(self, x: float, y: float) -> tuple[int, int]:
        """The dot of the point ``(x, y)``."""
        return (
            math.floor(self.width_dots / 2 + (x - self.x_mid) * self.scale),
            math.floor(self.height_dots / 2 - (y - self.y_mid) * self.scale),
        )

    def to_point(self, x_dot: float, y_dot: float) -> tuple[float, float]:
        """The centre of dot ``(x_dot, y_dot)`` in the plane (:meth:`to_dot` inverted)."""
        return (
            self.x_mid + (x_dot + 0.5 - self.width_dots / 2) / self.scale,
            self.y_mid - (y_dot + 0.5 - self.height_dots / 2) / self.scale,
        )


def nice_length(most: float) -> float:
    """The largest 1-2-5 × 10^k length not above ``most`` (> 0)."""
    if most <= 0 or not math.isfinite(most):
        return 0.0
    power = 10.0 ** math.floor(math.log10(most))
    for factor in (5.0, 2.0, 1.0):
        if factor * power <= most * (1 + 1e-12):
            return factor * power
    return power

"""The screen as plain text, read back from Textual's public SVG screenshot.

Textual exposes what is on screen only through :meth:`textual.app.App.export_screenshot`
(an SVG written by :meth:`rich.console.Console.export_svg`). That SVG places each run of
text as a ``<text>`` element at ``x = column × cell width`` and clips it to its line
(``clip-path="url(#…-line-ROW)"``), with spaces written as ``&#160;``; a run of blanks
has no element, and Textual's line breaks appear as runs of ``\n`` past the last column. :func:`svg_screen_text` puts every run back at its row and column, so
the text is the screen's, cell for cell (dialogs over a dimmed screen included).
"""

from __future__ import annotations

import html
import re

#: One run of text: its x (in SVG units), its line number and its escaped text.
TEXT_RUN = re.compile(
    r'<text class="[^"]*" x="(?P<x>[0-9.e+-]+)" y="[^"]*" textLength="[^"]*" '
    r'clip-path="url\(#[^")]*-line-(?P<row>\d+)\)">(?P<text>[^<]*)</text>'
)
#: The first line's clip rectangle: its width is the screen's width in SVG units.
CLIP_RECT = re.compile(r'<clipPath id="[^"]*-line-0">\s*<rect x="0" y="[^"]*" width="([0-9.]+)"')


def svg_screen_text(svg: str, width: int, height: int) -> str:
    """The ``width`` × ``height`` screen drawn in ``svg`` as text, one line per row (each
    padded to ``width`` cells)."""
    from rich.cells import cell_len

    clip = CLIP_RECT.search(svg)
    cell_width = float(clip.group(1)) / width if clip else 20 * 0.61  # Rich's default
    rows: list[list[tuple[int, str]]] = [[] for _ in range(height)]
    for run in TEXT_RUN.finditer(svg):
        row = int(run["row"])
        if row < height:
            text = html.unescape(run["text"]).replace("\xa0", " ").replace("\n", "")
            rows[row].append((round(float(run["x"]) / cell_width), text))
    lines = []
    for runs in rows:
        line, column = [], 0
        for start, text in sorted(runs):
            if start > column:
                line.append(" " * (start - column))
                column = start
            line.append(text)
            column += cell_len(text)
        line.append(" " * max(0, width - column))
        lines.append("".join(line))
    return "\n".join(lines)

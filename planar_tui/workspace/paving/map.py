"""Character-cell map of a workspace: one glyph per terminal cell, readable without colour.

:func:`render_map` is shared: the CLI prints it (``planar_tui.workspace.rrr.job``'s view) and
the Textual app shows it in a ``Static``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

INSIDE_GLYPH = "█"
BOUNDARY_GLYPH = "▒"
OUTSIDE_GLYPH = " "
LEGEND = f"{INSIDE_GLYPH} inside (proved)  {BOUNDARY_GLYPH} boundary (kept)  blank: outside"
SINGULAR_GLYPH = "×"
CIRCLE_GLYPH = "o"
CENTRE_GLYPH = "+"
#: The overlays' legend, item by item (``render_map`` wraps it to the map's width).
SINGULAR_LEGEND_ITEMS = (
    f"{SINGULAR_GLYPH} may be type II singular",
    f"{CIRCLE_GLYPH} singularity-free circle (r_in)",
    f"{CENTRE_GLYPH} its centre",
)
#: Terminal cells are about twice as tall as wide.
CELL_ASPECT = 2.0
_LABEL_WIDTH = 8  # "-123.45 " then the axis line


def _nice_step(span: float, target_ticks: int) -> float:
    raw = span / max(target_ticks, 1)
    magnitude = 10.0 ** math.floor(math.log10(raw)) if raw > 0 else 1.0
    for factor in (1.0, 2.0, 5.0, 10.0):
        if factor * magnitude >= raw:
            return factor * magnitude
    return 10.0 * magnitude


def _axis_step(lo: float, hi: float, target_ticks: int, most_ticks: int) -> float:
    """A 1-2-5 tick step giving about ``target_ticks`` labels on ``[lo, hi]`` and never fewer
    than two (up to ``most_ticks``, the labels that fit), so every axis shows a scale."""
    target = max(2, target_ticks)
    while True:
        step = _nice_step(hi - lo, target)
        ticks = math.floor(hi / step) - math.ceil(lo / step) + 1
        if ticks >= 2 or target >= most_ticks:
            return step
        target += 1


def _label(value: float, step: float) -> str:
    decimals = max(0, -math.floor(math.log10(step))) if step > 0 else 0
    return f"{value:.{decimals}f}"


def _overlaps(lo, hi, origin, cell):
    """For intervals no wider than a cell: first cell index, overlap with it, and overlap
    with the next cell (0 when the interval ends in its first cell)."""
    first = np.floor((lo - origin) / cell).astype(np.int64)
    split = origin + (first + 1) * cell
    head = np.minimum(hi, split) - lo
    tail = np.where(hi > split, hi - split, 0.0)
    return first, head, tail


def _coverage(boxes, status, extent, columns, rows):
    """Fraction of each cell covered by inside boxes (layer 0) and boundary boxes (layer 1).

    Boxes smaller than a cell (the usual case) are spread over at most 2 x 2 cells in one
    vectorised pass; larger ones are clipped cell by cell.
    """
    xlo, xhi, ylo, yhi = extent
    cw = (xhi - xlo) / columns
    ch = (yhi - ylo) / rows
    cover = np.zeros((2, rows + 2, columns + 2))  # one guard cell on each side
    layer = np.where(status == 2, 0, 1)
    small = ((boxes[:, 1] - boxes[:, 0]) <= cw) & ((boxes[:, 3] - boxes[:, 2]) <= ch)
    b = boxes[small]
    i, xhead, xtail = _overlaps(b[:, 0], b[:, 1], xlo, cw)
    j, yhead, ytail = _overlaps(b[:, 2], b[:, 3], ylo, ch)
    for di, ox in ((0, xhead), (1, xtail)):
        for dj, oy in ((0, yhead), (1, ytail)):
            ii = np.clip(i + di, -1, columns) + 1
            jj = np.clip(j + dj, -1, rows) + 1
            np.add.at(cover, (layer[small], jj, ii), ox * oy)
    for (bx0, bx1, by0, by1), lay in zip(boxes[~small], layer[~small], strict=True):
        i0 = max(0, int((bx0 - xlo) // cw))
        i1 = min(columns - 1, int((bx1 - xlo) // cw))
        j0 = max(0, int((by0 - ylo) // ch))
        j1 = min(rows - 1, int((by1 - ylo) // ch))
        for ci in range(i0, i1 + 1):
            ox = min(bx1, xlo + (ci + 1) * cw) - max(bx0, xlo + ci * cw)
            for cj in range(j0, j1 + 1):
                oy = min(by1, ylo + (cj + 1) * ch) - max(by0, ylo + cj * ch)
                if ox > 0 and oy > 0:
                    cover[lay, cj + 1, ci + 1] += ox * oy
    return cover[:, 1:-1, 1:-1] / (cw * ch)


def fit_extent(boxes: np.ndarray, fallback: tuple[float, float, float, float]):
    """The kept boxes' bounding box grown by 5 % (``fallback`` when there are none)."""
    if len(boxes) == 0:
        return fallback
    xlo, xhi = float(boxes[:, 0].min()), float(boxes[:, 1].max())
    ylo, yhi = float(boxes[:, 2].min()), float(boxes[:, 3].max())
    pad = 0.05 * max(xhi - xlo, yhi - ylo)
    return (xlo - pad, xhi + pad, ylo - pad, yhi + pad)


def render_map(
    boxes: np.ndarray,
    status: np.ndarray,
    extent: tuple[float, float, float, float] | None = None,
    width: int = 80,
    height: int | None = None,
    singular: np.ndarray | None = None,
    circle: tuple[float, float, float] | None = None,
    layers: Sequence[tuple[np.ndarray, str, str]] = (),
) -> list[str]:
    """The workspace as lines of text, at most ``width`` columns.

    Parameters
    ----------
    boxes, status
        Rows ``x_lo, x_hi, y_lo, y_hi`` (cm) and their status (2 inside, 1 boundary).
    extent
        ``(x_lo, x_hi, y_lo, y_hi)`` shown, in cm; default: the boxes' bounding box + 5 %.
    width, height
        Size in terminal cells, axes and legend included; ``height`` defaults to an
        aspect-true map (a cell is twice as tall as wide) of at most 40 plot rows.

    singular, circle
        Optional overlays: boxes that may hold a type II singularity (``×`` on every cell
        they touch) and a circle ``(x, y, r)`` in cm (``o`` on the cells it crosses, ``+``
        at its centre), with their legend below, wrapped to ``width``.
    layers
        More workspaces ``(boxes, glyph, legend)`` (a tolerance-certified job's nominal and
        "some" workspaces): a blank cell that a layer's boxes touch shows its glyph (the
        first such layer's), with the legends below; the extent covers them too.

    A cell fully covered by inside boxes shows ``█``, any other covered cell ``▒``, an
    empty cell a blank; the y axis is labelled on the left, the x axis below, in cm.
    """
    boxes = np.asarray(boxes, dtype=np.float64).reshape(-1, 4)
    status = np.asarray(status).reshape(-1)
    if extent is None:
        everything = np.concatenate([boxes, *(np.reshape(b, (-1, 4)) for b, _, _ in layers)])
        extent = fit_extent(everything, (0.0, 1.0, 0.0, 1.0))
    xlo, xhi, ylo, yhi = extent
    columns = max(10, width - _LABEL_WIDTH - 1)
    if height is None:
        rows = round(columns * (yhi - ylo) / (xhi - xlo) / CELL_ASPECT)
        rows = int(min(40, max(5, rows)))
    else:
        rows = max(3, height - 3)
    cover = _coverage(boxes, status, extent, columns, rows)
    marks = _marks(extent, columns, rows, singular, circle)
    for layer_boxes, glyph, _ in layers:  # the first layer's glyph wins
        b = np.asarray(layer_boxes, dtype=np.float64).reshape(-1, 4)
        touched = _coverage(b, np.ones(len(b)), extent, columns, rows)[1] > 1e-12
        empty = cover[0] + cover[1] <= 1e-12
        for j, i in zip(*np.nonzero(touched & empty), strict=True):
            marks[j][i] = marks[j][i] or glyph
    lines = []
    ystep = _axis_step(ylo, yhi, rows // 4, rows)
    ch = (yhi - ylo) / rows
    labelled = set()
    for j in range(rows - 1, -1, -1):
        y_top = ylo + (j + 1) * ch
        tick = math.floor(y_top / ystep) * ystep
        label = ""
        if tick >= ylo + j * ch and tick not in labelled:
            labelled.add(tick)
            label = _label(tick, ystep)
        cells = []
        for i in range(columns):
            inside, boundary = cover[0, j, i], cover[1, j, i]
            if marks[j][i]:
                cells.append(marks[j][i])
            elif inside >= 1.0 - 1e-9:
                cells.append(INSIDE_GLYPH)
            elif inside + boundary > 1e-12:
                cells.append(BOUNDARY_GLYPH)
            else:
                cells.append(OUTSIDE_GLYPH)
        lines.append(f"{label:>{_LABEL_WIDTH - 1}} ┤" + "".join(cells))
    axis = [" "] * columns
    ticks = [" "] * (columns + _LABEL_WIDTH + 8)
    xstep = _axis_step(xlo, xhi, columns // 12, columns // 6)
    value = math.ceil(xlo / xstep) * xstep
    last_end = -1
    while value <= xhi:
        i = int((value - xlo) / (xhi - xlo) * columns)
        if 0 <= i < columns:
            axis[i] = "┬"
            text = _label(value, xstep)
            start = _LABEL_WIDTH + i - len(text) // 2
            if start > last_end and start + len(text) <= width:
                ticks[start : start + len(text)] = list(text)
                last_end = start + len(text)
        value += xstep
    lines.append(" " * (_LABEL_WIDTH - 1) + " └" + "".join(axis)[: columns - 1])
    lines.append("".join(ticks).rstrip()[:width])
    lines.append(f"{'x (cm) →, y (cm) ↑':>{_LABEL_WIDTH + 18}}  {LEGEND}")
    if singular is not None or circle is not None:
        lines += _wrapped(SINGULAR_LEGEND_ITEMS, _LABEL_WIDTH + 20, width)
    if layers:
        lines += _wrapped([f"{g} {text}" for _, g, text in layers], _LABEL_WIDTH + 20, width)
    return [line[:width] for line in lines]


def _wrapped(items, indent: int, width: int) -> list[str]:
    """``items`` two spaces apart on lines of at most ``width`` columns, indented by
    ``indent`` (less where a line would not fit)."""
    texts: list[str] = []
    for item in items:
        if texts and indent + len(texts[-1]) + 2 + len(item) <= width:
            texts[-1] += "  " + item
        else:
            texts.append(item)
    return [" " * min(indent, max(0, width - len(text))) + text for text in texts]


def _marks(extent, columns, rows, singular, circle) -> list[list[str]]:
    """Overlay glyphs per cell (``""`` for none): singular boxes, then the circle's cells
    (the circle passes between the cell's nearest and farthest points) and its centre."""
    marks = [[""] * columns for _ in range(rows)]
    xlo, xhi, ylo, yhi = extent
    cw, ch = (xhi - xlo) / columns, (yhi - ylo) / rows
    if singular is not None and len(singular):
        boxes = np.asarray(singular, dtype=np.float64).reshape(-1, 4)
        i0 = np.clip(np.floor((boxes[:, 0] - xlo) / cw), 0, columns - 1).astype(int)
        i1 = np.clip(np.ceil((boxes[:, 1] - xlo) / cw) - 1, 0, columns - 1).astype(int)
        j0 = np.clip(np.floor((boxes[:, 2] - ylo) / ch), 0, rows - 1).astype(int)
        j1 = np.clip(np.ceil((boxes[:, 3] - ylo) / ch) - 1, 0, rows - 1).astype(int)
        inside = (
            (boxes[:, 1] > xlo) & (boxes[:, 0] < xhi) & (boxes[:, 3] > ylo) & (boxes[:, 2] < yhi)
        )
        for a, b, c, d in zip(i0[inside], i1[inside], j0[inside], j1[inside], strict=True):
            for j in range(c, max(c, d) + 1):
                for i in range(a, max(a, b) + 1):
                    marks[j][i] = SINGULAR_GLYPH
    if circle is not None:
        cx, cy, radius = circle
        for j in range(rows):
            y0, y1 = ylo + j * ch, ylo + (j + 1) * ch
            dy_near = max(y0 - cy, 0.0, cy - y1)
            dy_far = max(abs(y0 - cy), abs(y1 - cy))
            for i in range(columns):
                x0, x1 = xlo + i * cw, xlo + (i + 1) * cw
                near = math.hypot(max(x0 - cx, 0.0, cx - x1), dy_near)
                far = math.hypot(max(abs(x0 - cx), abs(x1 - cx)), dy_far)
                if x0 <= cx < x1 and y0 <= cy < y1:
                    marks[j][i] = CENTRE_GLYPH
                elif near <= radius <= far and not marks[j][i]:
                    marks[j][i] = CIRCLE_GLYPH
    return marks

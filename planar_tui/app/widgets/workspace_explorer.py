"""The workspace map, explorable: a cursor, zoom and pan over the CLI's character-cell map
(:func:`planar_tui.workspace.paving.map.render_map`), the cell's status and the legs' joint
angles read out at the cursor, the exact boundary and the circle's working mode overlaid.

The view is aspect-true (a cell is twice as tall as wide): :attr:`MapExplorer.cell_cm` cm
per column and twice that per row, centred on :attr:`MapExplorer.centre_cm`. Keys (when
the map has the focus): arrows move the cursor one cell, shift+arrows pan a quarter of
the view, ``+``/``-`` zoom in/out about the cursor, ``0`` fits the map again, ``b`` shows
the exact boundary, ``m`` the circle's working-mode region, ``k`` the κ map of a job with
``kappa_max`` (each cell the band of the worst certified κ upper bound of the dexterity
boxes over it, :mod:`planar_tui.workspace.paving.kappa_map`, drawn over the boxes), ``a`` the
error map of a job with ``accuracy`` (each cell the band of the worst certified
:math:`\\max(|\\Delta x|, |\\Delta y|)` of the accuracy boxes over it, ``?`` where one is not
certified, :func:`planar_tui.workspace.paving.accuracy.error_glyph`), ``r`` paves the visible region
again at a finer precision (in a worker; ``r`` again or any zoom cancels it).
"""

from __future__ import annotations

import itertools
import math
from typing import Any, ClassVar

import numpy as np
from rich.text import Text
from textual.binding import Binding
from textual.message import Message
from textual.widget import Widget

from planar_tui.workspace.paving import accuracy as accuracy_map
from planar_tui.workspace.paving import kappa_map
from planar_tui.workspace.paving.map import (
    BOUNDARY_GLYPH,
    OUTSIDE_GLYPH,
    SINGULAR_LEGEND_ITEMS,
    fit_extent,
    render_map,
)

#: Cells of ``render_map``'s y labels and axis before the first map column.
LABEL_CELLS = 9
#: Lines of ``render_map`` below the map rows kept (the x axis and its labels).
AXIS_LINES = 2
CURSOR_GLYPH = "@"
EXACT_GLYPH = "·"
OTHER_MODE_GLYPH = "░"
#: The explorer's legend items (wrapped to the pane; each fits 80 columns).
LEGEND_ITEMS = (
    "x, y in cm",
    "█ inside (proved)",
    "▒ boundary (kept)",
    "blank outside",
    f"{CURSOR_GLYPH} cursor",
)
EXACT_ITEM = f"{EXACT_GLYPH} exact boundary"
MODE_ITEM = f"{OTHER_MODE_GLYPH} not in the circle's working mode"
KAPPA_ITEM = "k: κ map"
ACCURACY_ITEM = "a: error map"


def cell_status(point: tuple[float, float], boxes, status, singular=None) -> str:
    """``inside``, ``boundary``, ``outside`` or ``singular`` at ``point``: ``singular``
    when a box that may hold a type II singularity contains it, else ``inside`` when a
    proved box (status 2) contains it, ``boundary`` when a kept one does, else ``outside``."""
    x, y = point

    def containing(rows) -> np.ndarray:
        rows = np.asarray(rows, dtype=np.float64).reshape(-1, 4)
        return (rows[:, 0] <= x) & (x <= rows[:, 1]) & (rows[:, 2] <= y) & (y <= rows[:, 3])

    if singular is not None and len(singular) and containing(singular).any():
        return "singular"
    hits = containing(boxes)
    if not hits.any():
        return "outside"
    return "inside" if (np.asarray(status)[hits] == 2).any() else "boundary"


def wrapped_legend(items, width: int) -> str:
    """``items`` two spaces apart, on lines of at most ``width`` cells."""
    lines: list[str] = []
    for item in items:
        if lines and len(lines[-1]) + 2 + len(item) <= width:
            lines[-1] += "  " + item
        else:
            lines.append(item)
    return "\n".join(lines)


class MapExplorer(Widget):
    """The boxes of a workspace (rows ``x_lo, x_hi, y_lo, y_hi`` in cm, ``status`` 2 inside,
    1 boundary) in an aspect-true, zoomable view with a cursor."""

    can_focus = True
    DEFAULT_CSS = """
    MapExplorer { width: 1fr; height: 1fr; }
    MapExplorer:focus { background: $boost; }
    """
    BINDINGS: ClassVar = [
        *(
            Binding(key, f"move({dx}, {dy})", show=False)
            for key, dx, dy in (("left", -1, 0), ("right", 1, 0), ("up", 0, 1), ("down", 0, -1))
        ),
        *(
            Binding(f"shift+{key}", f"pan({dx}, {dy})", show=False)
            for key, dx, dy in (("left", -1, 0), ("right", 1, 0), ("up", 0, 1), ("down", 0, -1))
        ),
        Binding("plus,equals_sign", "zoom(0.5)", "Zoom in", key_display="+", show=False),
        Binding("minus", "zoom(2)", "Zoom -", key_display="-", show=False),
        Binding("0", "fit", "Fit", show=False),
        Binding("b", "toggle('exact')", "Exact", show=False),
        Binding("m", "toggle('mode')", "Mode", show=False),
        Binding("k", "toggle('kappa')", "κ map", show=False),
        Binding("a", "toggle('accuracy')", "Error map", show=False),
        Binding("r", "repave", "Re-pave"),
    ]

    class Moved(Message):
        """The cursor or the view changed (the pane redraws the read-out and drawing)."""

        def __init__(self, explorer: MapExplorer) -> None:
            super().__init__()
            self.explorer = explorer

    class RepaveRequested(Message):
        """``r``: pave the visible region again, finer (the pane runs it)."""

        def __init__(self, extent: tuple[float, float, float, float]) -> None:
            super().__init__()
            self.extent = extent

    def __init__(self, **kwargs: Any):
        super().__init__(**kwargs)
        self.boxes = np.zeros((0, 4))
        self.status = np.zeros(0, dtype=np.int64)
        self.overlays: dict[str, Any] = {}
        self.note = ""
        self.cursor_cm = (0.0, 0.0)
        self.centre_cm = (0.0, 0.0)
        self.cell_cm = 1.0
        self.fitted = False
        self.show_exact = False
        self.show_mode = False
        self.show_kappa = False
        #: The dexterity outcome whose κ map ``k`` shows (``None``: the job has no
        #: ``kappa_max``; set by the pane).
        self.kappa: Any = None
        self.show_accuracy = False
        #: The accuracy outcome whose error map ``a`` shows (``None``: the job has no
        #: ``accuracy``; set by the pane).
        self.accuracy: Any = None
        #: Callables giving the exact boundary's rings and whether a point is in the
        #: circle's working mode (set by the pane; ``None`` when not available).
        self.exact_rings: Any = None
        self.in_mode: Any = None
        self.text = ""

    # -- content ------------------------------------------------------------------------
    def show_boxes(self, boxes, status, note: str = "", refit: bool = True, **overlays) -> None:
        """Draw ``boxes``; ``refit`` fits the view to them and puts the cursor at their
        middle (else the view and cursor stay, e.g. after a re-paving)."""
        self.boxes = np.asarray(boxes, dtype=np.float64).reshape(-1, 4)
        self.status = np.asarray(status).reshape(-1)
        self.overlays = overlays
        self.note = note
        if refit or not self.fitted:
            self.fit()
        self.refresh()
        self.post_message(self.Moved(self))

    def show_text(self, text: str) -> None:
        """A message instead of a map."""
        self.boxes = np.zeros((0, 4))
        self.status = np.zeros(0, dtype=np.int64)
        self.overlays = {}
        self.kappa = None
        self.accuracy = None
        self.fitted = False
        self.text = text
        self.refresh()

    def plot_size(self) -> tuple[int, int]:
        """Map columns and rows in the widget's current size."""
        size = self.content_region.size
        return max(10, size.width - LABEL_CELLS), max(3, size.height - AXIS_LINES)

    def fit(self) -> None:
        if not len(self.boxes):
            return
        layers = [np.reshape(b, (-1, 4)) for b, _, _ in self.overlays.get("layers", ())]
        x_lo, x_hi, y_lo, y_hi = fit_extent(
            np.concatenate([self.boxes, *layers]), (0.0, 1.0, 0.0, 1.0)
        )
        columns, rows = self.plot_size()
        self.cell_cm = max((x_hi - x_lo) / columns, (y_hi - y_lo) / (2 * rows), 1e-9)
        self.centre_cm = (0.5 * (x_lo + x_hi), 0.5 * (y_lo + y_hi))
        self.cursor_cm = self.centre_cm
        self.fitted = True

    def extent(self) -> tuple[float, float, float, float]:
        """The view ``(x_lo, x_hi, y_lo, y_hi)`` in cm (aspect-true)."""
        columns, rows = self.plot_size()
        half_x, half_y = 0.5 * columns * self.cell_cm, rows * self.cell_cm
        cx, cy = self.centre_cm
        return (cx - half_x, cx + half_x, cy - half_y, cy + half_y)

    def cursor_cell(self) -> tuple[int, int]:
        """``(column, row from the top)`` of the cursor in the map."""
        x_lo, _, _, y_hi = self.extent()
        x, y = self.cursor_cm
        return math.floor((x - x_lo) / self.cell_cm), math.floor((y_hi - y) / (2 * self.cell_cm))

    def cell_centre(self, column: int, row: int) -> tuple[float, float]:
        x_lo, _, _, y_hi = self.extent()
        return (x_lo + (column + 0.5) * self.cell_cm, y_hi - (row + 0.5) * 2 * self.cell_cm)

    # -- keys -----------------------------------------------------------------------------
    def action_move(self, dx: int, dy: int) -> None:
        """Move the cursor one cell (to the cell's centre), panning when it leaves the view."""
        column, row = self.cursor_cell()
        self.cursor_cm = self.cell_centre(column + dx, row - dy)
        columns, rows = self.plot_size()
        column, row = self.cursor_cell()
        if not (0 <= column < columns and 0 <= row < rows):
            cx, cy = self.centre_cm
            self.centre_cm = (cx + dx * self.cell_cm, cy + dy * 2 * self.cell_cm)
        self.changed()

    def action_pan(self, dx: int, dy: int) -> None:
        x_lo, x_hi, y_lo, y_hi = self.extent()
        shift = (0.25 * dx * (x_hi - x_lo), 0.25 * dy * (y_hi - y_lo))
        self.centre_cm = (self.centre_cm[0] + shift[0], self.centre_cm[1] + shift[1])
        self.cursor_cm = (self.cursor_cm[0] + shift[0], self.cursor_cm[1] + shift[1])
        self.changed()

    def action_zoom(self, factor: float) -> None:
        """Scale the cell size by ``factor`` about the cursor (the cursor stays put)."""
        cx, cy = self.centre_cm
        px, py = self.cursor_cm
        self.centre_cm = (px + (cx - px) * factor, py + (cy - py) * factor)
        self.cell_cm *= factor
        self.changed()

    def action_fit(self) -> None:
        self.fit()
        self.changed()

    def action_toggle(self, what: str) -> None:
        if what == "exact":
            self.show_exact = not self.show_exact
        elif what == "mode":
            self.show_mode = not self.show_mode
        elif what == "kappa":
            self.show_kappa = not self.show_kappa
        elif what == "accuracy":
            self.show_accuracy = not self.show_accuracy
        self.changed()

    def action_repave(self) -> None:
        if len(self.boxes):
            self.post_message(self.RepaveRequested(self.extent()))

    def changed(self) -> None:
        self.refresh()
        self.post_message(self.Moved(self))

    # -- drawing --------------------------------------------------------------------------
    def map_lines(self) -> list[str]:
        """The map rows and the x axis (``render_map``) with the overlays asked for."""
        columns, rows = self.plot_size()
        width, height = columns + LABEL_CELLS, rows + 3
        lines = render_map(self.boxes, self.status, self.extent(), width, height, **self.overlays)
        lines = lines[: rows + AXIS_LINES]
        grid = [list(line.ljust(width)) for line in lines[:rows]]

        def mark(column: int, row: int, glyph: str, over: tuple[str, ...]) -> None:
            if 0 <= column < columns and 0 <= row < rows:
                cell = grid[row][LABEL_CELLS + column]
                if cell in over:
                    grid[row][LABEL_CELLS + column] = glyph

        if self.show_mode and self.in_mode is not None:
            for row in range(rows):
                for column in range(columns):
                    if not self.in_mode(self.cell_centre(column, row)):
                        mark(column, row, OTHER_MODE_GLYPH, ("█", BOUNDARY_GLYPH))
        layers = []
        if self.show_kappa and self.kappa is not None:
            worst = kappa_map.view_cells(self.kappa, self.extent(), columns, rows)
            edges = kappa_map.band_edges(self.kappa.kappa_max)
            kappa_max = self.kappa.kappa_max
            layers.append((worst, lambda v, e=edges, k=kappa_max: kappa_map.cell_glyph(v, e, k)))
        if self.show_accuracy and self.accuracy is not None:
            error = accuracy_map.position_error(self.accuracy)
            boxes = self.accuracy.boxes
            worst = kappa_map.view_worst_cells(boxes, error, self.extent(), columns, rows)
            edges = accuracy_map.error_edges(self.accuracy)
            layers.append((worst, lambda v, e=edges: accuracy_map.error_glyph(v, e)))
        for worst, glyph_of in layers:
            for row in range(rows):
                for column, value in enumerate(worst[rows - 1 - row]):
                    if not np.isnan(value):
                        grid[row][LABEL_CELLS + column] = glyph_of(value)
        if self.show_exact and self.exact_rings is not None:
            x_lo, _, _, y_hi = self.extent()
            for ring in self.exact_rings():
                for (xa, ya), (xb, yb) in itertools.pairwise(ring):
                    steps = max(1, int(math.hypot(xb - xa, yb - ya) / (0.5 * self.cell_cm)))
                    for k in range(steps + 1):
                        x, y = xa + (xb - xa) * k / steps, ya + (yb - ya) * k / steps
                        mark(
                            math.floor((x - x_lo) / self.cell_cm),
                            math.floor((y_hi - y) / (2 * self.cell_cm)),
                            EXACT_GLYPH,
                            (OUTSIDE_GLYPH, BOUNDARY_GLYPH),
                        )
        return ["".join(row) for row in grid] + lines[rows:]

    def render(self):
        if not len(self.boxes):
            return Text(self.text)
        lines = self.map_lines()
        column, row = self.cursor_cell()
        columns, _ = self.plot_size()
        text = Text(no_wrap=True, overflow="crop")
        for index, line in enumerate(lines):
            if index:
                text.append("\n")
            if index == row and 0 <= column < columns:
                at = LABEL_CELLS + column
                text.append(line[:at])
                text.append(CURSOR_GLYPH, "bold reverse")
                text.append(line[at + 1 :])
            else:
                text.append(line)
        return text

    def legend(self, width: int) -> str:
        items = list(LEGEND_ITEMS)
        if self.show_exact:
            items.append(EXACT_ITEM)
        if self.show_mode and self.in_mode is not None:
            items.append(MODE_ITEM)
        if self.kappa is not None:
            shown = self.show_kappa
            items += kappa_map.legend_items(self.kappa.kappa_max) if shown else [KAPPA_ITEM]
        if self.accuracy is not None:
            edges = accuracy_map.error_edges(self.accuracy)
            shown = self.show_accuracy
            items += accuracy_map.error_legend_items(edges) if shown else [ACCURACY_ITEM]
        if "singular" in self.overlays or "circle" in self.overlays:
            items += SINGULAR_LEGEND_ITEMS
        items += [f"{glyph} {text}" for _, glyph, text in self.overlays.get("layers", ())]
        if self.note:
            items.append(self.note)
        return wrapped_legend(items, width)

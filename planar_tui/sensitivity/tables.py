"""Sensitivity index tables fitted to a width without cutting a number (CLI and app).

A table per speed, in the first of these layouts whose natural width fits the pane:

1. paper A's Table 4: a row per torque (and per method), a column per parameter;
2. the same with one-letter method labels (``S`` Sobol', ``E`` eFAST);
3. transposed: a row per parameter (and per method), a column per torque;
4. transposed with one-letter method labels.

Rich never shrinks a column here (every column has its exact width and ``no_wrap``), so
a number is never cut to "…": when even the narrowest layout is wider than the pane, it is
shown at its natural width (the app's pane scrolls sideways; a terminal wraps). At 80 columns a 6R robot (12
parameters, both methods) fits as Table 4 with the form hidden (``ctrl+f``), transposed
beside the form.

Cells print the number; heat colours mark its size (16-colour safe) and the largest value
of each torque and method is **bold**, so the dominant parameter survives ``NO_COLOR``.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from rich import box
from rich.cells import cell_len
from rich.console import Group, RenderableType
from rich.table import Table
from rich.text import Text


@dataclass(frozen=True)
class View:
    """A quantity the table can show.

    ``row`` is the row of ``Analysis.indices`` (S1, S1 conf, ST, ST conf), ``None`` for
    ``Analysis.percent``; ``heat_scale`` turns a value into a heat fraction (``None``: no
    heat and no bold, for confidence half-widths).
    """

    key: str
    title: str
    row: int | None
    decimals: int
    heat_scale: float | None


#: The views ``ctrl+t`` cycles through.
VIEWS = (
    View("percent", "% of {percent_of} per {row}", None, 1, 100.0),
    View("S1", "S1, first-order index", 0, 2, 1.0),
    View("ST", "ST, total index", 2, 2, 1.0),
    View("confidence", "± 95 % half-width of ST (eFAST's unreliable, SALib #649)", 3, 3, None),
)

#: Long and one-letter row labels of each method.
METHOD_LABELS = {"sobol": ("Sobol'", "S"), "efast": ("eFAST", "E"), "pce": ("PCE", "P")}

#: Columns are separated by one blank cell.
GAP = 1


def heat_style(fraction: float) -> str:
    """Background by size, readable in 16 colours: >= 0.5 red, >= 0.2 yellow, >= 0.05 green."""
    if fraction >= 0.5:
        return "black on red"
    if fraction >= 0.2:
        return "black on yellow"
    if fraction >= 0.05:
        return "black on green"
    return ""


def view_values(analysis, view: View) -> np.ndarray:
    """The (torques, parameters) array ``view`` shows for one analysis."""
    return np.asarray(analysis.percent if view.row is None else analysis.indices[view.row])


def method_label(method: str, short: bool) -> str:
    long_label, short_label = METHOD_LABELS.get(method, (method, method[:1].upper()))
    return short_label if short else long_label


@dataclass
class Grid:
    """A table as text cells: a header, rows, and how many leading label columns."""

    header: list[str]
    rows: list[list[Text]]
    label_columns: int

    def widths(self) -> list[int]:
        """Each column's natural width (header and cells); value columns share the widest."""
        widths = [
            max([cell_len(title)] + [cell_len(row[c].plain) for row in self.rows])
            for c, title in enumerate(self.header)
        ]
        values = max(widths[self.label_columns :], default=0)
        return widths[: self.label_columns] + [values] * (len(widths) - self.label_columns)

    def width(self) -> int:
        """The table's natural width, gaps included."""
        widths = self.widths()
        return sum(widths) + GAP * (len(widths) - 1)

    def table(self) -> Table:
        """A Rich table with exact, unshrinkable column widths."""
        table = Table(box=box.SIMPLE_HEAD, show_edge=False, pad_edge=False, padding=0, expand=False)
        for c, (title, width) in enumerate(zip(self.header, self.widths(), strict=True)):
            label = c < self.label_columns
            table.add_column(
                title,
                justify="left" if label else "right",
                width=width,
                no_wrap=True,
            )
        for row in self.rows:
            table.add_row(*row)
        return table


def build_grid(chosen: Sequence, view: View, transposed: bool, short: bool) -> Grid:
    """The cells of one speed's analyses (one per method) in one layout."""
    values = [view_values(a, view) for a in chosen]
    n_torques, n_params = values[0].shape
    dominant = [v.argmax(axis=1) if view.heat_scale else None for v in values]
    labels = [method_label(a.method, short) for a in chosen]
    several = len(chosen) > 1
    outputs = chosen[0].output_labels()

    def cell(k: int, torque: int, parameter: int) -> Text:
        if not chosen[k].is_defined(torque):  # no variance, no index
            return Text("—", style="dim")
        value = float(values[k][torque, parameter])
        style = heat_style(value / view.heat_scale) if view.heat_scale else ""
        top = dominant[k]
        if top is not None and top[torque] == parameter:
            style = f"bold {style}".strip()
        return Text(f"{value:.{view.decimals}f}", style=style)

    def label_cells(key: str, k: int) -> list[Text]:
        cells = [Text(key if k == 0 else "")]
        return [*cells, Text(labels[k], style="italic")] if several else cells

    corner = "τ" if not chosen[0].outputs else ""
    lead = [corner if not transposed else ""] + ([""] if several else [])
    rows = []
    if not transposed:
        header = lead + list(chosen[0].names)
        for torque in range(n_torques):
            for k in range(len(chosen)):
                cells = [cell(k, torque, j) for j in range(n_params)]
                rows.append(label_cells(outputs[torque], k) + cells)
    else:
        header = lead + list(outputs)
        for j, name in enumerate(chosen[0].names):
            for k in range(len(chosen)):
                cells = [cell(k, torque, j) for torque in range(n_torques)]
                rows.append(label_cells(name, k) + cells)
    return Grid(header, rows, len(lead))


#: (transposed, short method labels), in order of preference.
LAYOUTS = ((False, False), (False, True), (True, False), (True, True))


@dataclass
class FittedTables:
    """What the tab shows: the renderable, its natural width and the layout chosen."""

    renderable: RenderableType
    width: int
    transposed: bool
    short: bool


def by_speed(analyses: Sequence) -> dict[float, list]:
    """Analyses grouped by speed (in run order), methods in run order within each."""
    groups: dict[float, list] = {}
    for analysis in analyses:
        groups.setdefault(analysis.speed_rad_s, []).append(analysis)
    return groups


def fit_tables(analyses: Sequence, view: View, width: int, percent_of: str = "ST") -> FittedTables:
    """The tables of every speed in the first layout that fits ``width`` cells.

    Parameters
    ----------
    analyses
        ``result.analyses`` of one sensitivity job (one posture).
    view
        One of :data:`VIEWS`.
    width
        Cells available; when no layout fits, the narrowest is returned at its natural
        width (``FittedTables.width > width``), never shrunk.
    percent_of
        The job's ``percent_of`` (``ST`` or ``S1``), named in the percent view's title.
    """
    groups = by_speed(analyses)
    candidates = []
    for transposed, short in LAYOUTS:
        grids = [build_grid(chosen, view, transposed, short) for chosen in groups.values()]
        candidates.append((max(grid.width() for grid in grids), transposed, short, grids))
        if candidates[-1][0] <= width:
            break
    natural, transposed, short, grids = min(candidates, key=lambda candidate: candidate[0])
    parts: list[RenderableType] = []
    posture = analyses[0].posture
    row = "output" if analyses[0].outputs else "torque"
    title = view.title.format(percent_of=percent_of, row=row)
    for speed, grid in zip(groups, grids, strict=True):
        context = groups[speed][0].context or f"{posture} · {speed:g} rad/s"
        parts.append(Text(f"{title} · {context}", style="bold"))
        parts.append(grid.table())
    notes = []
    if view.heat_scale:
        notes.append(f"bold: largest of each {row}")
    shown = {a.method for a in next(iter(groups.values()))}
    if short and len(shown) > 1:
        notes.append(
            ", ".join(
                f"{METHOD_LABELS[m][1]} = {METHOD_LABELS[m][0]}"
                for m in METHOD_LABELS
                if m in shown
            )
        )
    runs = {a.method: a.runs for a in next(iter(groups.values())) if a.runs}
    if runs:
        notes.append(
            "runs: " + ", ".join(f"{METHOD_LABELS.get(m, (m,))[0]} {r}" for m, r in runs.items())
        )
    loo = [a.loo_error.max() for group in groups.values() for a in group if a.loo_error is not None]
    if loo:
        notes.append(f"PCE leave-one-out error ≤ {max(loo):.2g}")
    if notes:
        parts.append(Text("; ".join(notes), style="dim"))
    return FittedTables(Group(*parts), natural, transposed, short)

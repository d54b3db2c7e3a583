"""Figure of a sweep (CSV: ``point``, one column per varied key named by its
path, the job kind's summary figures, ``status``, ``message``, ``seconds``).

Varied keys are the leading columns after ``point`` named as preset key paths (a job key
such as ``orientation_deg`` or ``form``, a robot key ``robot3rrr.distal_cm``, a list
element ``robot.lengths_m[2]``) that take at least two values; a key whose cells are all
numbers is numeric, any other (text such as a workspace ``form``, a list such as a
posture) is categorical, its values in order of first appearance. The figures are the
other numeric columns but ``seconds``, the settings echoed by the kind's summary
(``precision_cm``, or a column equal to a varied key's, such as ``orientation_lo_deg``)
and those that hold one value at every point (nothing to plot). A figure is never taken
as an axis: a table where no key column varies is refused.

- One numeric key: each figure against it as a line.
- Numeric keys that move together (a ``zip`` sweep: each value of one goes with one value
  of the others, ``proximal_cm`` 20 → 40 with ``distal_cm`` 40 → 20): one axis, the first
  key's, each figure against it as a line, the others' values named in the axis label.
- One categorical key: each figure as points over the categories (tick labels).
- A categorical key and a numeric key: one line per category against the numeric key.
- Two numeric keys: a heat map per figure (a full grid), or the points coloured by the
  figure (a sampled design).
- Two categorical keys: a heat map over the categories (labelled ticks; a cell holding
  several points shows their mean).

A heat map's cell is centred on its values: half as wide (and as tall) as the distance
to the nearer neighbouring value, so unevenly spaced values leave blank space between
their cells rather than drawing cells off their values; a single value (and a category)
gets a cell of width 1.

Failed points are marked with a red ✕ (on the x axis for a line, in the cell for a heat
map); with more than two varied keys the first two are the axes. With no figure to draw
(every point failed), one panel along the varied keys holds the failed points' ✕ marks
and a note.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Any

from planar_tui.csvio import CsvTable
from planar_tui.figures.canvas import colour, new_figure
from planar_tui.figures.table import column, text_column
from planar_tui.registry import JOB_KINDS, ROBOT_KINDS

#: Most figures drawn (the first ones in column order).
MOST_PANELS = 9
BOOKKEEPING = ("point", "status", "message", "seconds")


def matches(header: tuple[str, ...]) -> bool:
    return len(header) > 0 and header[0] == "point" and "status" in header


def _key_names() -> set[str]:
    names = {key for kind in JOB_KINDS.values() for key in kind.keys}
    return names | {f"{r}.{key}" for r, kind in ROBOT_KINDS.items() for key in kind.keys}


def is_key_path(name: str, keys: set[str]) -> bool:
    """Whether a column names a preset key (``[k]`` elements allowed, 1-based)."""
    bare = re.sub(r"\[\d+\]", "", name)
    return bare in keys or (bare.split(".", 1)[-1] in keys and "." in bare)


def _is_number(cell: Any) -> bool:
    import numpy as np

    return isinstance(cell, int | float | np.number) and not isinstance(cell, bool | np.bool_)


def is_numeric(table: CsvTable, name: str) -> bool:
    """Whether every non-empty cell of column ``name`` is a number (not text, a list or a
    boolean)."""
    if getattr(getattr(table.rows, "dtype", None), "kind", "") == "f":
        return True
    index = table.header.index(name)
    cells = [row[index] for row in table.rows if index < len(row)]
    return all(_is_number(cell) for cell in cells if cell is not None and cell != "")


@dataclass(frozen=True)
class Axis:
    """A varied key as an axis: ``values`` per row (the numbers, or the category index),
    and for a categorical key its ``categories`` (tick labels, in order of appearance)."""

    name: str
    values: Any
    categories: tuple[str, ...] | None = None

    @property
    def categorical(self) -> bool:
        return self.categories is not None


def key_axis(table: CsvTable, name: str) -> Axis:
    """Column ``name`` as an :class:`Axis` (numeric or categorical, see the module doc)."""
    import numpy as np

    if is_numeric(table, name):
        return Axis(name, column(table, name))
    labels = text_column(table, name)
    categories = tuple(dict.fromkeys(labels))
    index = {label: k for k, label in enumerate(categories)}
    return Axis(name, np.array([index[label] for label in labels], dtype=float), categories)


def _varies(table: CsvTable, name: str) -> bool:
    return len(set(text_column(table, name)) - {""}) > 1


def split_columns(table: CsvTable) -> tuple[list[str], list[str]]:
    """(varied keys, figures) of a sweep table (see the module doc)."""
    import numpy as np

    keys = _key_names()
    varied, figures = [], []
    for name in table.header[1:]:
        if name in BOOKKEEPING:
            continue
        if is_key_path(name, keys):
            # the keys lead; a key setting after the first figure, or one that stays put
            # (an echoed ε or strategy), is neither an axis nor a figure
            if not figures and _varies(table, name):
                varied.append(name)
            continue
        values = column(table, name)
        if np.isfinite(values).any():
            figures.append(name)
    echoes = [
        name
        for name in figures
        if any(_same(column(table, name), column(table, key)) for key in varied)
    ]
    return varied, [
        name for name in figures if name not in echoes and _varies_numerically(column(table, name))
    ]


def _varies_numerically(values: Any) -> bool:
    """Whether a figure column holds two different finite values (a constant is no plot)."""
    import numpy as np

    finite = values[np.isfinite(values)]
    return bool(finite.size and finite.max() > finite.min())


def zipped(axes_keys: list[Axis]) -> bool:
    """Whether numeric keys move together: every value of each goes with one value of each
    other (as many distinct tuples as distinct values of every key), so one key orders the
    points and the others follow (a ``zip`` sweep, not a grid)."""
    if len(axes_keys) < 2 or any(axis.categorical for axis in axes_keys):
        return False
    columns = [axis.values.tolist() for axis in axes_keys]
    tuples = len(set(zip(*columns, strict=True)))
    return all(len(set(values)) == tuples for values in columns)


def _followers_label(lead: Axis, followers: list[Axis]) -> str:
    """The axis label of zipped keys: ``LEAD (with KEY first → last, ...)``, the followers'
    values at the lead's smallest and largest."""
    import numpy as np

    order = np.argsort(lead.values, kind="stable")
    first, last = order[0], order[-1]
    parts = [f"{f.name} {f.values[first]:g} → {f.values[last]:g}" for f in followers]
    return f"{lead.name} (with {', '.join(parts)})"


def _same(values: Any, other: Any) -> bool:
    """Whether a figure column repeats a varied key's values (a workspace's
    ``orientation_lo_deg`` in a sweep over ``orientation_deg``): an echo, not a figure."""
    import numpy as np

    return bool(np.array_equal(values, other, equal_nan=True))


def draw(table: CsvTable, title: str) -> Any:
    """The figures against one varied key or two (see the module doc)."""
    import numpy as np

    varied, figures = split_columns(table)
    if not varied:
        raise ValueError("the sweep has no varied key column")
    failed = np.array([s != "ok" for s in text_column(table, "status")], dtype=bool)
    every_key = [key_axis(table, name) for name in varied]
    axes_keys = every_key[:2]
    xlabel = None
    if zipped(every_key):  # one axis: the others follow it
        axes_keys, xlabel = every_key[:1], _followers_label(every_key[0], every_key[1:])
    if len(axes_keys) == 2 and axes_keys[0].categorical and not axes_keys[1].categorical:
        axes_keys.reverse()  # the numeric key across, one line per category
    if not figures or failed.all():
        return _failures_only(axes_keys, failed, title)
    shown = figures[:MOST_PANELS]
    cols = min(max(len(shown), 1), 3)
    rows = max(1, math.ceil(len(shown) / cols))
    fig = new_figure(4.2 * cols + 0.6, 3.4 * rows + 0.6)
    axes = fig.subplots(rows, cols, squeeze=False).ravel()
    for ax, name in zip(axes, shown, strict=False):
        y = column(table, name)
        if len(axes_keys) == 1:
            _line(ax, axes_keys[0], y, failed)
            ax.set(ylabel=name, xlabel=xlabel or axes_keys[0].name)
        elif axes_keys[1].categorical and not axes_keys[0].categorical:
            _lines_per_category(ax, axes_keys[0], axes_keys[1], y, failed)
            ax.set(ylabel=name)
        else:
            _heat(fig, ax, axes_keys[0], axes_keys[1], y, failed, name)
    for ax in axes[len(shown) :]:
        ax.set_visible(False)
    fig.suptitle(title)
    return fig


def _failures_only(axes_keys: list[Axis], failed: Any, title: str) -> Any:
    """One panel along the varied key(s): the failed points' ✕ marks and a note that no
    point succeeded (or that the table holds no figure column)."""
    fig = new_figure(6.0, 3.4 if len(axes_keys) == 1 else 4.6)
    ax = fig.add_subplot()
    across = axes_keys[0]
    if len(axes_keys) == 1:
        _failed_on_axis(ax, across.values[failed])
        ax.set_yticks([])
    else:
        down = axes_keys[1]
        ax.plot(
            across.values[failed],
            down.values[failed],
            "x",
            color="red",
            ms=8,
            mew=2,
            gid="failed",
            label="failed",
        )
        _ticks(ax, down, "y")
        ax.set(ylabel=down.name)
    for axis, set_limits in zip(axes_keys, (ax.set_xlim, ax.set_ylim), strict=False):
        if axis.categorical:
            set_limits(-0.5, len(axis.categories) - 0.5)
    _ticks(ax, across, "x")
    ax.set(xlabel=across.name)
    note = "no point succeeded" if failed.all() else "no figure column varies"
    ax.text(0.5, 0.5, note, transform=ax.transAxes, ha="center", va="center", gid="note")
    ax.grid(alpha=0.3)
    fig.suptitle(title)
    return fig


def _failed_on_axis(ax: Any, x: Any) -> None:
    """A red ✕ on the x axis at each failed point's ``x``."""
    import numpy as np

    if len(x):
        ax.plot(
            x,
            np.zeros(len(x)),
            "x",
            color="red",
            ms=8,
            mew=2,
            clip_on=False,
            transform=ax.get_xaxis_transform(),
            gid="failed",
            label="failed",
        )


def _ticks(ax: Any, axis: Axis, which: str) -> None:
    """Label a categorical axis with its categories."""
    if axis.categorical:
        getattr(ax, f"set_{which}ticks")(range(len(axis.categories)), axis.categories)
        if which == "x":
            ax.tick_params(axis="x", labelrotation=20 if len(axis.categories) > 3 else 0)


def _line(ax: Any, across: Axis, y: Any, failed: Any) -> None:
    """The figure against one key: a line (numeric) or points per category."""
    import numpy as np

    x = across.values
    order = np.argsort(x, kind="stable")
    ok = order[~failed[order]]
    ax.plot(
        x[ok],
        y[ok],
        "o" if across.categorical else "-o",
        ms=5 if across.categorical else 3.5,
        gid="sweep",
    )
    _failed_on_axis(ax, x[failed])
    if failed.any():
        ax.legend(fontsize="small")
    if across.categorical:
        ax.set_xlim(-0.5, len(across.categories) - 0.5)
    _ticks(ax, across, "x")
    ax.set(xlabel=across.name)
    ax.grid(alpha=0.3)


def _lines_per_category(ax: Any, across: Axis, by: Axis, y: Any, failed: Any) -> None:
    """The figure against the numeric key ``across``, one line per category of ``by``."""
    import numpy as np

    count = len(by.categories)
    for k, category in enumerate(by.categories):
        rows = np.flatnonzero((by.values == k) & ~failed)
        rows = rows[np.argsort(across.values[rows], kind="stable")]
        ax.plot(
            across.values[rows],
            y[rows],
            "-o",
            ms=3.5,
            color=colour(k, count),
            label=f"{by.name} = {category}",
            gid="sweep",
        )
    _failed_on_axis(ax, across.values[failed])
    ax.legend(fontsize="x-small")
    ax.set(xlabel=across.name)
    ax.grid(alpha=0.3)


def _heat(fig, ax, across: Axis, down: Axis, value, failed, name) -> None:
    """A heat map of ``value`` over a full grid of the two keys, one rectangle per cell
    centred on its two values (:func:`_half_widths`; categories on their own cells; a
    cell with several points: their mean, a cell with none left blank), else coloured
    points."""
    import numpy as np
    from matplotlib.collections import PolyCollection

    x, y = across.values, down.values
    xs = np.arange(len(across.categories)) if across.categorical else np.unique(x[np.isfinite(x)])
    ys = np.arange(len(down.categories)) if down.categorical else np.unique(y[np.isfinite(y)])
    both = across.categorical and down.categorical
    if both or len(xs) * len(ys) == len(x):
        good = ~failed & np.isfinite(value)
        sums = np.zeros((len(ys), len(xs)))
        counts = np.zeros((len(ys), len(xs)))
        cells = (np.searchsorted(ys, y[good]), np.searchsorted(xs, x[good]))
        np.add.at(sums, cells, value[good])
        np.add.at(counts, cells, 1)
        with np.errstate(invalid="ignore"):
            grid = np.where(counts > 0, sums / np.maximum(counts, 1), np.nan)
        hx, hy = _half_widths(xs), _half_widths(ys)
        cx, cy = np.meshgrid(xs, ys)  # row-major: the cell of (ys[i], xs[j]) at i * nx + j
        wx, wy = np.meshgrid(hx, hy)
        x0, x1, y0, y1 = (cx - wx).ravel(), (cx + wx).ravel(), (cy - wy).ravel(), (cy + wy).ravel()
        verts = np.stack(
            [np.column_stack(corner) for corner in ((x0, y0), (x1, y0), (x1, y1), (x0, y1))], axis=1
        )
        image = PolyCollection(
            verts,
            array=np.ma.masked_invalid(grid.ravel()),
            cmap="viridis",
            edgecolors="none",
            gid="heat",
        )
        ax.add_collection(image)
        ax.set(xlim=(x0.min(), x1.max()), ylim=(y0.min(), y1.max()))
    else:
        image = ax.scatter(x[~failed], y[~failed], c=value[~failed], cmap="viridis", gid="heat")
    if failed.any():
        ax.plot(x[failed], y[failed], "x", color="red", ms=8, mew=2, gid="failed")
    fig.colorbar(image, ax=ax, label=name)
    _ticks(ax, across, "x")
    _ticks(ax, down, "y")
    ax.set(xlabel=across.name, ylabel=down.name)


def _half_widths(values: Any) -> Any:
    """Half the width of each value's cell: half the distance to the nearer neighbouring
    value (sorted, distinct ``values``), so every cell is centred on its value and no two
    overlap; 0.5 for a single value."""
    import numpy as np

    values = np.asarray(values, dtype=float)
    if len(values) < 2:
        return np.full(len(values), 0.5)
    gaps = np.diff(values)
    return 0.5 * np.minimum(np.r_[gaps[0], gaps], np.r_[gaps, gaps[-1]])

"""Figure of a sweep (issue 10's CSV: ``point``, one column per varied key named by its
path, the job kind's summary figures, ``status``, ``message``, ``seconds``).

Varied keys are the columns after ``point`` named as preset key paths (a job key such as
``orientation_deg``, a robot key ``robot3rrr.distal_cm``, a list element
``robot.lengths_m[2]``) that take at least two values; the figures are the other numeric
columns but ``seconds`` and the settings echoed by the kind's summary (``precision_cm``,
or a column equal to a varied key's, such as ``orientation_lo_deg``). One varied key: each figure against it as a line, the failed
points marked with a red ✕ on the axis. Two: a heat map per figure (a full grid), or the
points coloured by the figure (a sampled design), failed points marked ✕.
"""

from __future__ import annotations

import math
import re
from typing import Any

from planar_tui.csvio import CsvTable
from planar_tui.figures.canvas import new_figure
from planar_tui.figures.table import column, text_column

#: Most figures drawn (the first ones in column order).
MOST_PANELS = 9
BOOKKEEPING = ("point", "status", "message", "seconds")


def matches(header: tuple[str, ...]) -> bool:
    return len(header) > 0 and header[0] == "point" and "status" in header


def _key_names() -> set[str]:
    from planar_tui.registry import JOB_KINDS, ROBOT_KINDS

    names = {key for kind in JOB_KINDS.values() for key in kind.keys}
    return names | {f"{r}.{key}" for r, kind in ROBOT_KINDS.items() for key in kind.keys}


def is_key_path(name: str, keys: set[str]) -> bool:
    """Whether a column names a preset key (``[k]`` elements allowed, 1-based)."""
    bare = re.sub(r"\[\d+\]", "", name)
    return bare in keys or (bare.split(".", 1)[-1] in keys and "." in bare)


def split_columns(table: CsvTable) -> tuple[list[str], list[str]]:
    """(varied keys, figures) of a sweep table (see the module doc)."""
    import numpy as np

    keys = _key_names()
    varied, figures = [], []
    for name in table.header[1:]:
        if name in BOOKKEEPING:
            continue
        values = column(table, name)
        finite = values[np.isfinite(values)]
        if not len(finite):
            continue
        if is_key_path(name, keys):
            if len(np.unique(finite)) > 1 and not figures:
                varied.append(name)  # a setting that stays put (an echoed ε) is no figure
        else:
            figures.append(name)
    if not varied and figures:  # no key path: the first numeric column that varies
        for name in list(figures):
            if len(np.unique(column(table, name)[np.isfinite(column(table, name))])) > 1:
                varied.append(name)
                figures.remove(name)
                break
    echoes = [name for name in figures
              if any(_same(column(table, name), column(table, key)) for key in varied)]  # fmt: skip
    return varied, [name for name in figures if name not in echoes]


def _same(values: Any, other: Any) -> bool:
    """Whether a figure column repeats a varied key's values (a workspace's
    ``orientation_lo_deg`` in a sweep over ``orientation_deg``): an echo, not a figure."""
    import numpy as np

    return bool(np.array_equal(values, other, equal_nan=True))


def draw(table: CsvTable, title: str) -> Any:
    """Figures against one varied key (lines) or two (heat maps)."""
    import numpy as np

    varied, figures = split_columns(table)
    if not varied:
        raise ValueError("the sweep has no varied numeric column")
    failed = np.array([s != "ok" for s in text_column(table, "status")], dtype=bool)
    shown = figures[:MOST_PANELS]
    cols = min(max(len(shown), 1), 3)
    rows = max(1, math.ceil(len(shown) / cols))
    fig = new_figure(4.2 * cols + 0.6, 3.4 * rows + 0.6)
    axes = fig.subplots(rows, cols, squeeze=False).ravel()
    x = column(table, varied[0])
    for ax, name in zip(axes, shown, strict=False):
        y = column(table, name)
        if len(varied) == 1:
            order = np.argsort(x, kind="stable")
            ok = order[~failed[order]]
            ax.plot(x[ok], y[ok], "-o", ms=3.5, gid="sweep")
            if failed.any():
                ax.plot(x[failed], np.zeros(failed.sum()), "x", color="red", ms=8, mew=2,
                        transform=ax.get_xaxis_transform(), clip_on=False, gid="failed",
                        label="failed")  # fmt: skip
                ax.legend(fontsize="small")
            ax.set(xlabel=varied[0], ylabel=name)
            ax.grid(alpha=0.3)
        else:
            _heat(fig, ax, x, column(table, varied[1]), y, failed, varied, name)
    for ax in axes[len(shown) :]:
        ax.set_visible(False)
    fig.suptitle(title)
    return fig


def _heat(fig, ax, x, y, value, failed, varied, name) -> None:
    """A heat map of ``value`` over a full (x, y) grid, else coloured points."""
    import numpy as np

    xs, ys = np.unique(x[np.isfinite(x)]), np.unique(y[np.isfinite(y)])
    if len(xs) * len(ys) == len(x):
        grid = np.full((len(ys), len(xs)), np.nan)
        grid[np.searchsorted(ys, y), np.searchsorted(xs, x)] = np.where(failed, np.nan, value)
        image = ax.imshow(grid, origin="lower", aspect="auto", cmap="viridis", gid="heat",
                          extent=_extent(xs) + _extent(ys))  # fmt: skip
    else:
        image = ax.scatter(x[~failed], y[~failed], c=value[~failed], cmap="viridis", gid="heat")
    if failed.any():
        ax.plot(x[failed], y[failed], "x", color="red", ms=8, mew=2, gid="failed")
    fig.colorbar(image, ax=ax, label=name)
    ax.set(xlabel=varied[0], ylabel=varied[1])


def _extent(values) -> tuple[float, float]:
    half = 0.5 * (values[1] - values[0]) if len(values) > 1 else 0.5
    return (float(values[0] - half), float(values[-1] + half))

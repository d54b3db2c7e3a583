"""Figure of sensitivity indices against time: stacked lines, one panel per output and
method (the form SALib's maintainers suggest for time-varying outputs, SALib issue 525).

Each panel stacks the parameters' shares (the ``percent`` column, 100 % in all where the
output varies) over the recorded times, so that a share is the height of its band. Reads
the motion-uncertainty indices CSV (``output, t_s, parameter, method, …, percent``); the
bar figure of :mod:`.sensitivity` hands it tables of more than ``MAX_BAR_TIMES`` times.
"""

from __future__ import annotations

import math
from typing import Any

from planar_tui.csvio import CsvTable
from planar_tui.figures.canvas import colour, new_figure

#: Times up to which the motion indices are drawn as bars (above: stacked lines).
MAX_BAR_TIMES = 8
PANELS_PER_ROW = 3


def draw(table: CsvTable, title: str) -> Any:
    """Stacked shares against time, a panel per (output, method)."""
    import numpy as np

    from planar_tui.figures.sensitivity import METHOD_LABELS, read_indices

    ix = read_indices(table)
    params = list(dict.fromkeys(ix.parameters))
    panels = list(dict.fromkeys(zip(ix.groups, ix.methods, strict=True)))
    cols = min(len(panels), PANELS_PER_ROW)
    rows = math.ceil(len(panels) / cols)
    fig = new_figure(3.6 * cols + 1.6, 2.8 * rows + 0.6)
    for k, (group, method) in enumerate(panels):
        ax = fig.add_subplot(rows, cols, k + 1, gid="stacked")
        chosen = [
            r for r in range(len(ix.groups)) if (ix.groups[r], ix.methods[r]) == (group, method)
        ]
        times = sorted({float(ix.swept[r]) for r in chosen})
        shares = np.zeros((len(params), len(times)))
        for r in chosen:
            shares[params.index(ix.parameters[r]), times.index(float(ix.swept[r]))] = ix.percent[r]
        ax.stackplot(times, shares, colors=[colour(p, len(params)) for p in range(len(params))],
                     linewidth=0.3, edgecolor="white")  # fmt: skip
        ax.set(ylim=(0, 100), xlim=(times[0], times[-1]), xlabel=ix.swept_label,
               title=f"{group} ({METHOD_LABELS.get(method, method)})")  # fmt: skip
        if k % cols == 0:
            ax.set_ylabel("share of the index (%)")
    from matplotlib.patches import Patch

    handles = [Patch(color=colour(p, len(params)), label=name) for p, name in enumerate(params)]
    fig.legend(handles=handles, loc="outside right upper", fontsize="small")
    fig.suptitle(title)
    return fig

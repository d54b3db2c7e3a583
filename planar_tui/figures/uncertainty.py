"""Figure of a motion-uncertainty band table (issue 11's band CSV: ``t_s``, then per
output its mean, standard deviation, 5th, 50th and 95th percentile).

Columns are recognised by a statistic token among the underscore-separated parts of the
name, wherever it stands (``theta1_rad_mean`` or ``theta1_mean_rad``): ``mean``,
``std``/``sd``, ``p5``/``p05``, ``p50``/``median``, ``p95``; the output is the name without
that token. An output needs ``mean``, ``p5`` and ``p95``. Per output, one panel: the mean
and the 5-95 % band against time (and the median dashed); with one recorded time, the
mean with a 5-95 % whisker per output.
"""

from __future__ import annotations

import math
from typing import Any

from planar_tui.csvio import CsvTable
from planar_tui.figures.canvas import colour, new_figure
from planar_tui.figures.table import column

TOKENS = {
    "mean": "mean",
    "std": "std",
    "sd": "std",
    "p5": "p5",
    "p05": "p5",
    "p50": "p50",
    "median": "p50",
    "p95": "p95",
}


def outputs(header: tuple[str, ...]) -> dict[str, dict[str, str]]:
    """``{output: {statistic: column}}`` for outputs having a mean, p5 and p95."""
    found: dict[str, dict[str, str]] = {}
    for name in header:
        parts = name.split("_")
        for k, part in enumerate(parts):
            if part.lower() in TOKENS:
                output = "_".join(parts[:k] + parts[k + 1 :])
                found.setdefault(output, {})[TOKENS[part.lower()]] = name
                break
    return {o: s for o, s in found.items() if {"mean", "p5", "p95"} <= set(s)}


def matches(header: tuple[str, ...]) -> bool:
    return len(header) > 0 and header[0] == "t_s" and bool(outputs(header))


def draw(table: CsvTable, title: str) -> Any:
    """Mean and 5-95 % band per output (see the module doc)."""
    found = outputs(table.header)
    t = column(table, "t_s")
    if len(t) <= 1:
        fig = new_figure(1.2 + 0.8 * len(found), 4.0)
        ax = fig.add_subplot()
        for k, stats in enumerate(found.values()):
            mean, lo, hi = (column(table, stats[s])[0] for s in ("mean", "p5", "p95"))
            ax.errorbar(
                k,
                mean,
                yerr=[[mean - lo], [hi - mean]],
                fmt="o",
                capsize=4,
                color=colour(k, len(found)),
                gid="band",
            )
        ax.set_xticks(range(len(found)), list(found), rotation=30, ha="right")
        ax.set(title=f"mean and 5-95 % range at t = {t[0]:g} s" if len(t) else "")
        fig.suptitle(title)
        return fig
    cols = min(len(found), 3)
    rows = math.ceil(len(found) / cols)
    fig = new_figure(4.0 * cols + 0.4, 3.0 * rows + 0.6)
    axes = fig.subplots(rows, cols, squeeze=False).ravel()
    for k, (ax, (output, stats)) in enumerate(zip(axes, found.items(), strict=False)):
        c = colour(k, len(found))
        ax.fill_between(
            t,
            column(table, stats["p5"]),
            column(table, stats["p95"]),
            color=c,
            alpha=0.3,
            lw=0,
            label="5-95 %",
            gid="band",
        )
        ax.plot(t, column(table, stats["mean"]), color=c, lw=1.5, label="mean", gid="mean")
        if "p50" in stats:
            ax.plot(t, column(table, stats["p50"]), color="k", lw=0.8, ls="--", label="median")
        ax.set(xlabel="t (s)", title=output)
        ax.grid(alpha=0.3)
        ax.legend(fontsize="x-small")
    for ax in axes[len(found) :]:
        ax.set_visible(False)
    fig.suptitle(title)
    return fig

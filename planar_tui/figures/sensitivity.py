"""Figure of Sobol'/eFAST/PCE indices: paper A's Figs 5-6 and its Table-4 matrix.

Top: per output (a torque τi; for the motion-uncertainty indices, a joint angle or the
tip) stacked 100 % bars of the parameters' shares (the ``percent`` column), the methods
side by side (S: Sobol', E: eFAST), one bar per swept value (joint speed, or time), with
error bars of the half-widths scaled like the shares, :math:`100\\,c_j / \\sum_k S_k`
(``ST_conf`` or ``S1_conf``, whichever index the percentages were made from; drawn where
a half-width exists). Bottom: the Table-4 matrix (outputs × methods by parameters) at one
swept value as an annotated heat map.

Motion indices of more than ``MAX_BAR_TIMES`` times (a PCE's, at every recorded time) are
drawn instead as stacked shares against time, a panel per output and method
(:func:`draw_over_time`).

Reads the sensitivity CSV (``robot, posture, speed_rad_s, torque, parameter, method, S1,
S1_conf, ST, ST_conf, percent``) and the motion-uncertainty indices CSV (``output, t_s,
parameter, method, …``); extra columns are ignored.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from planar_tui.csvio import CsvTable
from planar_tui.figures.canvas import colour, new_figure
from planar_tui.figures.table import column, has_columns, text_column

INDEX_COLUMNS = ("parameter", "method", "S1", "S1_conf", "ST", "ST_conf", "percent")
SENSITIVITY = ("torque", "speed_rad_s", *INDEX_COLUMNS)
MOTION_INDICES = ("output", "t_s", *INDEX_COLUMNS)
METHOD_LABELS = {"sobol": "Sobol'", "efast": "eFAST", "pce": "PCE"}
#: Panels of bars per row.
PANELS_PER_ROW = 3
#: Times up to which the motion indices are drawn as bars (above: stacked shares).
MAX_BAR_TIMES = 8


def matches(header: tuple[str, ...]) -> bool:
    """A sensitivity CSV (the torques' indices)."""
    return has_columns(header, SENSITIVITY)


def matches_motion(header: tuple[str, ...]) -> bool:
    """A motion-uncertainty indices CSV (the simulated outputs' indices over time)."""
    return has_columns(header, MOTION_INDICES)


@dataclass
class Indices:
    """The rows of an indices table, column by column."""

    groups: list[str]  # the output of each row: "τ1", "tip_x_m", with the case prefixed
    swept: Any  # the swept value of each row (speed or time)
    swept_label: str
    parameters: list[str]
    methods: list[str]
    s1: Any
    s1_conf: Any
    st: Any
    st_conf: Any
    percent: Any


def read_indices(table: CsvTable) -> Indices:
    """The indices of a sensitivity or motion-uncertainty indices table."""
    header = table.header
    if has_columns(header, SENSITIVITY):
        groups = [f"τ{t}" for t in text_column(table, "torque")]
        cases = [
            " ".join(part for part in parts if part)
            for parts in zip(
                *(
                    text_column(table, c) if c in header else [""] * len(groups)
                    for c in ("robot", "posture")
                ),
                strict=True,
            )
        ]
        if len(set(cases)) > 1:
            groups = [f"{case}: {g}" for case, g in zip(cases, groups, strict=True)]
        swept, label = column(table, "speed_rad_s"), "joint speed (rad/s)"
    else:
        groups, swept, label = text_column(table, "output"), column(table, "t_s"), "t (s)"
    return Indices(
        groups,
        swept,
        label,
        text_column(table, "parameter"),
        text_column(table, "method"),
        column(table, "S1"),
        column(table, "S1_conf"),
        column(table, "ST"),
        column(table, "ST_conf"),
        column(table, "percent"),
    )


def _conf_percent(ix: Indices, rows: list[int]) -> list[float]:
    """Half-widths on the percent scale for the rows of one bar (NaN where none):
    :math:`100 c_j / \\sum_k \\max(S_k, 0)` with the index the percentages came from."""
    import numpy as np

    st, s1 = np.clip(ix.st[rows], 0, None), np.clip(ix.s1[rows], 0, None)
    pct = ix.percent[rows]
    use_st = bool(st.sum() > 0 and np.allclose(100 * st / st.sum(), pct, atol=0.05))
    chosen, conf = (st, ix.st_conf[rows]) if use_st else (s1, ix.s1_conf[rows])
    total = chosen.sum()
    return [100.0 * c / total if total > 0 and math.isfinite(c) else math.nan for c in conf]


def draw(table: CsvTable, title: str) -> Any:
    """Stacked share bars per output and the annotated matrix (see the module doc)."""

    ix = read_indices(table)
    if ix.swept_label == "t (s)" and len(set(ix.swept.tolist())) > MAX_BAR_TIMES:
        return draw_over_time(ix, title)
    groups = list(dict.fromkeys(ix.groups))
    params = list(dict.fromkeys(ix.parameters))
    methods = list(dict.fromkeys(ix.methods))
    swept = sorted(set(ix.swept.tolist()), key=lambda v: (math.isnan(v), v))
    where: dict[tuple, list[int]] = {}
    for row, key in enumerate(zip(ix.groups, ix.swept.tolist(), ix.methods, strict=True)):
        where.setdefault(key, []).append(row)
    rows_bars = math.ceil(len(groups) / PANELS_PER_ROW)
    cols = min(len(groups), PANELS_PER_ROW)
    heat_rows = len(groups) * len(methods)
    fig = new_figure(3.6 * cols + 2.0, 3.0 * rows_bars + 0.3 * heat_rows + 1.8)
    grid = fig.add_gridspec(
        rows_bars + 1, cols, height_ratios=[3.0] * rows_bars + [0.3 * heat_rows + 0.8]
    )
    width = 0.8 / len(methods)
    for g, group in enumerate(groups):
        ax = fig.add_subplot(grid[g // cols, g % cols], gid="bars")
        tops: list[tuple[float, float, float]] = []  # (x, top of a segment, half-width)
        for m, method in enumerate(methods):
            # segments[p]: (x, share, bottom) of parameter p at every swept value
            segments: list[list[tuple[float, float, float]]] = [[] for _ in params]
            for s, value in enumerate(swept):
                rows = where.get((group, value, method))
                if not rows:
                    continue
                x = s + (m - (len(methods) - 1) / 2) * width
                order = {ix.parameters[r]: r for r in rows}
                conf = dict(zip(rows, _conf_percent(ix, rows), strict=True))
                bottom = 0.0
                for p, param in enumerate(params):
                    r = order.get(param)
                    if r is None:
                        continue
                    share = float(ix.percent[r])
                    if math.isnan(share):  # an output without indices: no segment
                        continue
                    segments[p].append((x, share, bottom))
                    bottom += share
                    if math.isfinite(conf[r]) and conf[r] > 0:
                        tops.append((x, bottom, conf[r]))
                ax.text(
                    x,
                    101,
                    METHOD_LABELS.get(method, method)[0].upper(),
                    ha="center",
                    va="bottom",
                    fontsize="x-small",
                )
            for p, bars in enumerate(segments):
                if bars:
                    xs, shares, bottoms = zip(*bars, strict=True)
                    ax.bar(
                        xs,
                        shares,
                        width * 0.9,
                        bottom=bottoms,
                        color=colour(p, len(params)),
                        edgecolor="white",
                        linewidth=0.3,
                        hatch="//" if m else None,
                    )
        if tops:
            xs, ys, half = zip(*tops, strict=True)
            ax.errorbar(
                xs, ys, yerr=half, fmt="none", ecolor="k", elinewidth=0.6, capsize=1.5, gid="conf"
            )
        ax.set_xticks(range(len(swept)), [f"{v:g}" for v in swept])
        ax.set(ylim=(0, 108), title=group, xlabel=ix.swept_label)
        if g % cols == 0:
            ax.set_ylabel("share of the index (%)")
    from matplotlib.patches import Patch

    handles = [Patch(color=colour(p, len(params)), label=name) for p, name in enumerate(params)]
    handles += [
        Patch(
            facecolor="white",
            edgecolor="k",
            hatch="//" if m else None,
            label=f"{METHOD_LABELS.get(name, name)} ({METHOD_LABELS.get(name, name)[0].upper()})",
        )
        for m, name in enumerate(methods)
    ]
    fig.legend(handles=handles, loc="outside right upper", fontsize="small")
    _matrix(fig.add_subplot(grid[rows_bars, :], gid="matrix"), ix, groups, params, methods, swept)
    fig.suptitle(title)
    return fig


def _matrix(ax, ix: Indices, groups, params, methods, swept) -> None:
    """The Table-4 matrix at the middle swept value: rows output × method, columns the
    parameters, each cell its percent."""
    import numpy as np

    value = swept[len(swept) // 2]
    matrix = np.full((len(groups) * len(methods), len(params)), np.nan)
    for r in range(len(ix.groups)):
        if ix.swept[r] == value or (math.isnan(value) and math.isnan(ix.swept[r])):
            row = groups.index(ix.groups[r]) * len(methods) + methods.index(ix.methods[r])
            matrix[row, params.index(ix.parameters[r])] = ix.percent[r]
    ax.imshow(matrix, cmap="Blues", vmin=0, vmax=100, aspect="auto")
    for (i, j), v in np.ndenumerate(matrix):
        if math.isfinite(v):
            ax.text(
                j,
                i,
                f"{v:.1f}",
                ha="center",
                va="center",
                fontsize="x-small",
                color="white" if v > 60 else "black",
                gid="cell",
            )
    labels = [f"{g} {METHOD_LABELS.get(m, m)}" for g in groups for m in methods]
    ax.set_yticks(range(len(labels)), labels, fontsize="small")
    ax.set_xticks(range(len(params)), params, fontsize="small")
    ax.xaxis.tick_top()
    ax.set_title(
        f"percent of the index at {ix.swept_label.split(' (')[0]} = {value:g}",
        fontsize="medium",
        loc="left",
    )


def from_result(job: Any, result: Any) -> Any:
    """The figure of a finished sensitivity job (its CSV holds everything drawn)."""
    return draw(result.table, job.label)


def draw_over_time(ix: Indices, title: str) -> Any:
    """Stacked shares against time, a panel per (output, method): the motion indices of
    more than :data:`MAX_BAR_TIMES` times (the form SALib's maintainers suggest for
    time-varying outputs, SALib issue 525); a share is the height of its band."""
    import numpy as np

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
        ax.stackplot(
            times,
            shares,
            colors=[colour(p, len(params)) for p in range(len(params))],
            linewidth=0.3,
            edgecolor="white",
        )
        ax.set(
            ylim=(0, 100),
            xlim=(times[0], times[-1]),
            xlabel=ix.swept_label,
            title=f"{group} ({METHOD_LABELS.get(method, method)})",
        )
        if k % cols == 0:
            ax.set_ylabel("share of the index (%)")
    from matplotlib.patches import Patch

    handles = [Patch(color=colour(p, len(params)), label=name) for p, name in enumerate(params)]
    fig.legend(handles=handles, loc="outside right upper", fontsize="small")
    fig.suptitle(title)
    return fig

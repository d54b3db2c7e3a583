"""An optimisation's figure: the convergence of one objective (every feasible evaluation's
value and the best so far, against the evaluation number) or the front of two (every
feasible evaluation, the non-dominated ones joined), from
:func:`planar_tui.optimise.evaluations.figure_data`'s plain data."""

from __future__ import annotations

from typing import Any

from planar_tui.figures.canvas import colour, new_figure


def draw(data: dict[str, Any]) -> Any:
    """The figure of ``data`` (``names``, ``numbers``, ``points``, ``best``, ``history``,
    ``title``); more than two objectives: the first two."""
    figure = new_figure(6.4, 4.2)
    ax = figure.add_subplot()
    names, points, best = data["names"], data["points"], data["best"]
    if len(names) == 1:
        ax.plot(
            data["numbers"],
            [p[0] for p in points],
            ".",
            color=colour(0, 2),
            label="feasible evaluations",
        )
        ax.plot(
            range(1, len(data["history"]) + 1),
            data["history"],
            "-",
            color=colour(1, 2),
            label="best so far",
        )
        ax.set_xlabel("evaluation")
        ax.set_ylabel(names[0])
    else:
        ax.plot(
            [p[0] for p in points],
            [p[1] for p in points],
            ".",
            color=colour(0, 2),
            label="feasible evaluations",
        )
        front = sorted(best)
        ax.plot(
            [p[0] for p in front],
            [p[1] for p in front],
            "o-",
            color=colour(1, 2),
            label="Pareto set",
        )
        ax.set_xlabel(names[0])
        ax.set_ylabel(names[1])
    ax.grid(True, alpha=0.3)
    if points:
        ax.legend(loc="best", fontsize="small")
    ax.set_title(data["title"], fontsize="medium")
    return figure

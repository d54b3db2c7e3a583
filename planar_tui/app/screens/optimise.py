"""The app's optimisations: a screen that follows a running ``[[optimise]]`` table
generation by generation (every evaluation so far, the best so far) and shows the
finished one, with the convergence (one objective) or the front (two) plotted.

:class:`OptimiseScreen` is the sweep screen (:class:`~planar_tui.app.screens.sweep.SweepScreen`:
its table, its plot, its export key) over the evaluations' CSV
(:attr:`planar_tui.optimise.evaluations.OptimiseRun.table`), drawing the optimiser's figure data
(:func:`planar_tui.optimise.evaluations.figure_data`) instead of a figure against a key.
"""

from __future__ import annotations

import math
from typing import Any, ClassVar

from textual.binding import Binding
from textual_plotext import PlotextPlot

from planar_tui.app.screens.sweep import SweepScreen
from planar_tui.optimise.evaluations import figure_data, number_of


class OptimiseScreen(SweepScreen):
    """A running or finished optimisation (see the module's docstring). Escape closes it
    (the optimisation goes on: the palette's "Show optimisation" opens it again); ``x``
    cancels it, keeping the finished evaluations; ``ctrl+e`` exports the evaluations' CSV
    and the optimum's beside it."""

    BINDINGS: ClassVar = [Binding("x", "cancel_run", "Cancel (keep evaluations)")]
    DEFAULT_CSS = (
        SweepScreen.DEFAULT_CSS
        + """
    OptimiseScreen .sweep-pickers { display: none; }
    """
    )

    def axes(self, run: Any) -> list[str]:
        return ["evaluation"]

    def title_text(self) -> str:
        run = self.run
        opt = run.optimisation
        failed = f", {run.failed} failed" if run.failed else ""
        state = "cancelled" if run.cancelled else ("done" if run.certified else "running")
        best = run.best()
        if not best:
            found = "no feasible design yet"
        elif len(opt.objectives) == 1:
            found = f"best {opt.objectives[0].column} = {best_value(run):.6g}"
        else:
            found = f"Pareto set of {len(best)}"
        return (
            f"{opt.label} ({state}): generation {run.generations}, "
            f"{len(run.evaluations)}/{opt.budget} evaluations{failed}; {found}  "
            "(escape closes; ctrl+e: CSVs)"
        )

    def action_cancel_run(self) -> None:
        self.app.action_cancel()

    def update_run(self, run: Any) -> None:
        """Show ``run`` as it now is (a generation came back, or it ended)."""
        self.run = run
        self.table = run.table
        if self.is_mounted:
            self.query_one("#sweep-title").update(self.title_text())
            self.fill_table()
            self.draw()

    def draw(self) -> None:
        """The convergence (every feasible evaluation and the best so far) or the front
        (the first two objectives: every feasible evaluation, the non-dominated ones)."""
        plot = self.query_one("#sweep-plot", PlotextPlot)
        plot.display, self.query_one("#sweep-heat").display = True, False
        data = figure_data(self.run)
        plt = plot.plt
        plt.clear_data()
        plt.clear_figure()
        names, points = data["names"], data["points"]
        if len(names) == 1:
            if points:
                plt.scatter(data["numbers"], [p[0] for p in points], marker="•", label="feasible")
            history = [(k, v) for k, v in enumerate(data["history"], 1) if not math.isnan(v)]
            if history:
                plt.plot([k for k, _ in history], [v for _, v in history], label="best so far")
            plt.title(f"{names[0]} by evaluation")
        else:
            if points:
                plt.scatter(
                    [p[0] for p in points], [p[1] for p in points], marker="•", label="feasible"
                )
            front = sorted(data["best"])
            if front:
                plt.plot(
                    [p[0] for p in front], [p[1] for p in front], marker="o", label="Pareto set"
                )
            plt.title(f"{names[1]} against {names[0]}")
        plot.refresh()


def best_value(run: Any) -> float:
    """The single objective's best value so far (as the column's value)."""
    return number_of(run.optimisation, run.best()[0].outcome, run.optimisation.objectives[0].column)

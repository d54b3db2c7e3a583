"""The Motion tab: the band of every output over time (mean and 5-95 % band,
textual-plotext) and the band table and Table-4-shaped index tables of the CLI
(:mod:`~planar_tui.sensitivity.tables`): beside the plot when the results area has at least
:data:`BESIDE_COLUMNS` columns, else below it; ``ctrl+t`` steps the plot through the
outputs (θ1 … θn, tip x, tip y). Beside the plot, the band's arms at the scrubbed time
(:mod:`.playback`'s keys when the drawing has the focus): the arm at every joint's median
(its joints drawn) and at every joint's 5 % and 95 % percentiles (links only), with a cursor
line on the plot at the same time."""

from __future__ import annotations

from rich.console import Group
from rich.text import Text
from textual.app import ComposeResult
from textual.containers import Container, Horizontal, ScrollableContainer
from textual.widgets import Static
from textual_plotext import PlotextPlot

from planar_tui.app.widgets.panes import JobPane
from planar_tui.app.widgets.playback import PlaybackView
from planar_tui.app.widgets.robot_drawing import serial_scene
from planar_tui.app.widgets.simulate_pane import thin
from planar_tui.jobkind import JobResult
from planar_tui.motion.engine import output_labels
from planar_tui.motion.results import BAND_STATISTICS, band_grid
from planar_tui.presets import Job
from planar_tui.sensitivity.tables import VIEWS, fit_tables


def band_series(result, output: int) -> dict[str, list[float]]:
    """The plotted curves of one output: t, mean, 5th and 95th percentile (thinned)."""
    rows = thin(len(result.t_s))
    band = result.band[rows, :, output]
    return {
        "t_s": result.t_s[rows].tolist(),
        "mean": band[:, 0].tolist(),
        "p5": band[:, 2].tolist(),
        "p95": band[:, 4].tolist(),
    }


#: Styles of the band's 5 % and 95 % arms (links only).
P5_STYLE, P95_STYLE = "blue", "magenta"


def band_arms_deg(result, row: int) -> dict[str, list[float]] | None:
    """Relative joint angles (deg) of the band's arms at recorded ``row``: every joint at
    its 5th (``p5``), 50th (``p50``) and 95th (``p95``) percentile; ``None`` without the
    angle outputs."""
    import math

    columns = [k for k, name in enumerate(result.names) if name.startswith("theta")]
    if not columns:
        return None
    band = result.band[row]
    return {
        stat: [math.degrees(float(band[index, k])) for k in columns]
        for stat, index in (("p5", 2), ("p50", 3), ("p95", 4))
    }


def wrapped_band_grids(result, width: int, row: int = -1) -> tuple[list, int]:
    """The band table at recorded ``row`` turned (statistics as rows, outputs as columns,
    5 significant digits) and wrapped into tables of as many output columns as fit
    ``width`` cells (at least one), so every output stays visible in a narrow pane;
    returns the tables and their widest width."""
    from rich import box
    from rich.table import Table

    labels = output_labels(result.names)
    cells = [[f"{v:.5g}" for v in result.band[row, :, k]] for k in range(len(labels))]
    widths = [
        max(len(label), *map(len, column)) for label, column in zip(labels, cells, strict=True)
    ]
    first = max(map(len, BAND_STATISTICS))
    groups: list[list[int]] = [[]]
    used = first
    for k, cell_width in enumerate(widths):
        if groups[-1] and used + 2 + cell_width > width:
            groups.append([])
            used = first
        groups[-1].append(k)
        used += 2 + cell_width
    tables, widest = [], 0
    for group in groups:
        table = Table(box=box.SIMPLE_HEAD, show_edge=False, pad_edge=False, padding=(0, 1, 0, 0))
        table.add_column("", width=first, no_wrap=True)
        for k in group:
            table.add_column(labels[k], justify="right", width=widths[k], no_wrap=True)
        for s, statistic in enumerate(BAND_STATISTICS):
            table.add_row(statistic, *(cells[k][s] for k in group))
        tables.append(table)
        widest = max(widest, first + sum(2 + widths[k] for k in group))
    return tables, widest


#: Lines of the band plot (the results area scrolls below it).
PLOT_LINES = 16
#: Columns of the results area from which the tables stand beside the plot (then fitted
#: to half of them), not below it.
BESIDE_COLUMNS = 150


class MotionPane(JobPane):
    """Simulation, tolerances, methods, times, outputs, device; band plot and indices."""

    kind = "motion_uncertainty"

    DEFAULT_CSS = """
    #motion-results { height: 1fr; scrollbar-gutter: stable; scrollbar-size: 1 1; }
    #motion-results Static { width: 100%; }
    #motion-body { height: auto; layout: vertical; }
    #motion-body.beside { layout: horizontal; }
    #motion-body.beside #motion-tables { margin-left: 1; }
    #motion-top { height: auto; }
    #band-arms { width: 1fr; min-width: 14; height: 100%; }
    #band-plot { width: 2fr; }
    #band-readout { height: auto; }
    """

    #: The output the plot shows (``ctrl+t`` steps through them).
    output = 0

    def compose_results(self) -> ComposeResult:
        with ScrollableContainer(id="motion-results"):
            yield Static("Run the study (F5) to plot the band.", id="result-text", markup=False)
            yield Static("", id="band-readout", markup=False)
            with Container(id="motion-body"):
                with Horizontal(id="motion-top"):
                    yield PlotextPlot(id="band-plot")
                    yield PlaybackView("(the band's arms: run the study)", id="band-arms")
                yield Static("", id="motion-tables")

    def on_mount(self) -> None:
        if self.available():  # the app's stylesheet gives every plot 1fr: this one scrolls
            self.query_one("#motion-top").styles.height = PLOT_LINES

    def render_result(self, job: Job, result: JobResult) -> None:
        lengths = list(job.robot.lengths_m)
        view = self.query_one("#band-arms", PlaybackView)
        same_run = view.frame_scene is not None and len(view.times) == len(result.t_s)

        def frame(row: int):
            arms = band_arms_deg(result, row)
            if arms is None:
                return None
            ghosts = [(arms["p5"], P5_STYLE), (arms["p95"], P95_STYLE)]
            return serial_scene(lengths, arms["p50"], ghosts, caption=f"t={result.t_s[row]:.3g} s")

        view.load(result.t_s, frame, view.row if same_run else len(result.t_s) - 1)
        self.draw_plot()
        self.query_one("#result-text", Static).update(result.summary)
        grid, band_width = band_grid(result)

        def fitted(width: int) -> tuple[list, int]:
            """The band and index tables fitted to ``width`` and their widest line."""
            parts: list = [
                Text(f"band at t = {result.t_s[-1]:g} s (ctrl+t: next output)", style="bold")
            ]
            if band_width <= width:
                parts.append(grid)
                natural = band_width
            else:  # too narrow: turned and wrapped, every output still shown
                grids, natural = wrapped_band_grids(result, width)
                parts += grids
            if result.analyses:
                indices = fit_tables(result.analyses, VIEWS[0], width, "ST")
                parts.append(indices.renderable)
                natural = max(natural, indices.width)
            parts += [Text(f"note: {note}", style="dim") for note in result.notes]
            return parts, natural

        area = max(20, self.query_one("#motion-results").scrollable_content_region.width)
        beside = False
        if area >= BESIDE_COLUMNS:  # the tables in half the width, the plot the rest (1fr)
            parts, natural = fitted(area // 2)
            beside = natural <= area // 2
        if not beside:
            parts, natural = fitted(area)
            natural = max(area, natural)
        self.query_one("#motion-body").set_class(beside, "beside")
        tables = self.query_one("#motion-tables", Static)
        tables.styles.width = natural  # never shrunk: a wide table scrolls sideways
        tables.update(Group(*parts))

    def on_playback_view_moved(self, message: PlaybackView.Moved) -> None:
        self.draw_plot()

    def draw_plot(self) -> None:
        """The band plot of the output shown, with the cursor at the scrubbed time."""
        result = self.result
        if result is None or not self.is_attached:
            return
        labels = output_labels(result.names)
        self.output %= len(labels)
        series = band_series(result, self.output)
        plot = self.query_one("#band-plot", PlotextPlot)
        plt = plot.plt
        plt.clear_data()
        plt.clear_figure()
        plt.plot(series["t_s"], series["p95"], marker="+", label="95 %")
        plt.plot(series["t_s"], series["mean"], marker="o", label="mean")
        plt.plot(series["t_s"], series["p5"], marker="-", label="5 %")
        view = self.query_one("#band-arms", PlaybackView)
        plt.vline(view.t_s, "red")
        unit = "rad" if result.names[self.output].endswith("_rad") else "m"
        plt.title(f"{labels[self.output]} ({unit}) vs t (s): o mean, + - 5-95 %")
        plot.refresh()
        if len(view.times):
            band = result.band[view.row, :, self.output]
            self.query_one("#band-readout", Static).update(
                f"{view.status()}  {labels[self.output]}: 5 % {band[2]:.5g}  "
                f"median {band[3]:.5g}  95 % {band[4]:.5g} {unit}  "
                f"(arms: median with joints, 5 % {P5_STYLE}, 95 % {P95_STYLE})"
            )

    def action_toggle_view(self) -> None:
        """Plot the next output's band."""
        self.output += 1
        self.rerender()

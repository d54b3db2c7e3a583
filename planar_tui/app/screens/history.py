"""The run history (``F10``): every run of the session and every result opened from a
file, one row each (kind, label, time, seed, N, form, ε, the preset's digest, summary),
the highlighted run's provenance and settings below; and the comparison of two runs of a
kind (:class:`CompareScreen`, from :func:`planar_tui.app.compare.compare_runs`).

Keys: ``space`` marks a run (A, then B); ``c`` compares the two marked, or the highlighted
run with the latest other run of its kind; ``o`` opens a result CSV into the history;
escape closes.
"""

from __future__ import annotations

from typing import Any, ClassVar

from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import VerticalScroll
from textual.screen import Screen
from textual.widgets import DataTable, Footer, Static

from planar_tui.app import recent
from planar_tui.app.compare import Comparison, compare_runs, series_glyphs, series_legend
from planar_tui.app.runs import Run, RunHistory
from planar_tui.app.screens.picker import result_picker

#: The history table's columns after the mark, number, kind and label.
HEADLINE = ("time", "seed", "N", "form", "ε (cm)", "preset")


class HistoryScreen(Screen[None]):
    """The session's runs (see the module's docstring)."""

    BINDINGS: ClassVar = [
        Binding("escape", "close", "Close"),
        Binding("space", "mark", "Mark A/B"),
        Binding("c", "compare", "Compare"),
        Binding("o", "open_result", "Open CSV"),
    ]
    DEFAULT_CSS = """
    HistoryScreen #history-title { height: 1; text-style: bold; }
    HistoryScreen #history-table { height: 1fr; min-height: 5; }
    HistoryScreen #history-detail { height: auto; max-height: 14; border-top: solid $primary; }
    """

    def __init__(self, history: RunHistory):
        super().__init__()
        self.history = history
        #: The runs marked for comparison, in the order marked (A first).
        self.marked: list[Run] = []

    def compose(self) -> ComposeResult:
        yield Static("", id="history-title", markup=False)
        yield DataTable(id="history-table", cursor_type="row", zebra_stripes=True)
        with VerticalScroll(id="history-detail"):
            yield Static("", id="history-text", markup=False)
        yield Footer(compact=True)

    def on_mount(self) -> None:
        table = self.query_one(DataTable)
        table.add_columns("", "#", "kind", "label", *HEADLINE, "result")
        self.refill()
        table.focus()

    def refill(self) -> None:
        """Show every run (the newest highlighted) and the title's counts."""
        table = self.query_one(DataTable)
        table.clear()
        for run in self.history:
            mark = "A" if self.marked[:1] == [run] else "B" if self.marked[1:2] == [run] else ""
            cells = run.headline()
            table.add_row(
                mark,
                str(run.number),
                run.kind,
                run.label,
                *(cells[name] for name in HEADLINE),
                run.summary,
                key=str(run.number),
            )
        if len(self.history):
            table.move_cursor(row=len(self.history) - 1)
        count = len(self.history)
        self.query_one("#history-title", Static).update(
            f"Run history: {count} run{'s' if count != 1 else ''}"
            + (", newest last" if count else " yet (F5 runs a job; o opens a result CSV)")
        )
        self.show_detail()

    def highlighted(self) -> Run | None:
        table = self.query_one(DataTable)
        if not len(self.history) or table.cursor_row is None:
            return None
        row = min(max(table.cursor_row, 0), len(self.history) - 1)
        return self.history.runs[row]

    def show_detail(self) -> None:
        run = self.highlighted()
        text = run.describe() if run is not None else ""
        self.query_one("#history-text", Static).update(text)

    def on_data_table_row_highlighted(self, event: DataTable.RowHighlighted) -> None:
        self.show_detail()

    def action_mark(self) -> None:
        """Mark the highlighted run (A, then B; a third mark starts over)."""
        run = self.highlighted()
        if run is None:
            return
        if run in self.marked:
            self.marked.remove(run)
        elif len(self.marked) >= 2:
            self.marked = [run]
        else:
            self.marked.append(run)
        row = self.query_one(DataTable).cursor_row
        self.refill()
        self.query_one(DataTable).move_cursor(row=row)

    def pair(self) -> tuple[Run, Run] | str:
        """The runs to compare (A, B), or why there are none."""
        if len(self.marked) == 2:
            return self.marked[0], self.marked[1]
        run = self.highlighted()
        if run is None:
            return "No run yet: run a job (F5) or open a result CSV (o)."
        other = self.history.partner(run)
        if other is None:
            return f"Only one {run.kind} run: run another, or open one (o), to compare."
        return (other, run) if other.number < run.number else (run, other)

    def action_compare(self) -> None:
        pair = self.pair()
        if isinstance(pair, str):
            self.notify(pair, severity="warning")
            return
        try:
            comparison = compare_runs(*pair)
        except ValueError as error:
            self.notify(str(error), severity="warning")
            return
        self.app.push_screen(CompareScreen(comparison))

    def action_open_result(self) -> None:
        def chosen(path: str | None) -> None:
            if path:
                self.open_result(path)

        self.app.push_screen(result_picker(getattr(self.app, "output_dir", ".")), chosen)

    def open_result(self, path: str) -> Run | None:
        """Open a result CSV into the history (its sidecar's settings, or what its header
        says); a file that cannot be opened is a notification, nothing else changes."""
        try:
            run = self.history.add_csv(path)
        except ValueError as error:
            self.notify(str(error), title="Not opened", severity="error")
            return None
        note = recent.remember("results", path)
        if note is not None:
            self.notify(note, title="Recent files", severity="warning", timeout=20)
        self.refill()
        if run.note:
            self.notify(run.note, title=f"Opened {run.label}", severity="warning")
        return run

    def action_close(self) -> None:
        self.dismiss(None)


class CompareScreen(Screen[None]):
    """Two runs side by side: the notes (what differs in their settings), the table of
    A, B and B − A, an overlay map (workspaces) or the curves of both (simulations)."""

    BINDINGS: ClassVar = [Binding("escape", "close", "Close")]
    DEFAULT_CSS = """
    CompareScreen #compare-title { height: 1; text-style: bold; }
    CompareScreen #compare-notes { height: auto; max-height: 6; }
    CompareScreen #compare-table { height: 1fr; min-height: 5; }
    CompareScreen #compare-overlay { height: auto; }
    CompareScreen #compare-legend { height: auto; }
    CompareScreen #compare-plot { height: 1fr; min-height: 10; }
    """

    def __init__(self, comparison: Comparison):
        super().__init__()
        self.comparison = comparison

    def compose(self) -> ComposeResult:
        c = self.comparison
        yield Static(c.title + "   (escape: back)", id="compare-title", markup=False)
        with VerticalScroll(id="compare-notes"):
            yield Static("\n".join(c.notes), markup=False)
        yield DataTable(id="compare-table", zebra_stripes=True)
        if c.overlay:
            yield Static(c.overlay, id="compare-overlay", markup=False)
        if c.series:
            from textual_plotext import PlotextPlot

            names = [name for name, _, _ in c.series]
            yield Static(series_legend(names), id="compare-legend", markup=False)
            yield PlotextPlot(id="compare-plot")
        yield Footer(compact=True)

    def on_mount(self) -> None:
        table = self.query_one(DataTable)
        table.add_columns(*self.comparison.header)
        table.add_rows(self.comparison.rows)
        table.focus()
        if self.comparison.series:
            self.draw_series()

    def draw_series(self) -> None:
        """Both runs' joint angles on one plot, a glyph per curve (A's digits, B's letters:
        told apart without colour; the legend line above names them)."""
        from textual_plotext import PlotextPlot

        plot: Any = self.query_one("#compare-plot", PlotextPlot)
        plt = plot.plt
        plt.clear_data()
        series = self.comparison.series
        glyphs = series_glyphs([name for name, _, _ in series])
        for (_, t, y), glyph in zip(series, glyphs, strict=True):
            plt.plot(t, y, marker=glyph)
        plt.title("joint angles (deg) against t (s): A and B")
        plot.refresh()

    def action_close(self) -> None:
        self.dismiss(None)

"""The app's sweeps: a dialog that turns the current tab's job into a sweep, and a screen
that shows a finished sweep's table with a plot of any figure.

:class:`SweepDialog` asks for one or two key paths (completed from the job's keys), their
values (``-20, 0, 20`` or ``25..35 x5``), how they combine and how many worker processes
run the points; the sweep is built and checked by
:func:`planar_tui.sweep.spec.build_sweep` (the CLI's checks for ``[[sweep]]`` tables) and
a problem is shown in the dialog, which stays open. :class:`SweepScreen` shows the sweep
CSV (:attr:`planar_tui.sweep.service.SweepRun.table`) and a figure against one key (a
line, failed points marked ``x``) or two (a character-cell heat map).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any, ClassVar

from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Horizontal, Vertical
from textual.screen import ModalScreen, Screen
from textual.suggester import SuggestFromList
from textual.widgets import Button, DataTable, Input, Label, Select, Static
from textual_plotext import PlotextPlot

from planar_tui.app.sweep_data import (
    VALUES_HINT,
    ValuesError,
    heat_grid,
    line_series,
    numeric_figures,
    parse_values,
    values_text,
    varying_figures,
)
from planar_tui.app.widgets.heat_map import heat_map_lines
from planar_tui.errors import PresetError
from planar_tui.figures.sweep import is_numeric
from planar_tui.plan import plan_sweep

#: Most rows the sweep screen's table shows (the CSV export has them all).
MAX_TABLE_ROWS = 2000
#: Sweeps of at most this many points are validated point by point in the dialog (about
#: 0.1 ms a point), so a bad value is shown there; larger ones in the job's thread.
DIALOG_CHECK_POINTS = 2000
#: Shown in the "down" picker for a line plot (no second key).
NO_KEY = "(none: a line)"


class SweepDialog(ModalScreen[tuple[Any, int, Any] | None]):
    """Make a sweep of a job: dismisses with ``(sweep, workers, points)`` (``points``:
    the validated points, or ``None`` for a sweep too large to check here), or ``None`` on
    Escape.

    ``build(values, combine)`` makes the sweep from the key paths' values (a dict of
    path -> list or ``{from, to, count}``) or raises :class:`PresetError`, whose message
    the dialog shows; so does a point whose value is invalid for its key.
    """

    BINDINGS: ClassVar = [
        Binding("escape", "dismiss_none", "Cancel"),
        Binding("enter", "submit", "Run", show=False),  # on the grid/zip list too
    ]

    def __init__(
        self, job_key: str, paths: Sequence[str], build: Callable[..., Any], own: Any = None
    ):
        super().__init__()
        self.job_key = job_key
        self.paths = list(paths)
        self.build = build
        #: The preset's own ``[[sweep]]`` of this job (a checked sweep), or ``None``: the
        #: dialog opens filled in with it, and runs it as written while left so.
        self.own = own
        self.filled: tuple = ()

    def compose(self) -> ComposeResult:
        suggester = SuggestFromList(self.paths, case_sensitive=True)
        with Vertical(classes="dialog sweep-dialog"):
            yield Label(f"Sweep of {self.job_key}", classes="dialog-title")
            for row in (1, 2):
                with Horizontal(classes="sweep-row"):
                    yield Input(
                        placeholder="key path" if row == 1 else "second key path (optional)",
                        suggester=suggester,
                        id=f"sweep-key-{row}",
                        classes="sweep-key",
                    )
                    yield Input(
                        placeholder="values", id=f"sweep-values-{row}", classes="sweep-values"
                    )
            with Horizontal(classes="sweep-row"):
                yield CombineSelect(
                    [("grid: every combination", "grid"), ("zip: same-length lists", "zip")],
                    value="grid",
                    allow_blank=False,
                    compact=True,
                    id="sweep-combine",
                )
                yield Label(" workers ", classes="sweep-label")
                yield Input("1", id="sweep-workers", classes="sweep-workers")
            yield Static("", id="sweep-problem", markup=False)
            yield Static(
                f"keys: {', '.join(self.paths)}; list items as KEY[k]\n{VALUES_HINT}\n"
                "workers: 1 runs here; more start a local Dask cluster of processes\n"
                "Enter: run   Escape: cancel",
                classes="dialog-hint",
                markup=False,
            )
            with Horizontal(classes="dialog-buttons"):
                # one row each: with an error shown the help still fits 80×24
                yield Button("Run sweep (Enter)", id="sweep-run", variant="success", compact=True)
                yield Button("Cancel (esc)", id="sweep-cancel", compact=True)

    def on_mount(self) -> None:
        self.query_one("#sweep-key-1", Input).focus()
        if self.own is not None:
            self.fill(self.own)

    def fill(self, sweep: Any) -> None:
        """Show the preset's sweep ``sweep`` (up to two of its keys with their values, how
        they combine; a sampled sweep's ranges are not typed here) and say so."""
        entries = list(sweep.source.get("values", {}).items()) if sweep.sample is None else []
        for row, (key, entry) in enumerate(entries[:2], start=1):
            self.query_one(f"#sweep-key-{row}", Input).value = key
            self.query_one(f"#sweep-values-{row}", Input).value = values_text(entry)
        self.query_one("#sweep-combine", Select).value = sweep.combine
        self.filled = self.typed()
        line = self.query_one("#sweep-problem", Static)
        line.update(
            f"the preset's {sweep.name}: {sweep.point_count} points, "
            f"{sweep.output}; Enter runs it as written (edit to change)"
        )
        line.add_class("-shown")

    def typed(self) -> tuple:
        """What the dialog's fields hold now (to tell the preset's sweep left as filled)."""
        rows = [
            self.query_one(f"#sweep-{part}-{row}", Input).value
            for row in (1, 2)
            for part in ("key", "values")
        ]
        return (*rows, self.query_one("#sweep-combine", Select).value)

    def problem(self, text: str) -> None:
        """Say why the sweep cannot run (the dialog stays open)."""
        line = self.query_one("#sweep-problem", Static)
        line.update(f"error: {text}")
        line.add_class("-shown")

    def chosen_values(self) -> dict[str, Any]:
        """The key paths typed with their values (raises :class:`ValuesError`; two rows
        of one key too)."""
        values: dict[str, Any] = {}
        rows: dict[str, int] = {}
        for row in (1, 2):
            key = self.query_one(f"#sweep-key-{row}", Input).value.strip()
            text = self.query_one(f"#sweep-values-{row}", Input).value
            if not key and not text.strip():
                continue
            if not key:
                raise ValuesError(f"row {row}: values without a key path")
            if key in rows:
                raise ValuesError(f"row {row}: {key} is already row {rows[key]}'s key")
            rows[key] = row
            values[key] = parse_values(text)
        if not values:
            raise ValuesError("no key path: type one (e.g. " + self.paths[0] + ")")
        return values

    def submit(self) -> None:
        """Build the sweep and check its points; dismiss with it, or show the problem."""
        try:
            workers_text = self.query_one("#sweep-workers", Input).value.strip()
            # isdecimal: "²" is a digit int() does not read
            if not workers_text.isdecimal() or int(workers_text) < 1:
                raise ValuesError(f"workers {workers_text!r} (expected a whole number ≥ 1)")
            if self.own is not None and self.typed() == self.filled:
                sweep = self.own  # as the preset wrote it (its output, plot, sampling)
            else:
                combine = str(self.query_one("#sweep-combine", Select).value)
                sweep = self.build(self.chosen_values(), combine)
            small = sweep.point_count <= DIALOG_CHECK_POINTS
            points = plan_sweep(sweep).points if small else None
        except ValuesError as error:
            self.problem(str(error))
            return
        except PresetError as error:
            self.problem(error.message)
            return
        self.dismiss((sweep, int(workers_text), points))

    def on_input_submitted(self, event: Input.Submitted) -> None:
        event.stop()
        self.submit()

    def on_button_pressed(self, event: Button.Pressed) -> None:
        event.stop()
        if event.button.id == "sweep-run":
            self.submit()
        else:
            self.dismiss(None)

    def action_submit(self) -> None:
        self.submit()

    def action_dismiss_none(self) -> None:
        self.dismiss(None)


class CombineSelect(Select[str], inherit_bindings=False):
    """The grid/zip list: opened with the arrows or space; Enter runs the sweep (the
    dialog's binding) rather than reopening the list."""

    BINDINGS: ClassVar = [Binding("down,space,up", "show_overlay", "Show menu", show=False)]


class SweepScreen(Screen[None]):
    """A finished sweep: its table (one row per point) and a figure plotted against one
    varied key or two. Escape closes it; ``ctrl+e`` exports the sweep CSV, ``ctrl+l``
    (the app's) writes its figure."""

    BINDINGS: ClassVar = [
        Binding("escape,q", "close", "Close"),
        Binding("ctrl+e", "export", "Export CSV"),  # the app's ctrl+e comes here too
    ]
    DEFAULT_CSS = """
    SweepScreen { layout: vertical; }
    SweepScreen #sweep-title { height: auto; padding: 0 1; text-style: bold; }
    SweepScreen .sweep-pickers { height: 1; }
    SweepScreen .sweep-pickers Select { width: 1fr; }
    SweepScreen #sweep-table { height: 1fr; }
    SweepScreen #sweep-plot, SweepScreen #sweep-heat { height: 1fr; }
    SweepScreen #sweep-heat { padding: 0 1; }
    """

    def __init__(self, run: Any, export: Callable[[Any], None]):
        super().__init__()
        self.run = run
        self.export = export
        self.table = run.table
        self.paths = self.axes(run)
        self.figures = numeric_figures(self.table, self.paths)
        #: The figure shown first: an output (one that varies), else the first.
        self.figure = ([*varying_figures(self.table, self.figures), *self.figures] or [""])[0]
        #: The varied keys whose values are numbers: the axes here (a text or list-valued
        #: key is one series per value; the figure file, ctrl+l, puts it on an axis).
        self.plottable_paths = [path for path in self.paths if is_numeric(self.table, path)]

    def axes(self, run: Any) -> list[str]:
        """The columns a figure is plotted against (the varied keys)."""
        return [path.text for path in run.sweep.paths]

    def title_text(self) -> str:
        """The screen's first line: what ran and the keys to press."""
        run = self.run
        failed = f", {run.failed} failed" if run.failed else ""
        done = f"{len(run.outcomes)} points"
        if run.cancelled:
            done = f"cancelled: {len(run.outcomes)} of {len(run.points)} points run"
        return f"{run.sweep.label}: {done}{failed}  (escape closes; ctrl+e: CSV, ctrl+l: figure)"

    def compose(self) -> ComposeResult:
        yield Static(self.title_text(), id="sweep-title", markup=False)
        yield DataTable(id="sweep-table", zebra_stripes=True)
        with Horizontal(classes="sweep-pickers"):
            # no value given when there is no option (a sweep over text keys only)
            yield Select(
                [(name, name) for name in self.figures],
                compact=True,
                **({"value": self.figure} if self.figures else {}),
                prompt="figure",
                id="sweep-figure",
            )
            yield Select(
                [(path, path) for path in self.plottable_paths],
                compact=True,
                **({"value": self.plottable_paths[0]} if self.plottable_paths else {}),
                prompt="across",
                id="sweep-across",
            )
            downs = [(NO_KEY, NO_KEY)] + [(p, p) for p in self.plottable_paths[1:]]
            # a heat map for a grid of two keys; zipped keys vary together: a line
            grid = len(self.plottable_paths) > 1 and self.run.sweep.combine == "grid"
            down = self.plottable_paths[1] if grid else NO_KEY
            yield Select(downs, compact=True, value=down, allow_blank=False, id="sweep-down")
        yield PlotextPlot(id="sweep-plot")
        yield Static("", id="sweep-heat", markup=False)

    def on_mount(self) -> None:
        self.query_one(DataTable).add_columns(*self.table.header)
        self.fill_table()
        self.draw()

    def fill_table(self) -> None:
        """Show the rows of :attr:`table` (at most :data:`MAX_TABLE_ROWS`)."""
        table = self.query_one(DataTable)
        table.clear()
        for row in list(self.table.rows)[:MAX_TABLE_ROWS]:
            table.add_row(
                *(f"{cell:.6g}" if isinstance(cell, float) else str(cell) for cell in row)
            )

    def on_select_changed(self, event: Select.Changed) -> None:
        event.stop()
        self.draw()

    def choice(self, selector: str) -> str | None:
        value = self.query_one(selector, Select).value
        # the options are text; no selection is a sentinel (Select.NULL, or BLANK before)
        return value if isinstance(value, str) and value != NO_KEY else None

    def draw(self) -> None:
        """Plot the chosen figure: a line against one key, a heat map against two."""
        figure, across, down = (
            self.choice(s) for s in ("#sweep-figure", "#sweep-across", "#sweep-down")
        )
        plot, heat = self.query_one("#sweep-plot", PlotextPlot), self.query_one("#sweep-heat")
        two = down is not None and down != across
        plot.display, heat.display = not two, two
        if figure is None or across is None:
            heat.update(
                "No numeric figure or key to plot here"
                + (
                    "; ctrl+l writes the figure, the keys' values on its axes."
                    if figure is not None
                    else "."
                )
            )
            plot.display, heat.display = False, True
            return
        if two:
            xs, ys, grid = heat_grid(self.table, across, down, figure)
            width = max(40, self.size.width - 2)
            heat.update(
                "\n".join(
                    heat_map_lines(
                        xs,
                        ys,
                        grid,
                        across_name=across,
                        down_name=down,
                        figure_name=figure,
                        width=width,
                    )
                )
            )
            return
        self.draw_line(plot, figure, across)

    def draw_line(self, plot: PlotextPlot, figure: str, across: str) -> None:
        """The figure against ``across``, one series per combination of the other keys."""
        plt = plot.plt
        plt.clear_data()
        plt.clear_figure()
        series = line_series(self.table, self.paths, across, figure)
        markers = "123456789"
        for number, line in enumerate(series):
            if line.x:
                plt.plot(
                    line.x,
                    line.y,
                    marker=markers[number % 9] if len(series) > 1 else "•",
                    label=line.label or None,
                )
        failed = [x for line in series for x in line.failed_x]
        if failed:
            low = min((y for line in series for y in line.y), default=0.0)
            plt.scatter(failed, [low] * len(failed), marker="x", label="failed")
        plt.title(f"{figure} vs {across}" + ("; x: failed points" if failed else ""))
        plot.refresh()

    def action_close(self) -> None:
        self.dismiss(None)

    def action_export(self) -> None:
        self.export(self.run)

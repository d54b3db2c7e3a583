"""The app's sweeps (F8): the dialog, the run with progress and cancel, the result screen's
table (against separate runs of the same jobs) and its line and heat-map plots."""

from __future__ import annotations

import csv
import time

import pytest
from textual.widgets import DataTable, Input

from planar_tui.app.screens.sweep import SweepDialog, SweepScreen
from planar_tui.app.sweep_data import ValuesError, heat_grid, parse_values
from planar_tui.app.widgets.heat_map import MISSING, SHADES, heat_map_lines, shade_level
from planar_tui.batch import run_job
from planar_tui.csvio import CsvTable
from planar_tui.presets import load_preset
from tests.test_app import SIZE, async_test, finish, make_app

pytestmark = pytest.mark.slow  # end to end (see pyproject.toml's markers)


def test_values_text():
    assert parse_values("-20, 0, 20") == [-20, 0, 20]
    assert parse_values("25..35 x5") == {"from": 25.0, "to": 35.0, "count": 5}
    assert parse_values(' "slope", "natural" ') == ["slope", "natural"]
    assert parse_values("[0, 1], [2, 3]") == [[0, 1], [2, 3]]
    for bad in ("", "1,,2", "25..35"):
        try:
            parse_values(bad)
        except ValuesError as error:
            assert "expected" not in str(error) or "values" in str(error)
        else:
            raise AssertionError(f"{bad!r} was read")


def test_heat_map_shades_order_and_missing_cells():
    lo, hi = 2.0, 7.0
    levels = [shade_level(v, lo, hi) for v in (2.0, 3.0, 4.5, 6.0, 7.0)]
    assert levels == sorted(levels) and levels[0] == 0 and levels[-1] == len(SHADES) - 1
    lines = heat_map_lines(
        [1, 2],
        [10, 20],
        [[2.0, None], [7.0, float("nan")]],
        across_name="a",
        down_name="b",
        figure_name="f",
        width=40,
    )
    top, bottom = lines[2], lines[3]  # largest "down" value first
    assert top.startswith("20") and bottom.startswith("10")
    assert SHADES[-1] in top and MISSING in top
    assert MISSING in bottom and SHADES[-1] not in bottom


def test_heat_grid_bins_a_sampled_design_and_averages_cells():
    rows = [
        [1, 0.0, 0.0, 1.0, "ok", "", 0.1],
        [2, 0.0, 0.0, 3.0, "ok", "", 0.1],  # same cell: mean 2
        [3, 1.0, 0.0, 5.0, "ok", "", 0.1],
        [4, 1.0, 1.0, 9.0, "failed", "boom", 0.1],
    ]
    table = CsvTable(("point", "a", "b", "f", "status", "message", "seconds"), rows)
    xs, ys, grid = heat_grid(table, "a", "b", "f")
    assert xs == [0.0, 1.0] and ys == [0.0, 1.0]
    assert grid == [[2.0, 5.0], [None, None]]


async def _open_dialog(app, pilot, tab: str) -> SweepDialog:
    app.action_show_tab(tab)
    await pilot.pause()
    await pilot.press("f8")
    await pilot.pause()
    assert isinstance(app.screen, SweepDialog)
    return app.screen


def _fill(dialog: SweepDialog, rows: list[tuple[str, str]]) -> None:
    for number, (key, values) in enumerate(rows, start=1):
        dialog.query_one(f"#sweep-key-{number}", Input).value = key
        dialog.query_one(f"#sweep-values-{number}", Input).value = values


@async_test
async def test_sweep_of_the_simulate_tab_matches_separate_runs(tmp_path):
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        dialog = await _open_dialog(app, pilot, "simulate")
        _fill(dialog, [("robot.masses_kg[1]", "1.0..2.0 x3"), ("duration_s", "0.1, 0.2")])
        await pilot.press("enter")
        await finish(app, pilot)
        await pilot.pause(0.2)
        assert isinstance(app.screen, SweepScreen), app.screen
        screen = app.screen
        assert screen.query_one(DataTable).row_count == 6
        heat = str(screen.query_one("#sweep-heat").render())
        assert "robot.masses_kg[1]" in heat and "duration_s" in heat
        table = screen.run.table
    header = list(table.header)
    assert header[:3] == ["point", "robot.masses_kg[1]", "duration_s"]
    document = (tmp_path / "tiny.toml").read_text()
    for row in table.rows:
        mass, duration = row[1], row[2]
        edited = document.replace("masses_kg = [1.126,", f"masses_kg = [{mass!r},").replace(
            "duration_s = 0.2", f"duration_s = {duration!r}"
        )
        path = tmp_path / f"point-{row[0]}.toml"
        path.write_text(edited)
        (job,) = [job for job in load_preset(path).jobs if job.kind == "simulate"]
        result = run_job(job)
        final = list(csv.reader(result.table.lines()))[-1]
        theta_end = header.index("theta1_end_rad")
        assert row[header.index("status")] == "ok"
        assert row[theta_end] == float(final[1])  # the simulate CSV's θ1 at the end


@async_test
async def test_line_plot_for_one_key_and_export(tmp_path):
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        dialog = await _open_dialog(app, pilot, "workspace")
        _fill(dialog, [("orientation_deg", "-10, 0, 10")])
        await pilot.press("enter")
        await finish(app, pilot)
        await pilot.pause(0.2)
        screen = app.screen
        assert isinstance(screen, SweepScreen)
        assert screen.query_one("#sweep-plot").display
        assert not screen.query_one("#sweep-heat").display
        await pilot.press("ctrl+e")
        await pilot.pause()
        app.screen.query_one(Input).value = str(tmp_path / "orientation.csv")
        await pilot.press("enter")
        await pilot.pause(0.2)
    rows = list(csv.reader((tmp_path / "orientation.csv").read_text().splitlines()))
    assert rows[0][:2] == ["point", "orientation_deg"]
    assert [row[1] for row in rows[1:]] == ["-10", "0", "10"]
    from planar_tui.provenance import read_sidecar

    record = read_sidecar(tmp_path / "orientation.csv")  # its provenance beside it
    assert record.kind == "sweep" and record.settings["job_kind"] == "workspace"
    assert record.form == "arc-distance" and record.precision_cm is not None


@async_test
async def test_bad_key_stays_in_the_dialog_with_the_reason(tmp_path):
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        dialog = await _open_dialog(app, pilot, "workspace")
        _fill(dialog, [("orientation_dg", "0, 1")])
        await pilot.press("enter")
        await pilot.pause()
        assert app.screen is dialog
        problem = str(dialog.query_one("#sweep-problem").render())
        assert "unknown key path" in problem and "orientation_deg" in problem
        _fill(dialog, [("precision_cm", "0.5, -1")])
        await pilot.press("enter")
        await pilot.pause()
        assert app.screen is dialog and "precision_cm" in str(
            dialog.query_one("#sweep-problem").render()
        )
        await pilot.press("escape")
        await pilot.pause()
        assert not isinstance(app.screen, SweepDialog) and not app.job_running


@async_test
async def test_a_superscript_worker_count_and_a_repeated_key_stay_in_the_dialog(tmp_path):
    """ "²" passes ``str.isdigit`` but not ``int()``; a second row of the first row's key
    once replaced it silently."""
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        dialog = await _open_dialog(app, pilot, "workspace")
        _fill(dialog, [("orientation_deg", "0, 1")])
        dialog.query_one("#sweep-workers", Input).value = "²"
        await pilot.press("enter")
        await pilot.pause()
        assert app.screen is dialog
        assert str(dialog.query_one("#sweep-problem").render()) == (
            "error: workers '²' (expected a whole number ≥ 1)"
        )
        dialog.query_one("#sweep-workers", Input).value = "1"
        _fill(dialog, [("orientation_deg", "0, 1"), ("orientation_deg", "5, 6, 7")])
        await pilot.press("enter")
        await pilot.pause()
        assert app.screen is dialog and not app.job_running
        assert str(dialog.query_one("#sweep-problem").render()) == (
            "error: row 2: orientation_deg is already row 1's key"
        )
        await pilot.press("escape")
        await pilot.pause()


@async_test
async def test_cancel_stops_a_sweep_promptly(tmp_path):
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        dialog = await _open_dialog(app, pilot, "simulate")
        _fill(dialog, [("duration_s", "300..400 x40")])
        await pilot.press("enter")
        await pilot.pause(0.5)
        assert app.job_running
        asked = time.monotonic()
        await pilot.press("escape")
        await finish(app, pilot)
        assert time.monotonic() - asked < 5.0  # 10x the 0.5 s goal; the sweep runs for hours
        assert "cancelled" in str(app.query_one("#pane-simulate #job-status").render())
        assert app.last_sweep is None or app.last_sweep.cancelled


@async_test
async def test_a_cancelled_sweep_shows_and_exports_its_finished_points(tmp_path):
    """Cancel after the two short points finished: the sweep screen opens on all five
    rows, the two finished ones with their figures (θ1 at the end of separate runs of the
    same jobs), the three others marked cancelled; ctrl+e exports that table."""
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        dialog = await _open_dialog(app, pilot, "simulate")
        _fill(dialog, [("duration_s", "0.01, 0.02, 30000, 40000, 50000")])
        await pilot.press("enter")
        deadline = time.monotonic() + 120
        while True:
            state = app.jobs.latest
            label = "" if state is None else state.stage
            if state is not None and label.endswith(":sweep") and state.completed >= 2:
                break
            assert time.monotonic() < deadline, "the two short points did not finish"
            await pilot.pause(0.05)
        await pilot.press("escape")
        await finish(app, pilot)
        await pilot.pause(0.2)
        screen = app.screen
        assert isinstance(screen, SweepScreen), screen
        assert "cancelled: 2 of 5 points run" in str(screen.query_one("#sweep-title").render())
        table = screen.query_one("#sweep-table", DataTable)
        assert table.row_count == 5
        rows = list(screen.table.rows)
        header = list(screen.table.header)
        status = [row[header.index("status")] for row in rows]
        assert status == ["ok", "ok", "cancelled", "cancelled", "cancelled"]
        document = (tmp_path / "tiny.toml").read_text()
        for row in rows[:2]:
            path = tmp_path / f"point-{row[0]}.toml"
            path.write_text(document.replace("duration_s = 0.2", f"duration_s = {row[1]!r}"))
            (job,) = [job for job in load_preset(path).jobs if job.kind == "simulate"]
            final = list(csv.reader(run_job(job).table.lines()))[-1]
            assert row[header.index("theta1_end_rad")] == float(final[1])
        await pilot.press("ctrl+e")
        await pilot.pause()
        app.screen.query_one(Input).value = str(tmp_path / "partial.csv")
        await pilot.press("enter")
        await pilot.pause(0.2)
        with open(tmp_path / "partial.csv", newline="") as stream:
            written = list(csv.reader(stream))
        assert [row[header.index("status")] for row in written[1:]] == status


@pytest.mark.parametrize(
    "sweep",
    [
        'job = "torques[9]"\nvalues."robot.masses_kg[2]" = [1.0]',
        'job = "torques"\nvalues."robot.masses_kg[2]" = [1.0, -2.0]',
        'job = "torques"\nvalues."robot.masses_kg[2]" = [1.0, 2.0, 3.0]\nmax_points = 2',
        'job = "torques"\nvalues."robot.masses_kg[2]" = [1.0]\nplot = "one.png"',
        'job = "torques"\nvalues.nope = [1.0]',
    ],
)
def test_the_app_refuses_the_sweep_tables_the_cli_refuses(tmp_path, cli, sweep):
    """The validation line is not "ok" for a sweep the CLI refuses: the same message."""
    from planar_tui.app.workbench import Workbench
    from tests.sweep_presets import TORQUES, TORQUES_BASE, write

    preset = write(tmp_path, "p.toml", TORQUES, f"[[sweep]]\n{sweep}\n", **TORQUES_BASE)
    refused = cli("sweep", preset, "--out-dir", tmp_path / "out", "--workers", "1")
    assert refused.exit_code == 2
    preset_found, problems = Workbench.open(preset).check()
    assert preset_found is None
    assert [str(problem) for problem in problems] == refused.stderr.strip().splitlines()

"""Pilot tests of the Textual workbench, one per flow, at 80×24 (tiny presets, quick jobs)."""

from __future__ import annotations

import asyncio
import csv
import functools
import re
import shutil
import time
from pathlib import Path

import pytest
from textual.widgets import Button

from planar_tui.app.app import WorkbenchApp
from planar_tui.app.screens.dialogs import ConfirmDialog, HelpScreen, MessageDialog, PathDialog
from planar_tui.app.workbench import Workbench

pytestmark = pytest.mark.slow  # end to end (see pyproject.toml's markers)

DATA = Path(__file__).parent / "data" / "app"
SIZE = (80, 24)


def async_test(function):
    """Run an async test in a fresh event loop (no pytest async plugin is installed)."""

    @functools.wraps(function)
    def wrapper(*args, **kwargs):
        return asyncio.run(function(*args, **kwargs))

    return wrapper


def make_app(tmp_path: Path, name: str = "tiny.toml") -> WorkbenchApp:
    """The app on a copy of a fixture preset, exporting into ``tmp_path``."""
    path = tmp_path / name
    shutil.copy(DATA / name, path)
    return WorkbenchApp(Workbench.open(path), output_dir=tmp_path)


async def finish(app: WorkbenchApp, pilot, timeout_s: float = 600.0) -> None:
    """Wait for the running job's thread, its worker and the result message (the bound
    only catches a hang: kernels compiling on a busy machine take minutes)."""
    deadline = time.monotonic() + timeout_s
    while app.job_running:
        assert time.monotonic() < deadline, "job did not finish in time"
        await pilot.pause(0.05)
    await app.workers.wait_for_complete()
    await pilot.pause(0.1)


async def until(pilot, predicate, timeout_s: float = 120.0) -> None:
    """Let the app run until ``predicate()`` holds (a validation or recomposition under
    load is slow; the bound only catches a hang)."""
    deadline = time.monotonic() + timeout_s
    while not predicate():
        assert time.monotonic() < deadline, "the screen did not change in time"
        await pilot.pause(0.05)


async def run_tab(app: WorkbenchApp, pilot, name: str) -> None:
    """Show a tab, press F5 and wait for the job to end."""
    app.action_show_tab(name)
    await pilot.pause()
    await pilot.press("f5")
    await finish(app, pilot)


def validation(app: WorkbenchApp) -> str:
    return str(app.query_one("#validation").render())


@async_test
async def test_tabs_visible_at_80x24(tmp_path):
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        await pilot.pause()
        first_line = app.export_text().splitlines()[0]
        for title in ("Robot", "Sensitivity", "Workspace", "Simulate"):
            assert title in first_line
        assert validation(app).startswith("ok: tiny.toml")


@async_test
async def test_edit_link_shows_the_cli_message(tmp_path, cli):
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        field = app.query_one("#link-2-lengths_m")
        field.focus()
        field.value = ""
        await pilot.press("minus", "0", "full_stop", "2")  # typed, keyboard only
        await pilot.pause()
        shown = validation(app)
        assert "robot.lengths_m: item 2 is -0.2, must be > 0" in shown
        # the CLI reads the same values from a file and says the same thing
        bad = tmp_path / "cli" / "tiny.toml"
        bad.parent.mkdir()
        bad.write_text((DATA / "tiny.toml").read_text().replace("[0.303, 0.214]", "[0.303, -0.2]"))
        result = cli("simulate", bad, "--out", tmp_path / "x.csv")
        assert result.exit_code == 2
        # the reason first, the preset by its name (not the machine path)
        assert shown.startswith(result.stderr.strip().replace(f"{bad}: ", ""))
        assert "· tiny.toml ·" in shown and str(tmp_path) not in shown
        field.value = "abc"
        await pilot.pause()
        assert "robot.lengths_m: item 2 is a string (expected a positive number)" in (
            validation(app)
        )
        field.value = "0.214"
        await pilot.pause()
        assert validation(app).startswith("ok:")


@async_test
async def test_add_and_remove_link_keep_arrays_consistent(tmp_path):
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        await pilot.press("ctrl+n")
        await pilot.pause()
        assert app.workbench.document["robot"]["lengths_m"] == [0.303, 0.214, 0.214]
        # the simulate job's per-link arrays follow the robot (the new link gets zeros)
        simulate = app.workbench.document["simulate"]
        assert simulate["theta0_deg"] == [30, -60, 0.0]
        assert simulate["torques_Nm"] == [0.5, 0.1, 0.0]
        assert validation(app).startswith("ok:")
        await pilot.press("ctrl+r")
        await pilot.pause()
        assert app.workbench.document["robot"]["lengths_m"] == [0.303, 0.214]
        assert simulate["theta0_deg"] == [30, -60] and simulate["torques_Nm"] == [0.5, 0.1]
        assert validation(app).startswith("ok:")


@async_test
async def test_small_sobol_run_shows_the_dominant_parameter(tmp_path):
    # Singular posture: tau2 = g m2 l2 / 2, so with uniform ±1 mm and ±1 g tolerances
    # Var(tau2) ∝ m2² (for l2) + l2² (for m2); l2's share is m2² / (m2² + l2²).
    l2_m, m2_kg = 0.214, 0.796
    expected_l2_percent = 100 * m2_kg**2 / (m2_kg**2 + l2_m**2)
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        await run_tab(app, pilot, "sensitivity")
        screen = app.export_text()
        row = next(line for line in screen.splitlines() if re.search(r"▕\s+τ2 ", line))
        values = [float(v) for v in row.split("▕")[-1].split()[1:5]]
        assert values.index(max(values)) == 1  # columns l1 l2 m1 m2: l2 dominates
        assert values[1] == pytest.approx(expected_l2_percent, abs=2.0)
        assert "% of ST per torque · singular · 1 rad/s" in screen
        assert "…" not in screen
        await pilot.press("ctrl+t")  # S1 view: same shape, fractions
        await pilot.pause()
        assert "S1, first-order index" in app.export_text()


@async_test
async def test_short_simulation_is_plotted(tmp_path):
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        await run_tab(app, pilot, "simulate")
        pane = app.query_one("#pane-simulate")
        assert pane.result is not None and len(pane.result.table.rows) == 41
        screen = app.export_text()
        assert "200 RK4 steps" in screen and "t (s)" in screen
        assert "E total" in screen  # the energy plot's legend
        assert "done in" in screen
        # the tab's Run button asks the app (a message) to run the job again
        first = pane.result
        pane.query_one("#run", Button).press()
        await pilot.pause()
        await finish(app, pilot)
        assert pane.result is not first and len(pane.result.table.rows) == 41
        # exporting into a path that is not a folder: the batch service's message, no file
        not_a_folder = tmp_path / "file"
        not_a_folder.write_text("")
        assert app.export_csv(pane, not_a_folder) == []
        await pilot.pause()
        assert isinstance(app.screen, MessageDialog)
        assert "is not a writable folder" in app.export_text()


@async_test
async def test_cancel_a_long_job_within_half_a_second(tmp_path, monkeypatch):
    app = make_app(tmp_path, "long.toml")
    # Observed from outside the app: when the tab draws progress, when the outcome arrives.
    finished: list[tuple[float, bool]] = []
    on_job_finished = WorkbenchApp.on_job_finished

    def record_finished(self, message):
        finished.append((time.perf_counter(), message.cancelled))
        on_job_finished(self, message)

    monkeypatch.setattr(WorkbenchApp, "on_job_finished", record_finished)
    async with app.run_test(size=SIZE) as pilot:
        app.action_show_tab("simulate")
        await pilot.pause()
        pane = app.query_one("#pane-simulate")
        refreshes: list[float] = []
        show_progress = pane.show_progress

        def record_refresh(state):
            show_progress(state)
            refreshes.append(time.perf_counter())

        monkeypatch.setattr(pane, "show_progress", record_refresh)
        await pilot.press("f5")
        started = time.monotonic()
        while len(refreshes) < 6:
            assert time.monotonic() - started < 60
            await pilot.pause(0.05)
        assert app.job_running
        # While the worker burns CPU each pilot.press costs up to 2 s (the pilot waits for
        # the process to go idle), so the quit question is answered through its actions.
        await app.run_action("quit")  # a job runs: quitting asks first
        await pilot.pause(0.05)
        assert isinstance(app.screen, ConfirmDialog)
        app.screen.action_answer(False)
        await pilot.pause(0.05)
        assert app.is_running and app.job_running
        pressed = time.perf_counter()
        await pilot.press("escape")  # the key is sent at once; the pilot then waits
        await finish(app, pilot)
        assert len(finished) == 1 and finished[0][1]  # one outcome: cancelled
        assert finished[0][0] - pressed < 5.0  # 10x the 0.5 s goal (benchmarks/bench_cancel.py)
        assert "cancelled" in app.export_text()
        assert not (tmp_path / "long-simulate.csv").exists()
        # the app stays usable: the second, short job runs
        app.query_one("#job-select").value = 1
        await pilot.pause(0.2)
        await pilot.press("f5")
        await finish(app, pilot)
        assert "done in" in app.export_text()


@async_test
async def test_save_load_and_the_cli_gives_the_same_csv(tmp_path, cli):
    app = make_app(tmp_path)
    saved = tmp_path / "saved.toml"
    async with app.run_test(size=SIZE) as pilot:
        app.action_show_tab("simulate")
        await pilot.pause()
        app.query_one("#pane-simulate #field-duration_s").value = "0.1"
        await pilot.pause()
        await pilot.press("ctrl+s")  # the preset's own file: saved in place, no question
        await pilot.pause()
        assert not isinstance(app.screen, PathDialog)
        assert "duration_s = 0.1\n" in (tmp_path / "tiny.toml").read_text()
        await app.run_action("save_as")  # the palette's "Save as" asks for a path
        await pilot.pause()
        assert isinstance(app.screen, PathDialog)
        app.screen.query_one("#path-input").value = str(saved)
        await pilot.press("enter")
        await pilot.pause()
        assert saved.is_file()
        assert await app.open_preset(str(saved))
        await pilot.pause()
        assert app.workbench.document["simulate"]["duration_s"] == 0.1
        await run_tab(app, pilot, "simulate")
        await pilot.press("ctrl+e")
        await pilot.pause()
        assert isinstance(app.screen, PathDialog)  # asks for a folder, the app's by default
        assert app.screen.query_one("#path-input").value == str(tmp_path)
        assert "Writes tiny-simulate.csv there" in app.export_text()
        app.screen.query_one("#path-input").value = str(tmp_path / "app")
        await pilot.press("enter")
        await pilot.pause()
    result = cli("simulate", saved, "--out", tmp_path / "cli.csv")
    assert result.exit_code == 0, result.stderr
    assert sorted(p.name for p in (tmp_path / "app").iterdir()) == [
        "tiny-simulate.csv",
        "tiny-simulate.csv.json",
    ]  # job.output, its provenance
    app_csv = (tmp_path / "app" / "tiny-simulate.csv").read_bytes()
    assert app_csv == (tmp_path / "cli.csv").read_bytes()
    assert app_csv.count(b"\n") == 1 + 21


@async_test
async def test_a_failing_job_opens_a_dialog_not_a_traceback(tmp_path, monkeypatch):
    import dataclasses

    from planar_tui.registry import JOB_KINDS

    broken = dataclasses.replace(JOB_KINDS["simulate"], run=exploding_runner)
    monkeypatch.setitem(JOB_KINDS, "simulate", broken)
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        await run_tab(app, pilot, "simulate")
        assert isinstance(app.screen, MessageDialog)
        assert "RuntimeError: the kernel exploded" in app.export_text()
        await pilot.press("enter")
        await pilot.pause()
        assert not isinstance(app.screen, MessageDialog)
        assert "failed" in app.export_text()


def exploding_runner(job, progress):
    progress.start(1, "exploding")
    raise RuntimeError("the kernel exploded")


@async_test
async def test_help_palette_and_quit(tmp_path):
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        await pilot.press("f1")
        await pilot.pause()
        assert isinstance(app.screen, HelpScreen)
        await pilot.press("escape")
        await pilot.pause()
        titles = {command.title for command in app.get_system_commands(app.screen)}
        for title in (
            "Run job",
            "Cancel job",
            "Open preset",
            "Save preset",
            "Export CSV",
            "Help",
            "Add link",
            "Remove link",
            "Sensitivity view",
        ):
            assert title in titles
        await pilot.press("q")  # no job runs: quits without asking
        await pilot.pause()
    assert app.return_code == 0


@async_test
async def test_a_bad_preset_opens_with_its_problems_marked_and_a_shapeless_one_too(tmp_path):
    app = make_app(tmp_path)
    bad = tmp_path / "bad.toml"
    bad.write_text("[robot]\nlengths_m = [1.0]\nmasses_kg = [1.0, 2.0]\n")
    shapeless = tmp_path / "shapeless.toml"
    shapeless.write_text("robot = 3\n")
    nothing = tmp_path / "nothing.toml"
    nothing.write_text("robot = [\n")  # no TOML: refused, the preset kept
    async with app.run_test(size=SIZE) as pilot:
        assert not await app.open_preset(str(nothing))
        await pilot.pause()
        assert isinstance(app.screen, MessageDialog)
        assert app.workbench.path.name == "tiny.toml"
        app.pop_screen()
        assert await app.open_preset(str(shapeless))  # [robot] is no table: opened empty
        await pilot.pause()
        assert app.workbench.path == shapeless and app.workbench.document["robot"] == {}
        assert app.workbench.modified and shapeless.read_text() == "robot = 3\n"
        assert await app.open_preset(str(bad))  # wrong values: opened, marked
        await pilot.pause()
        assert app.workbench.path == bad and not isinstance(app.screen, MessageDialog)
        assert validation(app).startswith("error: robot.masses_kg: has 2 values")
        assert app.query_one("#pane-robot").query(".-bad")  # the field is marked


@async_test
async def test_workspace_form_wraps_and_the_run_shows_map_area_and_boxes(tmp_path, cli):
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        app.action_show_tab("workspace")
        await pilot.pause()
        screen = app.export_text()
        assert "[[20, 70], [110, 160]," in screen and "[245, 295]]" in screen  # wrapped, not cut
        field = app.query_one("#pane-workspace #field-precision_cm")
        field.focus()
        await pilot.pause()
        assert "█0.9375 " in app.export_text()  # a focused field: its value and a ▌ mark
        await pilot.press("end", "0", "enter")  # enter moves on instead of a new line
        await pilot.pause()
        assert field.value == "0.93750" and app.focused is not field
        assert app.workbench.document["workspace"]["precision_cm"] == 0.9375
        # the preset names the boxes file, as `planar-tui run` would write it
        app.query_one("#pane-workspace #field-boxes_output").value = "ws-boxes.csv"
        await run_tab(app, pilot, "workspace")
        screen = app.export_text()
        result = app.query_one("#pane-workspace").result
        assert result.summary[:24] in screen  # the runner's summary line (area bracket)
        assert "█" in screen and "▒" in screen  # inside and boundary cells of the map
        assert "x, y in cm" in screen and "┤" in screen  # legend, labelled y axis
        outcome = result.outcome
        # the bracket holds the exact area of paper B's Table 3 (106.750 cm²)
        assert outcome.area_inside_cm2 <= 106.75 <= outcome.area_kept_cm2
        await pilot.press("ctrl+e")
        await pilot.pause()
        app.screen.query_one("#path-input").value = str(tmp_path / "app")
        await pilot.press("enter")
        await pilot.pause()
    outputs = ("--out", tmp_path / "cli.csv", "--boxes", tmp_path / "cli-boxes.csv")
    result = cli("workspace", tmp_path / "tiny.toml", *outputs, "--no-map")
    assert result.exit_code == 0, result.stderr
    exported = tmp_path / "app"
    assert sorted(p.name for p in exported.iterdir()) == [
        "tiny-workspace.csv",
        "tiny-workspace.csv.json",
        "ws-boxes.csv",
        "ws-boxes.csv.json",
    ]
    assert (exported / "ws-boxes.csv").read_bytes() == (tmp_path / "cli-boxes.csv").read_bytes()
    app_rows = (exported / "tiny-workspace.csv").read_text().splitlines()
    cli_rows = (tmp_path / "cli.csv").read_text().splitlines()
    assert app_rows[0] == cli_rows[0]  # same columns; the last one (seconds) differs per run
    assert app_rows[1].rsplit(",", 1)[0] == cli_rows[1].rsplit(",", 1)[0]


@async_test
async def test_no_color_keeps_every_state_readable(tmp_path, monkeypatch):
    monkeypatch.setenv("NO_COLOR", "1")
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        assert app.no_color  # Textual renders in monochrome
        app.query_one("#link-1-masses_kg").value = "0"
        await until(pilot, lambda: "error:" in app.export_text())  # in the text, not colour
        app.query_one("#link-1-masses_kg").value = "1.126"
        await until(pilot, lambda: "ok:" in app.export_text())
        await run_tab(app, pilot, "sensitivity")
        assert "τ2" in app.export_text()


@async_test
async def test_enter_in_a_field_moves_to_the_next_field_without_a_newline(tmp_path):
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        app.action_show_tab("simulate")
        await pilot.pause()
        field = app.query_one("#pane-simulate #field-duration_s")
        field.focus()
        await pilot.press("end", "5", "enter")
        await pilot.pause()
        assert field.text == "0.25" and "\n" not in field.text
        assert app.focused is app.query_one("#pane-simulate #field-step_s")
        assert app.workbench.document["simulate"]["duration_s"] == 0.25
        await pilot.press("enter")  # and on, field after field
        await pilot.pause()
        assert app.focused is app.query_one("#pane-simulate #field-theta0_deg")


@async_test
async def test_the_torques_tab_keeps_the_generic_view_of_summary_and_csv_rows(tmp_path):
    """The Torques pane adds the arm's drawing (tests/test_app_torques.py) to the generic
    view (:class:`JobPane`'s summary and CSV rows), checked here; a kind with no pane of
    its own getting :class:`JobPane` itself: tests/test_toy_kind.py."""
    from planar_tui.app.widgets.panes import JobPane
    from planar_tui.csvio import CsvTable
    from planar_tui.jobkind import JobResult

    preset = Path(__file__).resolve().parent.parent / "presets" / "paper-a-table1.toml"
    app = WorkbenchApp(Workbench.open(preset), output_dir=tmp_path)  # its Torques tab
    async with app.run_test(size=SIZE) as pilot:
        pane = app.query_one("#pane-torques")
        assert isinstance(pane, JobPane) and pane.kind == "torques"
        await run_tab(app, pilot, "torques")
        assert pane.result is not None
        screen = app.export_text()
        assert "2 states, max |tau| = [" in screen  # the runner's summary
        # a table, the torques first: both states' six torques on screen beside the form
        # at 80 columns, as the CSV has them (4 significant digits)
        lines = [line.split("▕")[-1].split() for line in screen.splitlines()]
        assert ["#", "τ1", "τ2", "τ3", "τ4", "τ5", "τ6"] in [line[:7] for line in lines]
        tau = [[float(v) for v in row[-6:]] for row in pane.result.table.rows]
        for k, row in enumerate(tau, start=1):
            assert [str(k), *(f"{v:.4g}" for v in row)] in [line[:7] for line in lines]
        assert "theta1_rad," not in screen  # no raw CSV text
        assert "done in" in screen
        # at most 12 CSV lines (header included), whatever the table's length
        many = JobResult(table=CsvTable(("a_m", "b_m"), [[i, i] for i in range(40)]), summary="40")
        pane.show_result(pane.job, many)
        await pilot.pause()
        lines = [line.split("▕")[-1].strip() for line in app.export_text().splitlines()]
        assert "a_m,b_m" in lines and "0,0" in lines  # on screen, the rest scrolls
        shown = str(pane.query_one("#result-rows").render()).splitlines()
        assert shown[0] == "a_m,b_m" and shown[-1] == "10,10" and len(shown) == 12


@async_test
async def test_export_names_and_writes_files_as_planar_tui_run(tmp_path, cli):
    preset = tmp_path / "small.toml"
    text = (DATA / "workspace-small.toml").read_text()
    preset.write_text(text.rstrip("\n") + '\nboxes_output = "small-boxes.csv"\n')
    app = WorkbenchApp(Workbench.open(preset), output_dir=tmp_path / "app")
    async with app.run_test(size=SIZE) as pilot:
        await run_tab(app, pilot, "workspace")
        await pilot.press("ctrl+e")
        await pilot.pause()
        assert app.screen.query_one("#path-input").value == str(tmp_path / "app")
        await pilot.press("enter")  # the default folder
        await pilot.pause()
    result = cli("run", preset, "--out-dir", tmp_path / "cli")
    assert result.exit_code == 0, result.stderr
    names = sorted(p.name for p in (tmp_path / "app").iterdir())
    assert names == sorted(p.name for p in (tmp_path / "cli").iterdir())
    assert names == [
        "small-boxes.csv",
        "small-boxes.csv.json",
        "small-workspace.csv",
        "small-workspace.csv.json",
    ]
    boxes = (tmp_path / "app" / "small-boxes.csv").read_bytes()
    assert boxes == (tmp_path / "cli" / "small-boxes.csv").read_bytes()
    assert boxes.count(b"\n") > 100
    app_rows, cli_rows = (
        list(csv.reader((tmp_path / folder / "small-workspace.csv").read_text().splitlines()))
        for folder in ("app", "cli")
    )
    assert app_rows[0] == cli_rows[0] and len(app_rows) == len(cli_rows) == 2
    timing = app_rows[0].index("seconds")  # the one column that differs between runs
    assert [row[:timing] + row[timing + 1 :] for row in app_rows] == [
        row[:timing] + row[timing + 1 :] for row in cli_rows
    ]


@async_test
async def test_ctrl_l_writes_the_figure_beside_the_csv_export_writes(tmp_path):
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        await pilot.press("ctrl+l")  # nothing run yet: a warning, no file
        await pilot.pause()
        assert not list(tmp_path.glob("*.png"))
        await run_tab(app, pilot, "simulate")
        await pilot.press("ctrl+l")
        await app.workers.wait_for_complete()
        await pilot.pause(0.1)
        figure = tmp_path / "tiny-simulate.png"  # the CSV export names, as .png
        assert figure.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        assert any(f"Wrote {figure}" in n.message for n in app._notifications)
        # again: the file exists, so it asks; "n" keeps it
        stamp = figure.stat().st_mtime_ns
        await pilot.press("ctrl+l")
        await pilot.pause()
        assert isinstance(app.screen, ConfirmDialog)
        await pilot.press("n")
        await pilot.pause()
        assert figure.stat().st_mtime_ns == stamp


@async_test
async def test_job_controls_updated_after_they_are_gone_raise_nothing(tmp_path):
    """A job's last message can reach its controls as the app closes (the NoMatches
    '#job-status' of a teardown): updating removed controls does nothing."""
    from planar_tui.app.widgets.job_controls import JobControls

    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        app.action_show_tab("simulate")
        await pilot.pause()
        controls = app.query_one("#pane-simulate").query_one(JobControls)
        await controls.remove_children()
        controls.status("done")
        controls.set_running(False)
        controls.finished()
        from planar_tui.progress import ProgressState

        controls.show_progress(ProgressState(1, 2, "x", ""))

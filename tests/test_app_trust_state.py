"""Pilot tests's "errors and state that tell the truth" (80×24, tiny presets).

Each test drives the app with keys where it can and reads the screen as text
(``app.export_text()``); focus styles are read from the widgets' rendered strips with
their colours reduced to the 16 standard ones.
"""

from __future__ import annotations

import csv
import re
import shutil
import threading
import time
from pathlib import Path

import pytest
from rich.color import ColorSystem
from textual.geometry import Region
from textual.widgets import Select, TabbedContent

from planar_tui.app.app import WorkbenchApp
from planar_tui.app.widgets.fields import Field, LinkEditor
from planar_tui.app.widgets.job_controls import JobControls
from planar_tui.app.workbench import Workbench
from planar_tui.progress import ProgressState
from tests.test_app import SIZE, async_test, finish, make_app, run_tab, until, validation

pytestmark = pytest.mark.slow  # end to end (see pyproject.toml's markers)

PRESETS = Path(__file__).resolve().parent.parent / "presets"


def active_tab(app: WorkbenchApp) -> str:
    return app.query_one(TabbedContent).active.removeprefix("tab-")


# -- 1. the error line, the bad field, the key to it -------------------------------------
@async_test
async def test_error_line_puts_the_reason_first_marks_the_field_and_ctrl_g_goes_there(tmp_path):
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        app.query_one("#pane-workspace #field-precision_cm").value = "-1"
        await pilot.pause()
        line = validation(app)
        assert line.startswith("error: workspace.precision_cm: is -1, must be > 0")
        assert "tiny.toml" in line and str(tmp_path) not in line  # the name, not the path
        screen = app.export_text()
        assert "must be > 0" in screen.splitlines()[-3] + screen.splitlines()[-2]
        field = app.query_one("#pane-workspace #field-precision_cm", Field)
        assert field.has_class("-bad")  # the red border
        assert active_tab(app) == "robot"
        await pilot.press("ctrl+g")
        await pilot.pause(0.2)
        assert active_tab(app) == "workspace" and app.focused is field
        screen = app.export_text()
        assert "▲ workspace.precision_cm:" in screen  # the message under the field
        field.value = "0.9375"
        await pilot.pause()
        assert not field.has_class("-bad") and validation(app).startswith("ok:")


@async_test
async def test_ctrl_g_selects_the_job_and_the_robot_the_error_names(tmp_path):
    shutil.copy(PRESETS / "paper-a-table4.toml", tmp_path / "t4.toml")
    app = WorkbenchApp(Workbench.open(tmp_path / "t4.toml"), output_dir=tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        app.workbench.document["sensitivity"][2]["seed"] = 0  # sensitivity[3].seed
        app.revalidate()
        await pilot.press("ctrl+g")
        await pilot.pause(0.2)
        pane = app.query_one("#pane-sensitivity")
        assert active_tab(app) == "sensitivity" and pane.index == 2
        assert app.focused is pane.query_one("#field-seed")
        app.workbench.document["sensitivity"][2]["seed"] = 42
        app.workbench.document["sensitivity"][4]["robot"]["masses_kg"][1] = -1.0
        app.revalidate()
        assert "sensitivity[5].robot.masses_kg: item 2" in validation(app)
        await pilot.press("ctrl+g")
        await pilot.pause(0.2)
        robot = app.query_one("#pane-robot")
        assert active_tab(app) == "robot" and robot.target == ("sensitivity", 4)
        assert app.focused is robot.query_one("#link-2-masses_kg")
        assert "▲ sensitivity[5].robot.masses_kg" in app.export_text()


# -- 2. one job's problem does not block another ------------------------------------------
@async_test
async def test_a_bad_workspace_field_does_not_block_the_simulation(tmp_path):
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        app.query_one("#pane-workspace #field-precision_cm").value = "-1"
        await pilot.pause()
        await run_tab(app, pilot, "simulate")
        pane = app.query_one("#pane-simulate")
        assert pane.result is not None and "done in" in app.export_text()
        await run_tab(app, pilot, "workspace")  # the bad job itself is not run
        assert app.query_one("#pane-workspace").result is None
        assert app.focused is app.query_one("#pane-workspace #field-precision_cm")
        # each tab shows its own problem: the Simulate tab none
        app.action_show_tab("simulate")
        await pilot.pause()
        assert not app.query_one("#pane-simulate #pane-problem").has_class("-shown")


# -- 3. stale results and a state line that matches reality -------------------------------
@async_test
async def test_results_from_before_an_edit_or_a_cancel_are_marked_stale(tmp_path):
    app = make_app(tmp_path, "long.toml")
    async with app.run_test(size=SIZE) as pilot:
        app.action_show_tab("simulate")
        await pilot.pause()
        app.query_one("#job-select", Select).value = 1  # the short job
        await until(pilot, lambda: "short-simulate" in app.export_text())
        await pilot.press("f5")
        await finish(app, pilot)
        pane = app.query_one("#pane-simulate")
        results = pane.query_one(".results")
        assert pane.result is not None and not results.has_class("stale")
        assert "stale" not in app.export_text()
        pane.query_one("#field-duration_s", Field).value = "0.2"
        await pilot.pause()
        assert results.has_class("stale")
        assert "stale: inputs changed since this run" in app.export_text()
        pane.query_one("#field-duration_s", Field).value = "0.1"  # back as it ran
        await pilot.pause()
        assert not results.has_class("stale")
        # a cancelled run leaves the earlier result, marked as such
        await pilot.press("f5")
        await finish(app, pilot)
        app.query_one("#job-select", Select).value = 0  # the 20-million-step job
        await until(pilot, lambda: "stale: result of simulate[2]" in app.export_text())
        await pilot.press("f5")
        await pilot.pause(0.3)
        await pilot.press("escape")
        await finish(app, pilot)
        screen = app.export_text()
        assert "the last run was cancelled" in screen and "cancelled after" in screen


def test_cancelling_stays_on_the_state_line_until_the_worker_stops():
    from textual.app import App

    class Host(App):
        def compose(self):
            yield JobControls()

    async def scenario():
        async with Host().run_test(size=SIZE) as pilot:
            controls = pilot.app.query_one(JobControls)
            controls.set_running(True)
            controls.show_cancelling()
            controls.show_progress(ProgressState(5, 10, "sampling", ""))  # a late snapshot
            await pilot.pause()
            status = str(controls.query_one("#job-status").render())
            assert status.startswith("cancelling…") and "50%" in status
            controls.set_running(False)  # the app does this when the worker has stopped
            assert not controls.cancelling

    import asyncio

    asyncio.run(scenario())


def endless_bisection(job, progress):
    """A workspace runner that reports a live bracket until it is cancelled."""
    progress.start(100, "bisection")
    while True:
        progress.advance(0.01, detail="area in [0, 12970] cm2")
        time.sleep(0.005)


@async_test
async def test_workspace_says_cancelled_not_running_after_a_cancel(tmp_path, monkeypatch):
    import dataclasses

    from planar_tui.registry import JOB_KINDS

    endless = dataclasses.replace(JOB_KINDS["workspace"], run=endless_bisection)
    monkeypatch.setitem(JOB_KINDS, "workspace", endless)
    monkeypatch.setattr("planar_tui.warmup.warm_kernels", lambda kinds, progress: None)
    app = make_app(tmp_path, "workspace-small.toml")
    async with app.run_test(size=SIZE) as pilot:
        app.action_show_tab("workspace")
        await pilot.pause()
        await pilot.press("f5")
        deadline = time.monotonic() + 300
        while "running bisection" not in app.export_text():
            assert time.monotonic() < deadline
            await pilot.pause(0.1)
        await pilot.press("escape")
        await finish(app, pilot)
        screen = app.export_text()
        assert "running" not in screen and "The last run was cancelled." in screen
        assert "cancelled after" in screen


# -- 4. a visible focus in 16 colours, no invisible stops ---------------------------------
def standard_look(widget) -> list[tuple]:
    """The rendering of the widget and its visible descendants (a tab bar draws its
    tabs as children) with colours reduced to the 16 standard ones."""
    look = []
    for part in [widget, *widget.query("*")]:
        if part.display and part.size.area:
            look.extend(strip_look(part))
    return look


def strip_look(widget) -> list[tuple]:
    """One widget's own strips, colours reduced to the 16 standard ones."""
    strips = widget.render_lines(Region(0, 0, widget.size.width, widget.size.height))
    look = []
    for strip in strips:
        for segment in strip:
            style = segment.style
            if style is None:
                look.append((segment.text,))
                continue
            colours = [
                None if c is None else c.downgrade(ColorSystem.STANDARD).number
                for c in (style.color, style.bgcolor)
            ]
            look.append((segment.text, *colours, style.reverse, style.bold, style.underline))
    return look


@pytest.mark.parametrize("tab", ["robot", "simulate", "sensitivity"])
@async_test
async def test_every_tab_stop_is_visible_with_a_focus_style_in_16_colours(tmp_path, tab):
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        app.action_show_tab(tab)
        await pilot.pause()
        seen = []
        for _ in range(60):
            await pilot.press("tab")
            await pilot.pause()
            widget = app.focused
            if widget is None or widget in seen:
                break
            seen.append(widget)
            region = widget.region
            assert widget.display and widget.visible, widget
            assert region.width > 0 and region.height > 0, widget  # not a hidden container
            assert app.screen.region.contains_region(region), widget
            focused = standard_look(widget)
            app.set_focus(None)
            await pilot.pause()
            assert standard_look(widget) != focused, f"{widget} looks the same unfocused"
            app.set_focus(widget)  # the next tab moves on from it (no repaint needed)
        kinds = {type(w).__name__ for w in seen}
        assert len(seen) >= 6 and {"Field", "Button"} <= kinds | {"Field"}


# -- 5. direct keys to the tabs ------------------------------------------------------------
@async_test
async def test_number_keys_and_function_keys_switch_tabs(tmp_path):
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        await pilot.pause()
        for key, tab in (("2", "sensitivity"), ("5", "torques"), ("3", "workspace")):
            await pilot.press(key)
            await pilot.pause()
            assert active_tab(app) == tab
        field = app.query_one("#pane-workspace #field-orientation_deg", Field)
        field.focus()
        await pilot.press("end", "4")  # inside a field a digit is typed, not a tab switch
        await pilot.pause()
        assert field.text == "04" and active_tab(app) == "workspace"
        for key, tab in (("f6", "simulate"), ("f2", "robot"), ("f7", "torques")):
            await pilot.press(key)  # function keys work inside fields too
            await pilot.pause()
            assert active_tab(app) == tab


# -- 6. the robot of each job on the Robot tab --------------------------------------------
@async_test
async def test_robot_tab_edits_the_robot_of_the_selected_job(tmp_path):
    shutil.copy(PRESETS / "paper-a-table4.toml", tmp_path / "t4.toml")
    app = WorkbenchApp(Workbench.open(tmp_path / "t4.toml"), output_dir=tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        picker = app.query_one("#robot-select", Select)
        labels = [label for label, _, _ in app.workbench.robot_targets()]
        assert labels[:2] == ["preset robots", "sensitivity[1] robot"]
        assert "sensitivity[5] robot" in labels
        picker.value = labels.index("sensitivity[3] robot")
        await until(pilot, lambda: "3R-PSM" in app.export_text())
        editor = app.query_one(LinkEditor)
        assert [row[0] for row in editor.current_rows()] == ["0.303", "0.303", "0.175"]
        cell = app.query_one("#link-3-lengths_m")
        cell.focus()
        cell.value = ""
        await pilot.press("0", "full_stop", "2")
        await pilot.pause()
        robot = app.workbench.document["sensitivity"][2]["robot"]
        assert robot["lengths_m"] == [0.303, 0.303, 0.2]
        assert app.workbench.job("sensitivity", 2).robot.lengths_m[2] == 0.2
        assert app.workbench.document["sensitivity"][3]["robot"]["lengths_m"][2] == 0.175
        # the Sensitivity tab's form keeps the robot edited here when it stores its table
        app.action_show_tab("sensitivity")
        await pilot.pause()
        pane = app.query_one("#pane-sensitivity")
        pane.index = 2
        await pane.recompose()
        pane.query_one("#field-seed", Field).value = "43"
        await pilot.pause()
        assert app.workbench.document["sensitivity"][2]["robot"]["lengths_m"][2] == 0.2


# -- 7. the Torques tab and "run all" -----------------------------------------------------
RUN_ALL_PRESET = """\
# run-all test preset
[robot]
lengths_m = [0.303, 0.214]
masses_kg = [1.126, 0.796]

[[simulate]]
duration_s = 0.05
step_s = 0.001
output = "a-sim.csv"

[[simulate]]
duration_s = 0.02
step_s = 0.001
output = "b-sim.csv"

[torques]
theta_deg = [[0, 0], [30, 60]]
output = "c-torques.csv"
"""


@async_test
async def test_torques_tab_and_run_all_write_what_planar_tui_run_writes(tmp_path, cli):
    preset = tmp_path / "all.toml"
    preset.write_text(RUN_ALL_PRESET)
    app = WorkbenchApp(Workbench.open(preset), output_dir=tmp_path / "app")
    async with app.run_test(size=SIZE) as pilot:
        assert "Torques" in app.export_text().splitlines()[0]
        await run_tab(app, pilot, "torques")
        torques_screen = app.export_text()  # a table, the torques first: τ1 τ2 θ1 θ2 …
        assert all(f" {column}" in torques_screen for column in ("τ1", "τ2", "θ1", "θ2"))
        await pilot.press("f9")
        await pilot.pause()
        assert "Runs 3 jobs in order" in app.export_text()
        await pilot.press("enter")  # the default folder: the app's output folder
        await pilot.pause()
        await finish(app, pilot)
        assert any("Run all 3 jobs in" in n.message for n in app._notifications)
    result = cli("run", preset, "--out-dir", tmp_path / "cli")
    assert result.exit_code == 0, result.stderr
    names = sorted(p.name for p in (tmp_path / "app").iterdir())
    assert names == sorted(p.name for p in (tmp_path / "cli").iterdir())
    csvs = ["a-sim.csv", "b-sim.csv", "c-torques.csv"]
    assert names == sorted([*csvs, *(f"{name}.json" for name in csvs)])  # with provenance
    with (tmp_path / "cli" / "c-torques.csv").open() as handle:
        rows = list(csv.DictReader(line for line in handle if not line.startswith("#")))
    assert len(rows) == 2
    for state, row in enumerate(rows, start=1):  # the tab showed what `run` wrote (4 digits)
        tau1, tau2 = (re.escape(f"{float(row[f'tau{i}_Nm']):.4g}") for i in (1, 2))
        assert re.search(rf"\s{state}\s+{tau1}\s+{tau2}\s", torques_screen)
    from planar_tui.provenance import read_sidecar

    for name in csvs:
        assert (tmp_path / "app" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes()
        app_record, cli_record = (read_sidecar(tmp_path / side / name) for side in ("app", "cli"))
        assert (app_record.kind, app_record.label, app_record.settings) == (
            cli_record.kind,
            cli_record.label,
            cli_record.settings,
        )
        assert app_record.preset_sha256 == cli_record.preset_sha256 is not None


# -- 8. the solved posture beside the sensitivity table -----------------------------------
@async_test
async def test_isotropic_posture_angles_and_kappa_are_shown(tmp_path):
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        app.action_show_tab("sensitivity")
        await pilot.pause()
        app.query_one("#pane-sensitivity #field-posture", Field).value = "isotropic"
        app.query_one("#pane-sensitivity #field-samples", Field).value = "64"
        await pilot.pause()
        await run_tab(app, pilot, "sensitivity")
        line = next(line for line in app.export_text().splitlines() if "posture isotropic" in line)
        match = re.search(r"θ = \[([-\d.]+), ([-\d.]+)\]° κ = ([\d.]+)", line)
        assert match, line
        _, theta2, kappa = map(float, match.groups())
        # 2R with l1/l2 = 1.416 ≈ √2: Jacobian isotropy at θ2 ≈ ±135° (paper A), κ ≈ 1
        assert abs(abs(theta2) - 135.0) < 2.0 and 1.0 <= kappa < 1.01


# -- 9. progress with count, percent and ETA; quitting waits only for the worker ---------
def test_progress_text_leads_with_percent_count_and_eta():
    from planar_tui.app.widgets.job_controls import progress_text

    state = ProgressState(9000, 20000, "sampling", "sobol")
    assert progress_text(state, 3.2) == " 45% 9.0k/20k eta 3s sampling sobol"
    assert progress_text(ProgressState(0, 8, "analysis", ""), None) == "  0% 0/8 eta … analysis"
    assert "eta 1:05" in progress_text(ProgressState(1, 2, "x", ""), 65)


@async_test
async def test_long_job_progress_line_and_quitting_during_it(tmp_path):
    app = make_app(tmp_path, "long.toml")
    async with app.run_test(size=SIZE) as pilot:
        app.action_show_tab("simulate")
        await pilot.pause()
        await pilot.press("f5")
        pattern = re.compile(r"\d+% [\d.]+[kMG]?/[\d.]+[kMG]? eta (\d|…)")
        deadline = time.monotonic() + 600
        while not pattern.search(app.export_text()):
            assert time.monotonic() < deadline, app.export_text()
            await pilot.pause(0.1)
        line = next(line for line in app.export_text().splitlines() if pattern.search(line))
        assert "Run F5" in line and len(line) <= 80  # on the controls line, at 80 columns
        assert re.search(r"eta \d", line) or "eta …" in line
        await app.run_action("quit")
        await pilot.pause(0.05)
        answered = time.perf_counter()
        app.screen.action_answer(True)
        while app.is_running and time.perf_counter() - answered < 30:
            await pilot.pause(0.01)
        exit_s = time.perf_counter() - answered
        assert not app.is_running and exit_s < 5.0, exit_s  # 10x the 0.5 s goal
        assert not [t for t in threading.enumerate() if "run" in t.name.lower() and t.is_alive()]
    assert not (tmp_path / "long-simulate.csv").exists()
    print(f"quit during a long stage: app exited {exit_s:.3f} s after the answer")

"""The workbench's rough edges a new user met in the first hour: the
comparison of two workspace runs' maps, the sweep dialog and screen's defaults, ..."""

from __future__ import annotations

import shutil
import time
from pathlib import Path

import numpy as np
import pytest
from textual.widgets import Input, Select

from planar_tui.app.app import WorkbenchApp
from planar_tui.app.compare import compare_runs
from planar_tui.app.history import COALESCE_S
from planar_tui.app.runs import RunHistory
from planar_tui.app.sweep_data import parse_values, values_text, varying_figures
from planar_tui.app.widgets.fields import Field
from planar_tui.app.workbench import Workbench
from planar_tui.batch import run_job
from planar_tui.csvio import CsvTable
from tests.test_app import SIZE, async_test, finish, run_tab, until

DATA = Path(__file__).parent / "data" / "app"


def test_two_real_workspace_runs_overlay_their_maps(tmp_path):
    # tiny.toml's coarse 3-RRR, then the same with the first leg's limits narrowed: run B
    # holds less, so the overlay shows cells inside both ('#') and inside A only ('A'),
    # none inside B only (B's workspace is a subset of A's).
    shutil.copy(DATA / "tiny.toml", tmp_path / "tiny.toml")
    bench = Workbench.open(tmp_path / "tiny.toml")
    history = RunHistory()
    job = bench.job("workspace")
    history.add_result(job, run_job(job))
    bench.document["workspace"]["joint_limits_deg"] = [[30, 60], [110, 160], [245, 295]]
    job = bench.job("workspace")
    history.add_result(job, run_job(job))
    a, b = history.runs
    assert {row[-1] for row in a.extra_tables["boxes"].rows} == {"inside", "boundary"}
    grid = compare_runs(a, b).overlay.splitlines()[:-1]
    glyphs = set("".join(grid))
    assert "#" in glyphs and "A" in glyphs and "B" not in glyphs, "\n".join(grid)


# -- sweeps --------------------------------------------------------------------------------


def test_values_text_reads_back_as_the_entry():
    for entry in (
        [20, 30.5],
        [[20, 70], [25, 65]],
        ["slope", "natural"],
        {"from": 20, "to": 40, "count": 21},
        {"from": -0.5, "to": 1e-05, "count": 3},
    ):
        assert parse_values(values_text(entry)) == entry, values_text(entry)


def test_varying_figures_leave_out_what_no_point_changed():
    header = ("point", "a", "precision_cm", "area_cm2", "status", "message", "seconds")
    rows = [
        [1, 1.0, 0.5, 10.0, "ok", "", 0.1],
        [2, 2.0, 0.5, 12.0, "ok", "", 0.1],
        [3, 3.0, 0.5, 99.0, "failed", "boom", 0.1],
    ]
    table = CsvTable(header, rows)
    assert varying_figures(table, ["precision_cm", "area_cm2"]) == ["area_cm2"]


ZIP_SWEEP = """
[[sweep]]
job = "workspace"
combine = "zip"
values."robot3rrr.proximal_cm" = [28, 30, 32]
values."robot3rrr.distal_cm" = [32, 30, 28]
output = "tiny-zip.csv"
"""


@pytest.mark.slow
@async_test
async def test_f8_offers_the_presets_own_sweep_and_plots_an_output(tmp_path):
    from planar_tui.app.screens.sweep import NO_KEY, SweepDialog, SweepScreen

    preset = tmp_path / "tiny.toml"
    preset.write_text((DATA / "tiny.toml").read_text() + ZIP_SWEEP)
    app = WorkbenchApp(Workbench.open(preset), output_dir=tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        app.action_show_tab("workspace")
        await pilot.pause()
        await pilot.press("f8")
        await until(pilot, lambda: isinstance(app.screen, SweepDialog))
        dialog = app.screen
        typed = [
            dialog.query_one(f"#sweep-{p}-{r}", Input).value
            for r in (1, 2)
            for p in ("key", "values")
        ]
        assert typed == ["robot3rrr.proximal_cm", "28, 30, 32", "robot3rrr.distal_cm", "32, 30, 28"]
        assert dialog.query_one("#sweep-combine", Select).value == "zip"
        assert "sweep[1]" in str(dialog.query_one("#sweep-problem").render())
        # Enter on the grid/zip list runs (it does not reopen the list)
        dialog.query_one("#sweep-combine", Select).focus()
        await pilot.press("enter")
        await until(pilot, lambda: not isinstance(app.screen, SweepDialog))
        await finish(app, pilot)
        await until(pilot, lambda: isinstance(app.screen, SweepScreen))
        screen = app.screen
        assert screen.run.sweep.output == "tiny-zip.csv"  # the preset's own sweep
        # an output that changes, against the first key, as a line (the keys are zipped)
        figure = screen.query_one("#sweep-figure", Select).value
        assert figure != "precision_cm" and figure in varying_figures(screen.table, [figure])
        assert screen.query_one("#sweep-across", Select).value == "robot3rrr.proximal_cm"
        assert screen.query_one("#sweep-down", Select).value == NO_KEY
        assert screen.query_one("#sweep-plot").display


# -- wrapped fields -----------------------------------------------------------------------


def shown_in(app, field) -> str:
    """The text a field shows on screen (its rows joined, spaces dropped)."""
    region = field.content_region
    rows = app.export_text().splitlines()[region.y : region.bottom]
    return "".join(row[region.x : region.right] for row in rows).replace(" ", "")


@pytest.mark.slow
@async_test
async def test_a_wrapped_field_is_cleared_whole_and_shown_whole(tmp_path):
    shutil.copy(DATA / "tiny.toml", tmp_path / "tiny.toml")
    app = WorkbenchApp(Workbench.open(tmp_path / "tiny.toml"), output_dir=tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        app.action_show_tab("workspace")
        await pilot.pause()
        field = app.query_one("#pane-workspace #field-joint_limits_deg")
        field.focus()
        await pilot.pause()
        assert field.wrapped_document.height >= 2  # the value wraps at 80 columns
        # End, ctrl+u: the whole value cleared (not its last row), then typed anew
        await pilot.press("end", "ctrl+u", *"[[10,80],[100,170],[240,300]]")
        await until(pilot, lambda: field.value == "[[10,80],[100,170],[240,300]]")
        limits = [[10, 80], [100, 170], [240, 300]]
        await until(
            pilot, lambda: app.workbench.document["workspace"]["joint_limits_deg"] == limits
        )
        # home, ctrl+k: the same from the start
        await pilot.press("home", "ctrl+k", *"[[20,70],[110,160],[245,295]]")
        await until(pilot, lambda: field.value == "[[20,70],[110,160],[245,295]]")
        # edits less than COALESCE_S apart are one undo step: the undo below takes back
        # the backspaces only, not the value typed above
        await pilot.pause(COALESCE_S + 0.2)
        # a value marked bad (its border drawn) is still shown whole, and after an undo
        await pilot.press("end", "backspace", "backspace", "backspace", "backspace")
        await until(pilot, lambda: field.has_class("-bad"))
        await pilot.pause(0.2)
        assert shown_in(app, field) == field.value.replace(" ", "")
        await pilot.press("ctrl+z")
        await pilot.pause(0.5)
        field = app.query_one("#pane-workspace #field-joint_limits_deg")
        assert shown_in(app, field) == field.value.replace(" ", ""), field.value


# -- the live preview ---------------------------------------------------------------------


def map_rows(explorer) -> int:
    """How many rows of the map show a kept box (inside or boundary)."""
    from planar_tui.workspace.paving.map import BOUNDARY_GLYPH, INSIDE_GLYPH

    return sum(INSIDE_GLYPH in row or BOUNDARY_GLYPH in row for row in explorer.map_lines())


@pytest.mark.slow
@async_test
async def test_the_preview_after_an_edit_keeps_the_maps_scale(tmp_path):
    shutil.copy(DATA / "tiny.toml", tmp_path / "tiny.toml")
    app = WorkbenchApp(Workbench.open(tmp_path / "tiny.toml"), output_dir=tmp_path)
    async with app.run_test(size=(120, 40)) as pilot:
        await run_tab(app, pilot, "workspace")
        pane = app.query_one("#pane-workspace")
        explorer = pane.query_one("#workspace-map")
        await pilot.pause(0.2)
        centre, cell_cm, rows = explorer.centre_cm, explorer.cell_cm, map_rows(explorer)
        assert rows >= 6, explorer.map_lines()
        field = pane.query_one("#field-joint_limits_deg")
        field.focus()
        field.value = "[[22, 68], [112, 158], [247, 293]]"  # a little narrower
        await until(pilot, lambda: "preview" in explorer.note, 300)
        # the same view (centre and scale; the legend's lines may take a row), paved at its
        # own cells: every boundary box's longer side in (one cell, two cells]
        assert explorer.centre_cm == centre and explorer.cell_cm == cell_cm
        edge = explorer.boxes[explorer.status == 1]
        sides = np.maximum(edge[:, 1] - edge[:, 0], edge[:, 3] - edge[:, 2])
        assert len(sides) and np.max(sides) <= 2 * cell_cm * (1 + 1e-9)
        assert np.min(sides) > cell_cm * (1 - 1e-9)
        # nearly the job's map, not a block of a few rows
        assert map_rows(explorer) >= 0.7 * rows, explorer.map_lines()


# -- the background warm-up ---------------------------------------------------------------


def test_the_compile_stage_says_compiling_first():
    from planar_tui.app.widgets.job_controls import progress_text
    from planar_tui.progress import ProgressState
    from planar_tui.warmup import STAGE

    text = progress_text(ProgressState(0, 2, STAGE, "workspace:joint kernels"), None)
    assert text == "compiling kernels (first run only): workspace:joint kernels 0/2"


@pytest.mark.slow
@async_test
async def test_the_presets_own_kernels_are_warmed_first_and_never_beside_a_job(
    tmp_path, monkeypatch
):
    """Three kinds 'missing' (markers redirected to tmp_path; the real examples replaced
    by a 0.3 s stand-in that marks them): the preset's sensitivity job (F5 pressed at once)
    is warmed before the kinds the preset does not use (torques, the 5-bar), which come
    in their own order and none while the job runs."""
    from planar_tui import warmup

    todo = ("sensitivity", "torques", "workspace5r")
    present = tmp_path / "warm-others"
    present.touch()
    monkeypatch.setattr(
        warmup, "marker", lambda unit: tmp_path / f"warm-{unit}" if unit in todo else present
    )
    app = WorkbenchApp(Workbench.open(DATA / "tiny.toml"), output_dir=tmp_path, warm_kernels=True)
    started = []

    def stand_in(unit):
        started.append((unit, app.jobs.running))
        time.sleep(0.3)
        (tmp_path / f"warm-{unit}").touch()

    monkeypatch.setattr(warmup, "_run_example", stand_in)
    async with app.run_test(size=SIZE) as pilot:
        app.action_show_tab("sensitivity")
        await pilot.press("f5")
        await finish(app, pilot)
        await until(pilot, lambda: all((tmp_path / f"warm-{u}").exists() for u in todo))
        await app.workers.wait_for_complete()
    assert [unit for unit, _ in started] == list(todo)
    assert not any(running for unit, running in started if unit != "sensitivity"), started


# -- smaller edges -------------------------------------------------------------------------


@pytest.mark.slow
@async_test
async def test_a_preset_opens_on_the_tab_of_its_first_job(tmp_path):
    from textual.widgets import TabbedContent

    presets = Path(__file__).resolve().parent.parent / "presets"
    app = WorkbenchApp(
        Workbench.open(presets / "paper-b-table3.toml"), output_dir=tmp_path, first_job_tab=True
    )
    async with app.run_test(size=SIZE) as pilot:
        await pilot.pause()
        assert app.query_one(TabbedContent).active == "tab-workspace"
        assert await app.open_preset(str(presets / "paper-a-table1.toml"))
        await pilot.pause()
        assert app.query_one(TabbedContent).active == "tab-simulate"


@pytest.mark.slow
@async_test
async def test_opening_a_preset_builds_only_its_own_tabs_until_another_is_visited(tmp_path):
    """The Robot tab and the tabs of the preset's job kinds are built when it opens; any
    other tab's pane (its whole form) only when it is first shown, with the preset's
    values and its form shown or hidden as the others'."""
    presets = Path(__file__).resolve().parent.parent / "presets"
    app = WorkbenchApp(Workbench.open(presets / "paper-b-table3.toml"), output_dir=tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        await pilot.pause()

        def built() -> set[str]:
            return {name for _, name in app.tabs() if app.query(f"#tab-{name} #pane-{name}")}

        assert built() == {"robot", "workspace"}
        assert not app.query_one("#tab-simulate").children
        app.action_toggle_form()  # hidden on every tab, those not built yet too
        app.action_show_tab("simulate")
        await pilot.pause()
        assert built() == {"robot", "workspace", "simulate"}
        assert app.current_pane() is app.query_one("#pane-simulate")
        assert app.query_one("#pane-simulate").has_class("hide-form")
        assert app.query_one("#pane-simulate #field-duration_s", Field).value
        assert await app.open_preset(str(presets / "paper-a-table1.toml"))
        await pilot.pause()
        kinds = {name for _, name in app.tabs() if app.workbench.has(name)}
        assert kinds and "workspace" not in kinds
        assert built() == {"robot", *kinds}


@pytest.mark.slow
@async_test
async def test_the_history_keeps_the_digest_of_the_edited_document_that_ran(tmp_path):
    import hashlib

    preset = tmp_path / "tiny.toml"
    shutil.copy(DATA / "tiny.toml", preset)
    app = WorkbenchApp(Workbench.open(preset), output_dir=tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        await run_tab(app, pilot, "simulate")  # the file as it is
        field = app.query_one("#pane-simulate #field-duration_s")
        field.value = "0.1"
        await until(pilot, lambda: app.workbench.document["simulate"]["duration_s"] == 0.1)
        await pilot.press("f5")
        await finish(app, pilot)
        edited = app.workbench.to_toml()
    first, second = (run.provenance.preset_sha256 for run in app.run_history)
    assert first == hashlib.sha256(preset.read_bytes()).hexdigest()
    assert second == hashlib.sha256(edited.encode()).hexdigest() != first


@pytest.mark.slow
@async_test
async def test_hiding_the_form_restyles_the_shown_tab_and_the_others_when_shown(tmp_path):
    """ctrl+f restyled all 800 widgets of the nine tabs (8-15 s at load 15 on 2 cores):
    now the tab shown at once, each other one when it is next shown."""
    shutil.copy(DATA / "tiny.toml", tmp_path / "tiny.toml")
    app = WorkbenchApp(Workbench.open(tmp_path / "tiny.toml"), output_dir=tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        app.action_show_tab("simulate")
        await pilot.pause()
        form = app.query_one("#pane-simulate .form")
        await pilot.press("ctrl+f")
        await pilot.pause()
        assert not form.display
        assert not app.query_one("#pane-workspace").has_class("hide-form")  # not yet
        app.action_show_tab("workspace")
        await pilot.pause()
        assert not app.query_one("#pane-workspace .form").display
        await pilot.press("ctrl+f")
        await pilot.pause()
        assert app.query_one("#pane-workspace .form").display
        app.action_show_tab("simulate")
        await pilot.pause()
        assert form.display


def test_two_instances_keep_each_others_saved_settings(tmp_path):
    from planar_tui.app.settings import load_settings

    first, second = (WorkbenchApp(Workbench.open(DATA / "tiny.toml")) for _ in range(2))
    first.remember(output_dir=str(tmp_path / "first"))  # the first exports there
    second.remember(theme="nord")  # the second, started before, changes its theme
    saved, warning = load_settings()
    assert warning is None
    assert saved.output_dir == str(tmp_path / "first") and saved.theme == "nord"


@pytest.mark.slow
@async_test
async def test_the_footer_shows_the_error_key_as_soon_as_a_value_is_wrong(tmp_path):
    shutil.copy(DATA / "tiny.toml", tmp_path / "tiny.toml")
    app = WorkbenchApp(Workbench.open(tmp_path / "tiny.toml"), output_dir=tmp_path)
    async with app.run_test(size=(120, 40)) as pilot:
        app.action_show_tab("simulate")
        await pilot.pause()
        field = app.query_one("#pane-simulate #field-duration_s")
        field.focus()
        await pilot.pause()
        footer = lambda: app.export_text().splitlines()[-1]  # noqa: E731
        assert "Error" not in footer()
        await pilot.press("end", "ctrl+u", "minus", "1")
        await until(pilot, lambda: bool(app.problems))
        await pilot.pause()
        assert "^g Error" in footer()
        await pilot.press("backspace", "backspace", "1")
        await until(pilot, lambda: not app.problems)
        await pilot.pause()
        assert "Error" not in footer()


@pytest.mark.slow
@async_test
async def test_the_history_footer_fits_80_columns_with_a_problem_in_the_form(tmp_path):
    from planar_tui.app.screens.history import HistoryScreen

    shutil.copy(DATA / "tiny.toml", tmp_path / "tiny.toml")
    app = WorkbenchApp(Workbench.open(tmp_path / "tiny.toml"), output_dir=tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        app.query_one("#link-1-masses_kg").value = "0"  # a problem: ^g Error in the footer
        await until(pilot, lambda: bool(app.problems))
        await pilot.press("f10")
        await until(pilot, lambda: isinstance(app.screen, HistoryScreen))
        await pilot.pause(0.2)
        footer = app.export_text().splitlines()[-1]
        # every key shown whole, ending in the palette's: no key cut at the edge
        assert "F1 Help" in footer and footer.rstrip().endswith("^p palette"), footer
        assert "Save" not in footer and "Error" not in footer
        await pilot.press("escape")
        await until(pilot, lambda: not isinstance(app.screen, HistoryScreen))
        await pilot.pause(0.2)
        footer = app.export_text().splitlines()[-1]
        assert "^s Save" in footer and "^g Error" in footer


@pytest.mark.slow
@async_test
async def test_every_tab_is_reachable_by_a_key_and_by_name(tmp_path):
    """Issue 32: the app had keys for 6 tabs and there are 9: on the tab bar the digits
    reach the first nine, and the palette names every tab, however many kinds."""
    from textual.widgets import TabbedContent, Tabs

    from planar_tui.app.palette import workbench_commands

    shutil.copy(DATA / "tiny.toml", tmp_path / "tiny.toml")
    app = WorkbenchApp(Workbench.open(tmp_path / "tiny.toml"), output_dir=tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        tabs = app.tabs()
        titles = {command.title for command in workbench_commands(app)}
        assert all(f"Show {title} tab" in titles for title, _ in tabs)
        app.query_one(Tabs).focus()
        for number, (_, name) in enumerate(tabs[:9], start=1):
            await pilot.press(str(number))
            await pilot.pause()
            assert app.query_one(TabbedContent).active == f"tab-{name}"
            app.query_one(Tabs).focus()


@pytest.mark.slow
@async_test
async def test_every_tab_is_reachable_however_many_kinds(tmp_path):
    """Six more kinds registered (15 tabs, past the digits and the function keys): the
    palette shows each by name and ctrl+pagedown steps through all of them in order."""
    from contextlib import ExitStack
    from dataclasses import dataclass

    from textual.widgets import TabbedContent

    from planar_tui.app.palette import workbench_commands
    from planar_tui.jobkind import JobKind, JobResult, Tab
    from planar_tui.registry import registered
    from planar_tui.schema import integer, setting

    @dataclass(frozen=True, kw_only=True)
    class ExtraSpec:
        count: int = setting(integer(minimum=1), type_doc="integer", doc="rows", default=1)

    def run_extra(job, progress):
        return JobResult(table=CsvTable(("i",), [[0]]), summary="one row")

    shutil.copy(DATA / "tiny.toml", tmp_path / "tiny.toml")
    with ExitStack() as stack:
        for number in range(1, 7):
            extra = JobKind(
                f"extra{number}", "robot", ExtraSpec, run_extra, "x", tab=Tab(f"X{number}", 50)
            )
            stack.enter_context(registered(extra))
        app = WorkbenchApp(Workbench.open(tmp_path / "tiny.toml"), output_dir=tmp_path)
        async with app.run_test(size=SIZE) as pilot:
            names = [name for _, name in app.tabs()]
            assert len(names) >= 15 and {f"extra{n}" for n in range(1, 7)} <= set(names)
            titles = {command.title for command in workbench_commands(app)}
            assert all(f"Show {title} tab" in titles for title, _ in app.tabs())
            seen = []
            for _ in names:
                await pilot.press("ctrl+pagedown")
                await pilot.pause()
                seen.append(app.query_one(TabbedContent).active.removeprefix("tab-"))
            assert seen == [*names[1:], names[0]]

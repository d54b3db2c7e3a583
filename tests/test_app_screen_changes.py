"""What a screen change of the workbench builds: a form's key is three widgets (no
container each), and opening a preset keeps the Robot tab's fields (new values in place)
and builds only the new preset's job tabs. Timings: ``benchmarks/bench_app.py --screens``."""

from __future__ import annotations

from pathlib import Path

import pytest
from textual.widgets import Label, Static, TabbedContent

from planar_tui.app.app import WorkbenchApp
from planar_tui.app.widgets.fields import Field, TableForm
from planar_tui.app.workbench import Workbench
from tests.test_app import SIZE, async_test, make_app

PRESETS = Path(__file__).resolve().parent.parent / "presets"


@async_test
async def test_a_form_key_is_its_label_field_and_note_and_the_focused_label_is_bold(tmp_path):
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        await pilot.pause()
        form = app.query_one("#form-robot3rrr", TableForm)
        kinds = [type(child) for child in form.children]
        assert kinds == [Label, Field, Static] * len(form.keys)
        labels = [child for child in form.children if type(child) is Label]
        assert [str(label.content) for label in labels] == list(form.keys)
        app.query_one("#form-robot3rrr #field-distal_cm", Field).focus()
        await pilot.pause()
        current = [str(label.content) for label in labels if label.has_class("-current")]
        assert current == ["distal_cm"]
        assert form.labels["distal_cm"].rich_style.bold
        assert not form.labels["proximal_cm"].rich_style.bold
        app.query_one("#form-robot3rrr #field-proximal_cm", Field).focus()
        await pilot.pause()
        current = [str(label.content) for label in labels if label.has_class("-current")]
        assert current == ["proximal_cm"]


@async_test
async def test_opening_a_preset_keeps_the_robot_tab_and_builds_its_own_job_tabs(tmp_path):
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        await pilot.pause()
        robot = app.query_one("#pane-robot")
        distal = app.query_one("#form-robot3rrr #field-distal_cm", Field)
        name = app.query_one("#robot-form #field-name", Field)
        old_panes = {name: pane for name, pane in app.tab_panes.items() if name != "robot"}
        assert set(old_panes) == {"simulate", "sensitivity", "workspace"}
        assert await app.open_preset(str(PRESETS / "paper-a-table1.toml"))
        await pilot.pause()
        # the same Robot pane and fields, showing the new document's values (six links)
        assert app.query_one("#pane-robot") is robot and app.tab_panes["robot"] is robot
        assert app.query_one("#form-robot3rrr #field-distal_cm", Field) is distal
        assert app.query_one("#robot-form #field-name", Field) is name
        assert name.value == '"6R-PSM, paper A Table 1"'
        assert distal.value == "30.0"  # the default table (no [robot3rrr]); tiny.toml's "30"
        assert robot.editors[0].current_rows()[5][0] == "0.15"
        # the job tabs: the new preset's own kinds built anew, the others not built
        assert set(app.tab_panes) == {"robot", "simulate", "torques"}
        assert app.tab_panes["simulate"] is not old_panes["simulate"]
        assert not any(pane.is_attached for pane in old_panes.values())
        assert not app.query_one("#tab-workspace").children
        assert app.query_one("#tab-simulate #pane-simulate") is app.tab_panes["simulate"]
        assert app.query_one("#pane-simulate #field-every", Field).value == "10"


@pytest.mark.slow
@async_test
async def test_the_robot_tab_after_opening_is_the_robot_tab_of_the_preset_started(tmp_path):
    """Opened into a running app (its Robot tab's fields kept, a job's own robots in a
    picker, more links), a preset's tabs show what an app started on it shows."""

    async def screens(app: WorkbenchApp, pilot, names: list[str]) -> dict[str, str]:
        shown = {}
        for name in names:
            app.action_show_tab(name)
            app.clear_notifications()  # "Opened ..." on one side only
            await pilot.pause()
            await pilot.wait_for_animation()
            shown[name] = "\n".join(app.export_text().splitlines()[2:])  # below the tab bar
        return shown

    running = WorkbenchApp(Workbench.open(PRESETS / "paper-b-table3.toml"), output_dir=tmp_path)
    async with running.run_test(size=(120, 40)) as pilot:
        await pilot.pause()
        for preset in ("paper-a-table4.toml", "fivebar-illustrative.toml"):
            started = WorkbenchApp(Workbench.open(PRESETS / preset), output_dir=tmp_path)
            async with started.run_test(size=(120, 40)) as started_pilot:
                await started_pilot.pause()
                names = ["robot", *(n for _, n in started.tabs()[1:] if started.workbench.has(n))]
                expected = await screens(started, started_pilot, names)
            assert await running.open_preset(str(PRESETS / preset))
            await pilot.pause()
            assert await screens(running, pilot, names) == expected


@async_test
async def test_leaving_a_tab_from_a_focused_field_hands_the_focus_to_no_field_of_it(tmp_path):
    # a form's fields are siblings: Textual handed the focus of a field hidden with its
    # tab to the next field of that form, whose tab then came back
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        app.action_show_tab("sensitivity")
        await pilot.pause()
        app.query_one("#pane-sensitivity #field-seed", Field).focus()
        await pilot.pause()
        app.action_show_tab("workspace")
        await pilot.pause()
        assert app.query_one(TabbedContent).active == "tab-workspace"
        assert app.focused is None

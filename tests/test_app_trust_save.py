"""Pilot tests: the app never loses edits nor overwrites a file without asking (issue 14).

Unsaved-edit marker, undo, save / discard / cancel before quitting or opening, bundled
presets read-only, overwrite questions (save as, export), comments kept by saving, per-link
arrays resized with the robot, every dialog's buttons visible at 80×24, and the inputs
that used to crash the app (unwritable targets, deep nesting, huge integers).
"""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest
from textual.geometry import Region
from textual.widgets import Button

from planar_tui.app.app import WorkbenchApp
from planar_tui.app.saving import merge_document
from planar_tui.app.screens.dialogs import (
    ConfirmDialog,
    MessageDialog,
    PathDialog,
    UnsavedDialog,
)
from planar_tui.app.workbench import Workbench
from planar_tui.presets import load_preset, parse_preset
from planar_tui.resources import bundled_presets_folder
from tests.test_app import DATA, SIZE, async_test, make_app, run_tab, validation

pytestmark = pytest.mark.slow  # end to end (see pyproject.toml's markers)

#: A preset with comments in every kind of place (header, after a table header, after a
#: value, between keys, before a table, at the end) and keys in no particular order.
COMMENTED = """\
# Round trip: comments in several places
# a second header line

[robot]  # the serial robot
name = "2R commented"     # its name
lengths_m = [0.303, 0.214]
# masses after lengths, gravity last
masses_kg = [1.126, 0.796]  # kg
gravity_m_s2 = 9.81

# the simulation
[simulate]
step_s = 0.001
duration_s = 0.2   # seconds
theta0_deg = [30, -60]
every = 5
output = "commented-simulate.csv"
# the end
"""


def commented_app(tmp_path: Path) -> WorkbenchApp:
    path = tmp_path / "commented.toml"
    path.write_text(COMMENTED)
    return WorkbenchApp(Workbench.open(path), output_dir=tmp_path)


async def type_into(pilot, selector: str, text: str) -> None:
    """Focus a field, clear it and type ``text`` key by key (one undo step)."""
    field = pilot.app.query_one(selector)
    field.focus()
    field.value = ""
    await pilot.pause()
    for char in text:
        await pilot.press({".": "full_stop", "-": "minus"}.get(char, char))
    await pilot.pause()


# -- 1. unsaved edits: marker, undo, questions before quitting or opening --------------
@async_test
async def test_modified_marker_and_undo(tmp_path, monkeypatch):
    import planar_tui.app.history

    # however slowly the keys arrive (a loaded machine), one field's typing is one step
    monkeypatch.setattr(planar_tui.app.history, "COALESCE_S", 60.0)
    app = make_app(tmp_path)
    original = {k: dict(v) for k, v in app.workbench.document.items()}
    async with app.run_test(size=SIZE) as pilot:
        await pilot.pause()
        assert app.sub_title == "tiny.toml" and "(modified)" not in validation(app)
        app.action_show_tab("simulate")
        await pilot.pause()
        await type_into(pilot, "#pane-simulate #field-duration_s", "0.15")
        assert app.workbench.document["simulate"]["duration_s"] == 0.15
        assert app.sub_title == "tiny.toml (modified)"
        assert validation(app).startswith("ok: tiny.toml (modified),")
        await pilot.press("ctrl+z")  # clearing and typing the value: one step
        await pilot.pause()
        assert app.workbench.document == original and len(app.workbench.history) == 0
        assert app.query_one("#pane-simulate #field-duration_s").value == "0.2"  # the form too
        assert app.sub_title == "tiny.toml" and "(modified)" not in validation(app)
        await pilot.press("ctrl+z")  # nothing left: says so
        await pilot.pause()
        assert app.workbench.document == original


@async_test
async def test_quit_and_open_with_unsaved_edits_ask_save_discard_cancel(tmp_path):
    app = make_app(tmp_path)
    text = (tmp_path / "tiny.toml").read_text()
    async with app.run_test(size=SIZE) as pilot:
        app.query_one("#robot-form #field-gravity_m_s2").value = "9.8"
        await pilot.pause()
        for key in ("q", "ctrl+q"):
            app.set_focus(None)
            await pilot.press(key)
            await pilot.pause()
            assert isinstance(app.screen, UnsavedDialog)
            assert "tiny.toml has unsaved changes" in app.export_text()
            await pilot.press("escape")  # cancel: still running, edits kept
            await pilot.pause()
            assert app.is_running and app.workbench.document["robot"]["gravity_m_s2"] == 9.8
        await pilot.press("ctrl+o")  # opening another preset asks too
        await pilot.pause()
        assert isinstance(app.screen, UnsavedDialog)
        await pilot.press("c")
        await pilot.pause()
        assert not isinstance(app.screen, UnsavedDialog | PathDialog)
        await pilot.press("ctrl+q")
        await pilot.pause()
        await pilot.press("d")  # discard: quits, the file untouched
        await pilot.pause()
    assert app.return_code == 0
    assert (tmp_path / "tiny.toml").read_text() == text

    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        app.query_one("#robot-form #field-gravity_m_s2").value = "9.8"
        await pilot.pause()
        app.set_focus(None)
        await pilot.press("q")
        await pilot.pause()
        await pilot.press("s")  # save: written into the preset's own file, then quits
        await pilot.pause()
    assert app.return_code == 0
    assert (tmp_path / "tiny.toml").read_text() == text.replace("9.81", "9.8")


# -- 2. bundled presets are read-only; overwriting asks ---------------------------------
@async_test
async def test_a_bundled_preset_is_saved_elsewhere(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    bundled = bundled_presets_folder() / "paper-a-table1.toml"
    before = bundled.read_bytes()
    app = WorkbenchApp(Workbench.open("paper-a-table1"), output_dir=tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        app.query_one("#robot-form #field-gravity_m_s2").value = "9.8"
        await pilot.pause()
        await pilot.press("ctrl+s")
        await pilot.pause()
        assert isinstance(app.screen, PathDialog)  # asks, offering ./NAME.toml
        assert app.screen.query_one("#path-input").value == "paper-a-table1.toml"
        assert "Bundled presets are read-only" in app.export_text()
        app.screen.query_one("#path-input").value = str(bundled)  # its own file: refused
        await pilot.press("enter")
        await pilot.pause()
        assert isinstance(app.screen, MessageDialog)
        assert "bundled presets are read-only" in app.screen.message
        await pilot.press("enter")
        await pilot.press("ctrl+s")
        await pilot.pause()
        await pilot.press("enter")  # the offered ./paper-a-table1.toml
        await pilot.pause()
        assert app.workbench.path == Path("paper-a-table1.toml")
        assert app.sub_title == "paper-a-table1.toml"
    assert bundled.read_bytes() == before
    saved = (tmp_path / "paper-a-table1.toml").read_text()
    assert "gravity_m_s2 = 9.8\n" in saved
    assert saved.splitlines()[0] == before.decode().splitlines()[0]  # its description


@async_test
async def test_save_as_onto_an_existing_file_asks_first(tmp_path):
    app = make_app(tmp_path)
    other = tmp_path / "other.toml"
    other.write_text("# someone else's preset\n")
    async with app.run_test(size=SIZE) as pilot:
        titles = {command.title for command in app.get_system_commands(app.screen)}
        assert {"Save as", "Undo"} <= titles  # in the command palette
        app.query_one("#robot-form #field-gravity_m_s2").value = "9.8"
        await pilot.pause()
        for answer in ("n", "y"):
            await app.run_action("save_as")
            await pilot.pause()
            app.screen.query_one("#path-input").value = str(other)
            await pilot.press("enter")
            await pilot.pause()
            assert isinstance(app.screen, ConfirmDialog)
            assert "This file exists. Overwrite it?" in app.export_text()
            assert app.screen.detail == str(other)
            await pilot.press(answer)
            await pilot.pause()
            if answer == "n":
                assert other.read_text() == "# someone else's preset\n"
                assert app.workbench.modified
        assert "gravity_m_s2 = 9.8\n" in other.read_text()
        assert app.workbench.path == other and not app.workbench.modified


@async_test
async def test_export_asks_before_overwriting_and_lists_the_files(tmp_path):
    app = make_app(tmp_path)
    folder = tmp_path / "out"
    folder.mkdir()
    (folder / "tiny-simulate.csv").write_text("old\n")
    async with app.run_test(size=SIZE) as pilot:
        await run_tab(app, pilot, "simulate")
        for answer in ("n", "y"):
            await pilot.press("ctrl+e")
            await pilot.pause()
            app.screen.query_one("#path-input").value = str(folder)
            await pilot.press("enter")
            await pilot.pause()
            assert isinstance(app.screen, ConfirmDialog)
            screen = app.export_text()
            assert "Overwrite 1 file?" in screen and "tiny-simulate.csv" in screen
            await pilot.press(answer)
            await pilot.pause()
            if answer == "n":
                assert (folder / "tiny-simulate.csv").read_text() == "old\n"
    assert (folder / "tiny-simulate.csv").read_text().startswith("t_s,")


# -- 3. saving keeps comments, order and formatting --------------------------------------
@async_test
async def test_saving_keeps_every_comment_and_the_order(tmp_path):
    app = commented_app(tmp_path)
    path = tmp_path / "commented.toml"
    async with app.run_test(size=SIZE) as pilot:
        app.action_show_tab("simulate")
        await pilot.pause()
        await type_into(pilot, "#pane-simulate #field-duration_s", "0.1")
        edited = app.workbench.document
        await pilot.press("ctrl+s")
        await pilot.pause()
    # exactly one value changed; every comment, blank line and key stays where it was
    assert path.read_text() == COMMENTED.replace("duration_s = 0.2 ", "duration_s = 0.1 ")
    assert load_preset(path).jobs == parse_preset(path, edited).jobs


def test_merge_updates_appends_and_deletes_in_place():
    text = (
        "# head\n[robot]  # r\nname = 'a'  # n\nlengths_m = [1, 2]\nmasses_kg = [1, 2]\n\n"
        "[[simulate]]  # first\nduration_s = 1\n\n[[simulate]]\nduration_s = 2  # two\n"
    )
    document = tomllib.loads(text)
    del document["robot"]["masses_kg"]  # removed key
    document["robot"]["name"] = "b"  # changed value, trailing comment kept
    document["robot"]["gravity_m_s2"] = 9.81  # new key
    document["simulate"][1]["duration_s"] = 3
    document["simulate"].append({"duration_s": 4})  # a new table of the array
    document["workspace"] = {"precision_cm": 1.0, "robot3rrr": {"proximal_cm": 30}}
    merged = merge_document(text, document)
    assert tomllib.loads(merged) == document
    for comment in ("# head", "# r", "# n", "# first", "# two"):
        assert comment in merged
    assert "masses_kg" not in merged and 'name = "b"  # n' in merged
    assert merged.index("lengths_m") < merged.index("gravity_m_s2") < merged.index("[[simulate]]")
    # an array of tables can also shrink
    document["simulate"] = document["simulate"][:1]
    assert tomllib.loads(merge_document(merged, document)) == document


# -- 4. adding or removing a link resizes the jobs' per-link arrays -------------------
PER_LINK_PRESET = """\
[robot]
lengths_m = [0.3, 0.2]
masses_kg = [1.0, 0.8]

[[simulate]]
theta0_deg = [30, -60]
omega0_deg_s = [1, 2]
torques_Nm = [0.5, 0.1]
duration_s = 0.01
step_s = 0.001
output = "a.csv"

[[simulate]]
duration_s = 0.01
step_s = 0.001
output = "b.csv"

[torques]
theta_deg = [[0, 0], [30, 60]]
omega_deg_s = [[1, 1], [2, 2]]
output = "t.csv"

[[sensitivity]]
posture = [10, 20]
samples = 8
output = "s.csv"

[[sensitivity]]
posture = "singular"
samples = 8
output = "s2.csv"
[sensitivity.robot]
lengths_m = [0.3]
masses_kg = [1.0]
"""


@async_test
async def test_adding_and_removing_a_link_resizes_every_job(tmp_path):
    path = tmp_path / "links.toml"
    path.write_text(PER_LINK_PRESET)
    app = WorkbenchApp(Workbench.open(path), output_dir=tmp_path)
    notes: list[str] = []
    notify = app.notify
    app.notify = lambda message, **kwargs: notes.append(message) or notify(message, **kwargs)
    async with app.run_test(size=SIZE) as pilot:
        await pilot.press("ctrl+n")
        await pilot.pause()
        document = app.workbench.document
        first, second = document["simulate"]
        assert first["theta0_deg"] == [30, -60, 0.0] and first["omega0_deg_s"] == [1, 2, 0.0]
        assert first["torques_Nm"] == [0.5, 0.1, 0.0]
        assert "theta0_deg" not in second  # the defaults fit any robot
        assert document["torques"]["theta_deg"] == [[0, 0, 0.0], [30, 60, 0.0]]
        assert document["torques"]["omega_deg_s"] == [[1, 1, 0.0], [2, 2, 0.0]]
        sensitivity, own_robot = document["sensitivity"]
        assert sensitivity["posture"] == [10, 20, 0.0]
        assert own_robot["robot"]["lengths_m"] == [0.3]  # a job with its own robot: untouched
        assert validation(app).startswith("ok:")
        assert notes == [
            "simulate.theta0_deg, simulate.omega0_deg_s, simulate.torques_Nm, "
            "torques.theta_deg, torques.omega_deg_s, sensitivity.posture "
            "resized to 3 links (new links: 0)"
        ]
        app.action_show_tab("simulate")
        await pilot.pause()
        assert app.query_one("#pane-simulate #field-theta0_deg").value == "[30, -60, 0.0]"
        app.action_show_tab("robot")
        await pilot.pause()
        await pilot.press("ctrl+r")
        await pilot.pause()
        first = app.workbench.document["simulate"][0]
        assert first["theta0_deg"] == [30, -60] and first["torques_Nm"] == [0.5, 0.1]
        assert app.workbench.document["torques"]["theta_deg"] == [[0, 0], [30, 60]]
        assert validation(app).startswith("ok:")
        await pilot.press("ctrl+r")  # 1 link
        await pilot.pause()
        assert app.workbench.document["simulate"][0]["theta0_deg"] == [30]
        assert validation(app).startswith("ok:")
        await pilot.press("ctrl+z")  # one step: the link and the arrays come back
        await pilot.pause()
        assert app.workbench.document["simulate"][0]["theta0_deg"] == [30, -60]
        assert app.query_one("#link-2-lengths_m").value == "0.2"
        assert validation(app).startswith("ok:")
        await run_tab(app, pilot, "simulate")
        assert app.query_one("#pane-simulate").result is not None


# -- 5. every dialog shows its buttons whole at 80×24 -----------------------------------
def assert_buttons_visible(app: WorkbenchApp, expected: int) -> None:
    """Each button of the dialog on top: its label on screen, its region on the screen
    and inside its container (not clipped to its top border)."""
    screen_text = app.export_text()
    buttons = list(app.screen.query(Button))
    assert len(buttons) == expected, [str(b.label) for b in buttons]
    whole = Region(0, 0, *SIZE)
    for button in buttons:
        label = str(button.label)
        assert label in screen_text, (label, screen_text)
        assert whole.contains_region(button.region), (label, button.region)
        assert button.parent.region.contains_region(button.region), (label, button.region)
        assert button.region.height == 3, label  # border, label, border


@async_test
async def test_every_dialog_shows_its_choices_at_80x24(tmp_path, monkeypatch):
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:

        async def check(expected_buttons: int, *texts: str) -> None:
            await pilot.pause()
            assert len(app.screen_stack) == 2, app.screen_stack
            assert_buttons_visible(app, expected_buttons)
            for text in texts:
                assert text in app.export_text()
            app.pop_screen()
            await pilot.pause()

        # quitting while a job runs (the question that showed only its buttons' top borders)
        monkeypatch.setattr(type(app.jobs), "running", property(lambda self: True))
        app.set_focus(None)
        await pilot.press("q")
        await check(2, "A job is running. Cancel it and quit?", "Yes (y)", "No (n)")
        monkeypatch.undo()
        app.push_screen(MessageDialog("Not saved", "error: x.toml: key: problem (expected y)"))
        await check(1, "Close (Enter)", "Not saved")
        await pilot.press("ctrl+o")  # the picker (no buttons: enter / escape)
        await check(0, "Open preset", "Enter: open", "Escape: cancel")
        await pilot.press("f1")
        await check(0, "Help (escape closes", "ctrl+z        undo")
        app.query_one("#robot-form #field-gravity_m_s2").value = "9.8"
        await pilot.pause()
        app.set_focus(None)
        await pilot.press("q")
        await check(3, "unsaved changes")  # save / discard / cancel
        monkeypatch.chdir(tmp_path)  # a short path: the whole of it shows
        Path("exists.toml").write_text("")
        app.confirm_save(Path("exists.toml"), "", None)
        await check(2, "This file exists. Overwrite it?", "exists.toml")
        # the export's question, listing many files
        pane = app.query_one("#pane-simulate")
        await run_tab(app, pilot, "simulate")
        (tmp_path / "tiny-simulate.csv").write_text("")
        app.confirm_export(pane, tmp_path)
        await check(2, "Overwrite 1 file?", "Overwrite (y)")


# -- 6. what used to crash the app: a dialog or the error line, the edits kept ----------
@async_test
async def test_save_onto_a_folder_or_into_an_unwritable_one_shows_a_dialog(tmp_path, monkeypatch):
    import planar_tui.csvio

    app = make_app(tmp_path)
    (tmp_path / "folder.toml").mkdir()
    (tmp_path / "file").write_text("")

    def denied(path, text):
        raise PermissionError(13, "Permission denied", str(path))

    async with app.run_test(size=SIZE) as pilot:
        app.query_one("#robot-form #field-gravity_m_s2").value = "9.8"
        await pilot.pause()
        targets = {
            tmp_path / "folder.toml": "is a folder",
            tmp_path / "file" / "x.toml": "is not a writable folder",
        }
        for target, reason in targets.items():
            app.save_preset(target)
            await pilot.pause()
            assert isinstance(app.screen, MessageDialog)
            assert reason in app.export_text()
            app.pop_screen()
        monkeypatch.setattr(planar_tui.csvio, "write_text_atomic", denied)
        await pilot.press("ctrl+s")  # the folder turned read-only since it was opened
        await pilot.pause()
        assert isinstance(app.screen, MessageDialog)
        assert "cannot write: Permission denied" in app.export_text()
        app.pop_screen()
        assert app.is_running and app.workbench.modified
        assert app.workbench.document["robot"]["gravity_m_s2"] == 9.8


@async_test
async def test_export_onto_a_folder_or_a_bad_path_shows_a_dialog(tmp_path):
    app = make_app(tmp_path)
    folder = tmp_path / "out"
    (folder / "tiny-simulate.csv").mkdir(parents=True)
    async with app.run_test(size=SIZE) as pilot:
        await run_tab(app, pilot, "simulate")
        pane = app.query_one("#pane-simulate")
        for out_dir, reason in ((folder, "is a folder"), (f"{tmp_path}/a\0b", "NUL character")):
            app.confirm_export(pane, out_dir)
            await pilot.pause()
            assert isinstance(app.screen, MessageDialog)
            assert reason in app.export_text()
            app.pop_screen()
            assert app.export_csv(pane, out_dir) == []
            await pilot.pause()
            app.pop_screen()
        assert app.is_running and pane.result is not None


@async_test
async def test_opening_a_deep_or_huge_preset_keeps_the_edits(tmp_path):
    deep = tmp_path / "deep.toml"
    deep.write_text("[robot]\nname = " + "[" * 1000 + "]" * 1000 + "\n")
    huge = tmp_path / "huge.toml"
    huge.write_text((DATA / "tiny.toml").read_text().replace("0.2\n", "9" * 5000 + "\n"))
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        app.query_one("#robot-form #field-gravity_m_s2").value = "9.8"
        await pilot.pause()
        for path, reason in ((deep, "nested too deep"), (huge, "integer")):
            assert not await app.open_preset(str(path))
            await pilot.pause()
            assert isinstance(app.screen, MessageDialog)
            assert str(path) in app.screen.message and reason in app.screen.message
            assert reason in app.export_text()
            app.pop_screen()
            assert app.workbench.path.name == "tiny.toml"
            assert app.workbench.document["robot"]["gravity_m_s2"] == 9.8


@async_test
async def test_typing_600_brackets_or_a_310_digit_integer_shows_the_error_line(tmp_path):
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        app.action_show_tab("simulate")
        await pilot.pause()
        field = app.query_one("#pane-simulate #field-duration_s")
        field.value = "[" * 600
        await pilot.pause()
        assert "simulate.duration_s: is a string" in validation(app)
        assert app.workbench.document["simulate"]["duration_s"] == "[" * 600
        field.value = "1" * 310
        await pilot.pause()
        line = validation(app)  # the parser names the key and the size
        assert "simulate.duration_s: " in line and "310 digits" in line
        await pilot.press("f5")  # running it: refused with the reason, not a crash
        await pilot.pause()
        assert app.is_running and not app.job_running
        assert "310 digits" in validation(app)
        await pilot.press("ctrl+s")  # saving it: only as a draft, after a question
        await pilot.pause()
        assert isinstance(app.screen, ConfirmDialog)
        assert "The preset is invalid. Save it as a draft" in app.export_text()
        await pilot.press("n")
        await pilot.pause()
        assert app.is_running and field.value == "1" * 310


def test_undo_steps_one_per_field_and_one_per_link(monkeypatch):
    import planar_tui.app.history

    monkeypatch.setattr(planar_tui.app.history, "COALESCE_S", 60.0)  # all edits "at once"
    bench = Workbench.open(DATA / "tiny.toml")
    robot = dict(bench.document["robot"])  # gravity 9.81, 2 links
    for gravity in (9, 9.7):  # typed into one field: "9", then "9.7"
        robot = robot | {"gravity_m_s2": gravity}
        bench.set_table("robot", 0, robot)
    for n in (3, 4):  # two links added
        robot = robot | {"lengths_m": [0.3] * n, "masses_kg": [1.0] * n, "inertias_kgm2": [0.1] * n}
        bench.set_table("robot", 0, robot)
    assert len(bench.history) == 3
    assert bench.undo() and len(bench.document["robot"]["lengths_m"]) == 3
    assert bench.undo() and bench.document["robot"]["lengths_m"] == [0.303, 0.214]
    assert bench.document["robot"]["gravity_m_s2"] == 9.7
    assert bench.undo() and bench.document["robot"]["gravity_m_s2"] == 9.81
    assert not bench.undo() and not bench.modified


def test_any_parser_failure_becomes_a_preset_error_naming_the_key():
    import pytest

    from planar_tui.app.workbench import guarded
    from planar_tui.errors import PresetError

    def fails(error: Exception):
        def action():
            raise error

        return action

    document = {"simulate": {"theta0_deg": [0, 10**400]}, "robot": {"name": [[[[]]]]}}
    with pytest.raises(PresetError) as caught:
        guarded(Path("p.toml"), fails(OverflowError("int too large")), document)
    assert caught.value.key == "simulate.theta0_deg[2]"
    assert caught.value.problem == "is an integer of 401 digits"
    deep: list = []
    for _ in range(30):
        deep = [deep]
    with pytest.raises(PresetError) as caught:
        guarded(Path("p.toml"), fails(RecursionError()), {"robot": {"name": deep}})
    assert caught.value.key.startswith("robot.name[1][1]")
    assert caught.value.problem == "is nested too deep"
    with pytest.raises(PresetError) as caught:  # no document: the file as a whole
        guarded(Path("p.toml"), fails(RecursionError()))
    assert str(caught.value).startswith("error: p.toml: (syntax): is nested too deep to read")

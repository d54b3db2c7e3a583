"""A recent-files state (``recent.json``) that cannot be used is a warning and empty
lists, and is set aside (``recent.json.damaged``), never overwritten, when the app next
remembers a file."""

from __future__ import annotations

import json
import os

import pytest

from planar_tui.app import recent
from planar_tui.app.app import WorkbenchApp
from planar_tui.app.settings import MAX_STATE_BYTES
from planar_tui.app.workbench import Workbench
from tests.test_app import DATA, SIZE, async_test

#: Damaged states by what is wrong, and the words of the warning.
DAMAGED = {
    "not JSON": ("{", "not JSON"),
    "a list": ("[1, 2]", "not an object of presets and results"),
    "an unknown key": ('{"presets": [], "files": []}', "not an object of presets and results"),
    "a number among paths": ('{"presets": ["/a.toml", 1]}', "presets is not a list of paths"),
    "text for a list": ('{"results": "/r.csv"}', "results is not a list of paths"),
    "over its bound": (json.dumps({"presets": ["x" * MAX_STATE_BYTES]}), "more than the 512 KiB"),
}


def state_file(text: str) -> str:
    path = recent.recent_path()
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return str(path)


@pytest.mark.parametrize("case", sorted(DAMAGED))
def test_a_damaged_state_warns_once_and_is_set_aside_not_overwritten(case, tmp_path):
    text, words = DAMAGED[case]
    path = state_file(text)
    lists, warning = recent.load_checked()
    assert lists == {"presets": [], "results": []}
    assert warning is not None and warning.startswith(f"{path}: ") and words in warning
    assert "\n" not in warning and "recent.json.damaged" in warning
    note = recent.remember("presets", tmp_path / "p.toml")
    assert note is not None and f"kept as {path}.damaged" in note
    with open(f"{path}.damaged", encoding="utf-8") as kept:
        assert kept.read() == text  # the user's file, whole
    assert recent.load_checked() == (
        {"presets": [str(tmp_path / "p.toml")], "results": []},
        None,
    )


def test_a_second_damaged_state_does_not_replace_the_first_one_set_aside(tmp_path):
    path = state_file("{")
    recent.remember("presets", tmp_path / "a.toml")
    state_file("[")
    note = recent.remember("presets", tmp_path / "b.toml")
    assert note is not None and f"kept as {path}.damaged.2" in note
    with open(f"{path}.damaged", encoding="utf-8") as first:
        assert first.read() == "{"
    with open(f"{path}.damaged.2", encoding="utf-8") as second:
        assert second.read() == "["


@pytest.mark.parametrize("make", ["fifo", "zero"])
def test_a_state_that_is_no_regular_file_warns_and_is_renamed(make, tmp_path):
    path = recent.recent_path()
    path.parent.mkdir(parents=True, exist_ok=True)
    if make == "fifo":
        os.mkfifo(path)
    else:
        path.symlink_to("/dev/zero")
    warning = recent.load_checked()[1]
    assert warning is not None and "is not a regular file" in warning
    assert recent.remember("results", tmp_path / "r.csv") is not None
    aside = path.with_name("recent.json.damaged")
    assert aside.is_fifo() if make == "fifo" else os.readlink(aside) == "/dev/zero"
    assert recent.load()["results"] == [str(tmp_path / "r.csv")]


def test_a_good_state_gives_no_warning_and_is_updated_in_place(tmp_path):
    state_file(json.dumps({"presets": ["/a.toml"], "results": ["/r.csv"]}))
    assert recent.load_checked() == ({"presets": ["/a.toml"], "results": ["/r.csv"]}, None)
    assert recent.remember("presets", tmp_path / "b.toml") is None
    assert recent.load()["presets"] == [str(tmp_path / "b.toml"), "/a.toml"]
    assert not recent.recent_path().with_name("recent.json.damaged").exists()


@async_test
async def test_the_app_shows_the_warning_once_and_says_where_the_file_went(tmp_path):
    path = state_file('{"presets": 3}')
    app = WorkbenchApp(Workbench.open(DATA / "tiny.toml"), output_dir=tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        await pilot.pause()
        assert app.is_running and app.recent_warning is not None
        shown = [str(n.message) for n in app._notifications]
        assert shown.count(app.recent_warning) == 1 and path in app.recent_warning
        app.remember_recent("presets", tmp_path / "p.toml")
        await pilot.pause()
        shown = [str(n.message) for n in app._notifications]
        assert any(f"kept as {path}.damaged" in message for message in shown)
    with open(f"{path}.damaged", encoding="utf-8") as kept:
        assert kept.read() == '{"presets": 3}'

"""Snapshot tests (pytest-textual-snapshot) of every screen at 80×24 and 120×40.

Update after an intended change of the layout with ``pytest tests/test_app_snapshots.py
--snapshot-update`` and review the SVGs in ``tests/__snapshots__/``.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from planar_tui.app.app import WorkbenchApp
from planar_tui.app.workbench import Workbench

REPO = Path(__file__).resolve().parent.parent
PRESET = Path("tests") / "data" / "app" / "tiny.toml"  # relative: no machine path on screen
SIZES = [(80, 24), (120, 40)]
SCREENS = ["robot", "sensitivity", "workspace", "simulate", "help", "invalid"]


def before(screen: str):
    async def run_before(pilot) -> None:
        app = pilot.app
        if screen == "help":
            await pilot.press("f1")
        elif screen == "invalid":  # an edit the preset parser rejects, in the CLI's words
            app.query_one("#link-1-masses_kg").value = "0"
        else:
            app.action_show_tab(screen)
        await pilot.pause()

    return run_before


@pytest.mark.parametrize("size", SIZES, ids=lambda s: f"{s[0]}x{s[1]}")
@pytest.mark.parametrize("screen", SCREENS)
def test_screen(snap_compare, screen, size, monkeypatch):
    monkeypatch.chdir(REPO)
    app = WorkbenchApp(Workbench.open(PRESET))
    assert snap_compare(app, terminal_size=size, run_before=before(screen))

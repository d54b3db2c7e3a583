"""Snapshot tests (pytest-textual-snapshot) of the drawn and explorable views at 80×24 and
120×40: the Simulate tab's playback and the Workspace tab's map explorer, each showing a
result computed here without the runner (deterministic: the summaries are fixed).

Update after an intended change with ``pytest tests/test_app_snapshots_views.py
--snapshot-update`` and review the SVGs in ``tests/__snapshots__/``.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest

from planar_tui.app.app import WorkbenchApp
from planar_tui.app.workbench import Workbench

pytestmark = pytest.mark.slow  # end to end (see pyproject.toml's markers)

REPO = Path(__file__).resolve().parent.parent
PRESET = Path("tests") / "data" / "app" / "explore.toml"  # relative: no machine path on screen
SIZES = [(80, 24), (120, 40)]
SCREENS = ["playback", "explore"]


def show_result(app: WorkbenchApp, kind: str) -> None:
    """Run the pane's job in this thread (no runner, no timing on screen) and show it."""
    from planar_tui.progress import Progress
    from planar_tui.registry import JOB_KINDS

    pane = app.query_one(f"#pane-{kind}")
    job = pane.current_job()
    result = JOB_KINDS[kind].run(JOB_KINDS[kind].prepare_job(job), Progress())
    pane.show_result(job, dataclasses.replace(result, summary=f"{kind}: recorded result"))


def before(screen: str):
    async def run_before(pilot) -> None:
        app = pilot.app
        kind = "simulate" if screen == "playback" else "workspace"
        app.action_show_tab(kind)
        await pilot.pause()
        show_result(app, kind)
        await pilot.pause()
        if screen == "playback":
            app.query_one("#simulate-arm").focus()
            await pilot.press(*["right"] * 25)
        else:
            app.query_one("#workspace-map").focus()
            await pilot.press("right", "right", "up", "b")
        await pilot.pause()

    return run_before


@pytest.mark.parametrize("size", SIZES, ids=lambda s: f"{s[0]}x{s[1]}")
@pytest.mark.parametrize("screen", SCREENS)
def test_view(snap_compare, screen, size, monkeypatch):
    monkeypatch.chdir(REPO)
    app = WorkbenchApp(Workbench.open(PRESET))
    assert snap_compare(app, terminal_size=size, run_before=before(screen))

"""Snapshot tests (pytest-textual-snapshot) of the run history (``F10``) and the comparison
of two runs (``c``) at 80×24 and 120×40: two Sobol' runs of ``tests/data/app/tiny.toml``
(seeds 1 and 2, N = 64) written by ``planar-tui sensitivity``, kept with their sidecars
in ``tests/data/app/history/`` (their start times and the preset's path fixed, so the
screens are deterministic), opened as ``planar-tui tui --open`` opens them.

Update after an intended change with ``pytest tests/test_app_snapshots_history.py
--snapshot-update`` and review the SVGs in ``tests/__snapshots__/``.
"""

from __future__ import annotations

import time
from pathlib import Path

import pytest

from planar_tui.app.app import WorkbenchApp
from planar_tui.app.workbench import Workbench

pytestmark = pytest.mark.slow  # end to end (see pyproject.toml's markers)

REPO = Path(__file__).resolve().parent.parent
PRESET = Path("tests") / "data" / "app" / "tiny.toml"  # relative: no machine path on screen
RUNS = [Path("tests") / "data" / "app" / "history" / f"seed{seed}.csv" for seed in (1, 2)]
SIZES = [(80, 24), (120, 40)]
SCREENS = ["history", "compare"]


@pytest.fixture
def utc(monkeypatch):
    """The history shows start times in the machine's zone: UTC here, whatever the host."""
    monkeypatch.setenv("TZ", "UTC")
    time.tzset()
    yield
    monkeypatch.undo()
    time.tzset()


def before(screen: str):
    async def run_before(pilot) -> None:
        from planar_tui.app.screens.history import CompareScreen, HistoryScreen

        app = pilot.app
        while not isinstance(app.screen, HistoryScreen):  # opened first, as with --open
            await pilot.pause(0.05)
        await pilot.pause()
        if screen == "compare":
            await pilot.press("c")
            while not isinstance(app.screen, CompareScreen):
                await pilot.pause(0.05)
        await pilot.pause()

    return run_before


@pytest.mark.parametrize("size", SIZES, ids=lambda s: f"{s[0]}x{s[1]}")
@pytest.mark.parametrize("screen", SCREENS)
def test_history(snap_compare, screen, size, monkeypatch, utc):
    monkeypatch.chdir(REPO)
    app = WorkbenchApp(Workbench.open(PRESET))
    app.open_results(RUNS)
    assert snap_compare(app, terminal_size=size, run_before=before(screen))

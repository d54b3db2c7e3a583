"""Snapshot tests (pytest-textual-snapshot) of every screen at 80×24 and 120×40.

Update after an intended change of the layout with ``pytest tests/test_app_snapshots.py
--snapshot-update`` and review the SVGs in ``tests/__snapshots__/``.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from planar_tui.app.app import WorkbenchApp
from planar_tui.app.workbench import Workbench
from planar_tui.sensitivity.results import csv_table
from planar_tui.sensitivity.runner import SensitivityResult
from tests.test_app_layout import load_6r

pytestmark = pytest.mark.slow  # end to end (see pyproject.toml's markers)

REPO = Path(__file__).resolve().parent.parent
PRESET = Path("tests") / "data" / "app" / "tiny.toml"  # relative: no machine path on screen
PRESET_6R = Path("presets") / "paper-a-table1.toml"  # its default sensitivity job: 6R
SIZES = [(80, 24), (120, 40)]
SCREENS = [
    "robot",
    "sensitivity",
    "workspace",
    "simulate",
    "help",
    "invalid",
    "sensitivity-6r",
    "sensitivity-6r-noform",
]


def show_6r_result(app: WorkbenchApp) -> None:
    """The recorded 6R result (tests/data/app/sensitivity-6r.json) on the Sensitivity tab,
    as if its job had just run (no job runs: the snapshot stays deterministic)."""
    analyses = load_6r()
    pane = app.query_one("#pane-sensitivity")
    job = pane.current_job()
    result = SensitivityResult(
        table=csv_table("6R", analyses),
        summary="6R-PSM, paper A Table 1 singular, 1 speed(s), sobol N=1024, efast N=1194",
        robot_label="6R",
        posture=None,
        analyses=analyses,
        samples={"sobol": 1024, "efast": 1194},
    )
    pane.show_result(job, result)


def before(screen: str):
    async def run_before(pilot) -> None:
        app = pilot.app
        if screen.startswith("sensitivity-6r"):
            app.action_show_tab("sensitivity")
            await pilot.pause()
            if screen.endswith("noform"):
                await pilot.press("ctrl+f")
                await pilot.pause()
            show_6r_result(app)
        elif screen == "help":
            await pilot.press("f1")
        elif screen == "invalid":  # an edit the preset parser rejects, in the CLI's words
            app.query_one("#link-1-masses_kg").value = "0"
        else:
            app.action_show_tab(screen)
        await pilot.pause()

    return run_before


CASES = [(screen, size) for screen in SCREENS for size in SIZES]
CASES.remove(("sensitivity-6r-noform", (120, 40)))  # at 120 columns the form changes nothing


@pytest.mark.parametrize(
    ("screen", "size"), CASES, ids=lambda v: f"{v[0]}x{v[1]}" if isinstance(v, tuple) else v
)
def test_screen(snap_compare, screen, size, monkeypatch):
    monkeypatch.chdir(REPO)
    app = WorkbenchApp(Workbench.open(PRESET_6R if "6r" in screen else PRESET))
    assert snap_compare(app, terminal_size=size, run_before=before(screen))

"""Regenerate the workbench screenshots (SVG and plain text) at 80×24.

Run from the repository root: ``python docs/screenshots/make_screenshots.py``. Each tab is
shown on ``tests/data/app/tiny.toml`` after its job ran (the Robot tab as opened; Motion
with its form hidden, ``ctrl+f``, so the band plot has the width), and
``sensitivity-6r`` shows the bundled ``paper-a-table1`` preset's default 6R sensitivity job
with the form hidden (``ctrl+f``), the widest table the app shows at 80 columns;
``sweep`` is the result screen of an ``F8`` sweep of tiny's simulation (a heat map of the
second joint's final angle over its link mass and the duration). On
``tests/data/app/explore.toml``: ``playback`` is the Simulate tab after its run, form
hidden, the arm focused and scrubbed to t = 0.5 s; ``explore`` the Workspace tab after its
run, form hidden, the map focused, the cursor moved and the exact boundary shown (``b``).
``history`` is the run history (``F10``) of two Sobol' runs of tiny (seeds 1 and 2) opened
from their CSVs and sidecars in ``tests/data/app/history/`` (as ``planar-tui tui --open``
opens them; times shown in UTC), ``compare`` their comparison (``c``).

``python docs/screenshots/make_screenshots.py NAME ...`` regenerates only those captures
(and skips the runs no named capture needs).
"""

from __future__ import annotations

import asyncio
import os
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO))

from planar_tui.app.settings import CONFIG_DIR_VARIABLE  # noqa: E402

# a fresh settings folder: the user's saved settings (form hidden, theme) neither change
# the captures nor are overwritten by them
os.environ[CONFIG_DIR_VARIABLE] = tempfile.mkdtemp(prefix="planar-tui-captures-")
# the history's start times in UTC, whatever the machine's zone; recent files kept apart
os.environ["TZ"] = "UTC"
time.tzset()
os.environ["PLANAR_TUI_STATE_DIR"] = tempfile.mkdtemp(prefix="planar-tui-captures-state-")

from planar_tui.app.app import WorkbenchApp  # noqa: E402
from planar_tui.app.workbench import Workbench  # noqa: E402

OUT = Path(__file__).resolve().parent
SIZE = (80, 24)
#: The captures asked for on the command line (none: all of them).
SELECTED = set(sys.argv[1:])
#: The captures other than the history's (they need the tabs' runs).
OTHERS = (
    "robot",
    "sensitivity",
    "workspace",
    "simulate",
    "motion",
    "help",
    "sweep",
    "sensitivity-6r",
    "playback",
    "explore",
)


def wanted(*names: str) -> bool:
    return not SELECTED or bool(SELECTED & set(names))


async def wait_for_job(app: WorkbenchApp, pilot) -> None:
    while app.job_running:
        await pilot.pause(0.05)
    await app.workers.wait_for_complete()
    await pilot.pause(0.3)


def save(app: WorkbenchApp, name: str) -> None:
    if not wanted(name):
        return
    app.save_screenshot(str(OUT / f"{name}.svg"))
    (OUT / f"{name}.txt").write_text(app.export_text(), encoding="utf-8")


async def main() -> None:
    await history()
    if SELECTED and not wanted(*OTHERS):
        return
    app = WorkbenchApp(Workbench.open(Path("tests/data/app/tiny.toml")), output_dir="/tmp")
    async with app.run_test(size=SIZE) as pilot:
        await pilot.pause()
        save(app, "robot")
        for tab in ("sensitivity", "workspace", "simulate"):
            app.action_show_tab(tab)
            await pilot.pause()
            await pilot.press("f5")
            await wait_for_job(app, pilot)
            save(app, tab)
        if wanted("motion"):
            app.action_show_tab("motion_uncertainty")  # the default job; form hidden
            await pilot.pause()
            await pilot.press("f5")
            await wait_for_job(app, pilot)
            await pilot.press("ctrl+f")
            await pilot.pause(0.3)
            save(app, "motion")
            await pilot.press("ctrl+f")
        await pilot.press("f1")
        await pilot.pause()
        save(app, "help")
        await pilot.press("escape")
        if not wanted("sweep"):
            return await views()
        app.action_show_tab("simulate")
        await pilot.pause()
        await pilot.press("f8")
        await pilot.pause()
        for field, text in (
            ("#sweep-key-1", "robot.masses_kg[2]"),
            ("#sweep-values-1", "0.5..1.5 x6"),
            ("#sweep-key-2", "duration_s"),
            ("#sweep-values-2", "0.1..0.2 x5"),
        ):
            app.screen.query_one(field).value = text
        await pilot.press("enter")
        await wait_for_job(app, pilot)
        sweep = app.screen
        sweep.query_one("#sweep-figure").value = "theta2_end_rad"
        await pilot.pause(0.3)
        save(app, "sweep")
    if wanted("sensitivity-6r"):
        app = WorkbenchApp(Workbench.open(Path("presets/paper-a-table1.toml")), output_dir="/tmp")
        async with app.run_test(size=SIZE) as pilot:
            app.action_show_tab("sensitivity")
            await pilot.pause()
            await pilot.press("ctrl+f", "f5")
            await wait_for_job(app, pilot)
            save(app, "sensitivity-6r")
    await views()


async def views() -> None:
    """The playback and the map explorer (``playback``, ``explore``)."""
    if not wanted("playback", "explore"):
        return
    app = WorkbenchApp(Workbench.open(Path("tests/data/app/explore.toml")), output_dir="/tmp")
    async with app.run_test(size=SIZE) as pilot:
        app.action_show_tab("simulate")
        await pilot.pause()
        await pilot.press("f5")
        await wait_for_job(app, pilot)
        await pilot.press("ctrl+f")
        app.query_one("#simulate-arm").focus()
        await pilot.press(*["right"] * 50)
        await pilot.pause(0.3)
        save(app, "playback")
        app.action_show_tab("workspace")
        await pilot.pause()
        await pilot.press("f5")
        await wait_for_job(app, pilot)
        app.query_one("#workspace-map").focus()
        await pilot.press("right", "right", "up", "up", "b")
        await pilot.pause(0.3)
        save(app, "explore")


async def history() -> None:
    """The run history of two recorded runs and their comparison (``history``,
    ``compare``)."""
    if not wanted("history", "compare"):
        return
    runs = [Path(f"tests/data/app/history/seed{seed}.csv") for seed in (1, 2)]
    app = WorkbenchApp(Workbench.open(Path("tests/data/app/tiny.toml")), output_dir="/tmp")
    app.open_results(runs)  # as `planar-tui tui --open` does: the history shows first
    async with app.run_test(size=SIZE) as pilot:
        while "Run history" not in app.export_text():
            await pilot.pause(0.05)
        await pilot.pause(0.3)
        save(app, "history")
        await pilot.press("c")
        while "(A) vs" not in app.export_text():
            await pilot.pause(0.05)
        await pilot.pause(0.3)
        save(app, "compare")


def sync_page() -> None:
    """Put each text capture into docs/app.md's code block under its ``[SVG](…NAME.svg)``
    heading, so the page shows what the app shows."""
    import re

    page = REPO / "docs" / "app.md"
    text = page.read_text(encoding="utf-8")
    for capture in sorted(OUT.glob("*.txt")):
        pattern = re.compile(
            r"(\(screenshots/" + re.escape(capture.stem) + r"\.svg\)[^\n]*\n\n```text\n)"
            r"(.*?)(```)",
            re.DOTALL,
        )
        body = capture.read_text(encoding="utf-8").rstrip("\n") + "\n"
        text = pattern.sub(lambda match, body=body: match[1] + body + match[3], text)
    page.write_text(text, encoding="utf-8")


if __name__ == "__main__":
    asyncio.run(main())
    sync_page()

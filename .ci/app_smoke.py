"""Headless smoke run of the installed app (run by .ci/run from the wheel's venv, outside
the repository): open a bundled preset, switch to the Workspace tab, run it, quit.

Fails (exit 1) if the stylesheet or the bundled presets are missing from the install, or
the job does not finish with a map.
"""

from __future__ import annotations

import asyncio
import sys
import time

import planar_tui
from planar_tui.app.app import WorkbenchApp
from planar_tui.app.workbench import Workbench


async def main() -> int:
    app = WorkbenchApp(Workbench.open("paper-b-table5"))
    async with app.run_test(size=(80, 24)) as pilot:
        await pilot.press("right", "right")
        await pilot.pause()
        await pilot.press("f5")
        pane = app.query_one("#pane-workspace")
        deadline = time.monotonic() + 240
        while pane.result is None:
            if time.monotonic() > deadline:
                print("app smoke: the workspace job did not finish", file=sys.stderr)
                return 1
            await pilot.pause(0.2)
        print(f"app smoke: {planar_tui.__file__}: {pane.result.summary}")
        await pilot.press("q")
    return 0


if __name__ == "__main__":
    sys.exit(asyncio.run(main()))

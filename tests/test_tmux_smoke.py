"""Real-terminal smoke test: the app in tmux at 80×24, driven by keys only.

Opens ``planar-tui tui`` on the smallest workspace preset, switches to the Workspace tab
(right arrow twice on the tab bar), runs it (F5), waits for the map and area, then quits
with ``q``. Polls the screen with a timeout instead of sleeping blindly.
"""

from __future__ import annotations

import os
import re
import shlex
import shutil
import subprocess
import sys
import time
import uuid
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent
TMUX = shutil.which("tmux") or "/usr/bin/tmux"
PRESET = "tests/data/app/workspace-small.toml"


def tmux(socket: str, *args: str) -> str:
    return subprocess.run(
        [TMUX, "-L", socket, *args], capture_output=True, text=True, check=True
    ).stdout


def wait_for(socket: str, predicate, timeout_s: float, what: str) -> str:
    deadline = time.monotonic() + timeout_s
    screen = ""
    while time.monotonic() < deadline:
        screen = tmux(socket, "capture-pane", "-p", "-t", "smoke")
        if predicate(screen):
            return screen
        time.sleep(0.2)
    raise AssertionError(f"timed out waiting for {what}; screen was:\n{screen}")


# SGR parameters that select one of 256 colours or a 24-bit colour (foreground/background)
RICH_COLOUR = re.compile(r"\x1b\[[0-9;]*[34]8;[25];")


@pytest.mark.parametrize(
    "terminal",
    ["TERM=xterm-256color", "TERM=xterm TEXTUAL_COLOR_SYSTEM=standard"],
    ids=["256-colours", "16-colours"],
)
def test_app_in_tmux_runs_a_workspace_job_and_quits(tmp_path, terminal):
    socket = f"planar-tui-{uuid.uuid4().hex[:8]}"
    status_file = tmp_path / "status"
    command = (
        f"cd {shlex.quote(str(REPO))} && {terminal} "
        f"{shlex.quote(sys.executable)} -m planar_tui tui {PRESET}; "
        f"echo $? > {shlex.quote(str(status_file))}; sleep 30"
    )
    env = dict(os.environ, PYTHONPATH=str(REPO))
    subprocess.run(
        [
            TMUX,
            "-L",
            socket,
            "-f",
            "/dev/null",
            "new-session",
            "-d",
            "-s",
            "smoke",
            "-x",
            "80",
            "-y",
            "24",
            command,
        ],
        check=True,
        env=env,
    )
    try:
        wait_for(socket, lambda s: "Workspace" in s and "ok: workspace-small" in s, 60, "the app")
        tmux(socket, "send-keys", "-t", "smoke", "Right")
        tmux(socket, "send-keys", "-t", "smoke", "Right")
        wait_for(socket, lambda s: "precision_cm" in s, 20, "the Workspace tab")
        tmux(socket, "send-keys", "-t", "smoke", "F5")
        screen = wait_for(socket, lambda s: "done in" in s, 120, "the workspace job")
        assert "arc-distance eps=0.9375" in screen and "cm2" in screen, screen  # the summary
        assert "█" in screen and "x, y in cm" in screen, screen  # the map
        if "standard" in terminal:  # a 16-colour terminal gets only its 16 colours
            styled = tmux(socket, "capture-pane", "-e", "-p", "-t", "smoke")
            assert "\x1b[" in styled and not RICH_COLOUR.search(styled), styled
        tmux(socket, "send-keys", "-t", "smoke", "q")
        deadline = time.monotonic() + 20
        while not status_file.exists():
            assert time.monotonic() < deadline, "the app did not quit on q"
            time.sleep(0.2)
        assert status_file.read_text().strip() == "0"
    finally:
        subprocess.run([TMUX, "-L", socket, "kill-server"], capture_output=True)

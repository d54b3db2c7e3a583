"""Real-terminal smoke test: the app in an 80×24 pseudo-terminal, driven by keys only.

Opens ``planar-tui tui`` on the smallest workspace preset, switches to the Workspace tab
(right arrow twice on the tab bar), runs it (F5), waits for the map and area, then quits
with ``q``. The terminal is a pty rendered by the ``pyte`` emulator (``tests/pty_terminal.py``);
it replaces a tmux-based test, so the README's test command needs no system program. Polls
the screen with a timeout instead of sleeping blindly; on a 16-colour terminal it checks
the raw bytes the app wrote, which show every colour code it sent.
"""

from __future__ import annotations

import os
import re
import sys
from pathlib import Path

import pytest

from tests.pty_terminal import PtyTerminal

pytestmark = pytest.mark.slow  # end to end (see pyproject.toml's markers)

REPO = Path(__file__).resolve().parent.parent
PRESET = "tests/data/app/workspace-small.toml"

# SGR parameters that select one of 256 colours or a 24-bit colour (foreground/background)
RICH_COLOUR = re.compile(rb"\x1b\[[0-9;]*[34]8;[25];")
# An SGR that sets one of the 16 colours (30-37, 40-47, 90-97, 100-107)
BASIC_COLOUR = re.compile(rb"\x1b\[(?:[0-9]+;)*(?:3[0-7]|4[0-7]|9[0-7]|10[0-7])(?:;[0-9]+)*m")

RIGHT = "\x1b[C"
F5 = "\x1b[15~"

# Variables of the runner's environment that would override what the test sets up: the
# window size (the pty's size must win), colour choices, Textual's own settings.
NOT_INHERITED = ("COLUMNS", "LINES", "COLORTERM", "NO_COLOR", "FORCE_COLOR")


def app_environment(terminal: dict[str, str]) -> dict[str, str]:
    env = {
        name: value
        for name, value in os.environ.items()
        if name not in NOT_INHERITED and not name.startswith("TEXTUAL")
    }
    env.update(PYTHONPATH=str(REPO), **terminal)
    return env


@pytest.mark.parametrize(
    "terminal",
    [{"TERM": "xterm-256color"}, {"TERM": "xterm", "TEXTUAL_COLOR_SYSTEM": "standard"}],
    ids=["256-colours", "16-colours"],
)
def test_app_in_a_terminal_runs_a_workspace_job_and_quits(terminal):
    with PtyTerminal() as term:
        term.start(
            [sys.executable, "-m", "planar_tui", "tui", PRESET],
            env=app_environment(terminal),
            cwd=REPO,
            columns=80,
            rows=24,
        )
        term.wait_for(
            lambda s: "Workspace" in s and "workspace-small.toml, 1 job" in s, 60, "the app"
        )
        # the app opens on the tab of the preset's first (and only) job: Workspace
        term.wait_for(lambda s: "precision_cm" in s, 20, "the Workspace tab")
        term.send(F5)  # the first run in a fresh cache compiles the numba kernels
        screen = term.wait_for(lambda s: "done in" in s, 120, "the workspace job")
        assert "arc-distance eps=0.9375" in screen and "cm2" in screen, screen  # the summary
        assert "█" in screen and "x, y in cm" in screen, screen  # the map
        if terminal.get("TEXTUAL_COLOR_SYSTEM") == "standard":  # only the 16 colours
            raw = term.raw_output()
            assert b"\x1b[" in raw and BASIC_COLOUR.search(raw), screen
            rich = RICH_COLOUR.findall(raw)
            assert not rich, f"256-colour or 24-bit codes {rich[:5]} on a 16-colour terminal"
        term.send("q")
        assert term.wait_exit(20) == 0, term.screen_text()

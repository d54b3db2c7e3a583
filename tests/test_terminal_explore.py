"""Real-terminal test of the new views: an 80×24 pty in 16 colours (``tests/pty_terminal.py``)
plays a simulation (focus the arm, step to t = 0.5 s, play to the end) and explores the
workspace map (focus it, move the cursor, zoom), driven by keys only."""

from __future__ import annotations

import re
import sys
import time

import pytest

from tests.pty_terminal import PtyTerminal
from tests.test_terminal_smoke import BASIC_COLOUR, F5, REPO, RICH_COLOUR, RIGHT, app_environment

pytestmark = pytest.mark.slow  # end to end (see pyproject.toml's markers)

PRESET = "tests/data/app/explore.toml"
TAB = "\t"
UP = "\x1b[A"
F4 = "\x1bOS"


def focus(term: PtyTerminal, hint: str, what: str) -> None:
    """Press Tab until the view whose read-out shows ``hint`` while unfocused has the focus.

    The hint must stay gone for a while: a screen read mid-redraw (a focused field's
    highlight being drawn) can lack it for a moment while the view is still unfocused."""

    def settled_without_hint() -> bool:
        for _ in range(4):
            if hint in term.screen_text():
                return False
            time.sleep(0.2)
        return True

    for _ in range(30):
        if settled_without_hint():
            return
        term.send(TAB)
        try:
            term.wait_for(lambda s: hint not in s, 1.5, what)
        except AssertionError:
            continue
    if settled_without_hint():
        return
    raise AssertionError(f"Tab never reached {what}:\n{term.screen_text()}")


def test_play_a_simulation_and_explore_the_map_at_80x24_in_16_colours():
    with PtyTerminal() as term:
        term.start(
            [sys.executable, "-m", "planar_tui", "tui", PRESET],
            env=app_environment({"TERM": "xterm", "TEXTUAL_COLOR_SYSTEM": "standard"}),
            cwd=REPO,
            columns=80,
            rows=24,
        )
        term.wait_for(lambda s: "explore.toml, 2 jobs valid" in s, 60, "the app")
        # the app opens on the tab of the preset's first job: Simulate
        term.wait_for(lambda s: "duration_s" in s, 20, "the Simulate tab")
        # keys sent while the app still lays out its first screen can be split (a digit
        # of F5's sequence selects a tab): wait for the tab bar's underline to settle
        term.wait_for(lambda s: "╸" in s.splitlines()[1], 20, "the tab underline")
        time.sleep(1.0)
        term.send(F5)
        term.wait_for(lambda s: "done in" in s and "t = 0 s / 1 s" in s, 120, "the simulation")
        focus(term, "(Tab to the arm", "the arm")
        term.send(RIGHT * 50)  # 101 rows: one row (10 ms) a step
        screen = term.wait_for(lambda s: "t = 0.5 s / 1 s" in s, 30, "t = 0.5 s")
        assert "#" in screen and "+" in screen and "m" in screen  # base, tip, scale bar
        assert re.search(r"θ1 -?[\d.]+°", screen), screen
        term.send(" ")
        term.wait_for(lambda s: "t = 1 s / 1 s ‖" in s, 30, "the playback's end")
        term.send(F4)  # the Workspace tab (tab 3)
        term.wait_for(lambda s: "precision_cm" in s, 20, "the Workspace tab")
        term.send(F5)
        term.wait_for(lambda s: "done in" in s and "(x, y) = (" in s, 120, "the workspace map")
        focus(term, "(Tab to the map", "the map")
        before = re.search(r"\(x, y\) = \(([-\d.]+), ([-\d.]+)\)", term.screen_text())
        assert before
        term.send(RIGHT + RIGHT + UP)
        screen = term.wait_for(
            lambda s: (
                (m := re.search(r"\(x, y\) = \(([-\d.]+), ([-\d.]+)\)", s)) is not None
                and float(m.group(1)) > float(before.group(1))
                and float(m.group(2)) > float(before.group(2))
            ),
            20,
            "the cursor moved right and up",
        )
        assert re.search(r"cm  (inside|boundary|outside)", screen), screen
        assert "@" in screen and "x, y in cm" in screen and "█" in screen, screen
        term.send("+")
        term.wait_for(lambda s: "@" in s, 20, "the zoomed map")
        raw = term.raw_output()
        assert BASIC_COLOUR.search(raw)
        rich = RICH_COLOUR.findall(raw)
        assert not rich, f"256-colour or 24-bit codes {rich[:5]} on a 16-colour terminal"
        term.send("q")
        assert term.wait_exit(20) == 0, term.screen_text()

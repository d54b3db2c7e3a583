"""Real-terminal test of typing (issue 20, defect 3): keys sent to the app's pty in one
write, as a fast typist on a busy machine sends them, land in the order typed, and
``ctrl+z`` undoes the edit in place (the Simulate tab, the focus on the field it was on).

Before the fix, ``End ctrl+u 200 Tab End ctrl+u 1e-5`` on the Simulate tab gave
``duration_s = 2001e-5`` (the printable keys queued on the first field, End and ``ctrl+u``
run on the second) and an emptied ``step_s``.
"""

from __future__ import annotations

import shutil
import sys
from pathlib import Path

import pytest

from tests.pty_terminal import PtyTerminal
from tests.test_terminal_smoke import app_environment

pytestmark = pytest.mark.slow  # end to end (see pyproject.toml's markers)

DATA = Path(__file__).resolve().parent / "data" / "app"

F6 = "\x1b[17~"
END = "\x1b[F"
CTRL_U = "\x15"
CTRL_Z = "\x1a"


def value_under(screen: str, key: str) -> str:
    """The form's value shown on the line under the label ``key`` (left column)."""
    lines = screen.splitlines()
    for row, line in enumerate(lines[:-1]):
        if line.split("▕")[0].strip() == key:
            return lines[row + 1].split("▕")[0].strip(" █▌▐▎▍▋▊▉")  # less the focus bar
    raise AssertionError(f"no field {key} on screen:\n{screen}")


def focused_field(screen: str) -> str | None:
    """The label of the form field whose value line carries the focus bar ``█``, if any."""
    lines = screen.splitlines()
    for row, line in enumerate(lines[1:], start=1):
        if line.startswith("█"):
            return lines[row - 1].split("▕")[0].strip()
    return None


def test_a_burst_of_keys_lands_in_order_and_undo_stays_in_place(tmp_path):
    shutil.copy(DATA / "tiny.toml", tmp_path / "tiny.toml")
    with PtyTerminal() as term:
        term.start(
            [sys.executable, "-m", "planar_tui", "tui", "tiny.toml"],
            env=app_environment({"TERM": "xterm", "TEXTUAL_COLOR_SYSTEM": "standard"}),
            cwd=tmp_path,
            columns=80,
            rows=24,
        )
        term.wait_for(lambda s: "tiny.toml, 3 jobs valid" in s, 60, "the app")
        term.send(F6)  # the Simulate tab (the focus goes to the tab bar)
        term.wait_for(lambda s: "duration_s" in s and "step_s" in s, 20, "the Simulate tab")
        term.send("\t")  # the first field: duration_s
        term.wait_for(lambda s: focused_field(s) == "duration_s", 20, "the focus in duration_s")
        term.send(END + CTRL_U + "200\t" + END + CTRL_U + "1e-5")  # one write: a burst
        screen = term.wait_for(lambda s: value_under(s, "step_s") == "1e-5", 30, "the burst typed")
        assert value_under(screen, "duration_s") == "200", screen
        term.send(CTRL_Z)  # undo: in place, same tab and field
        screen = term.wait_for(lambda s: value_under(s, "step_s") == "0.001", 30, "the undo")
        # Edits of one table within 1.5 s of each other are one undo step
        # (history.COALESCE_S): quiet, the burst is one step; while the app still compiles
        # kernels in the background (a fresh install), its keys may land further apart and
        # be several steps. Undo until duration_s is back, each undo changing it.
        for _ in range(8):
            shown = value_under(screen, "duration_s")
            if shown == "0.2":
                break
            term.send(CTRL_Z)
            screen = term.wait_for(
                lambda s, shown=shown: value_under(s, "duration_s") != shown, 30, "an undo"
            )
        assert value_under(screen, "duration_s") == "0.2", screen
        assert value_under(screen, "step_s") == "0.001", screen
        focused = [line for line in screen.splitlines() if line.startswith("█")]
        assert [line.split("▕")[0].strip() for line in focused] == ["█0.001"], screen
        term.send("\x11")  # ctrl+q: back at the saved state, so it quits without asking
        assert term.wait_exit(20) == 0, term.screen_text()

"""The Torques tab: the serial arm drawn at the job's first state, before and after a run;
the tip's cell is computed here from the closed-form joint positions (paper A eq. 1) and
the viewport's stated map, not from the drawing code."""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import pytest

from planar_tui.app.app import WorkbenchApp
from planar_tui.app.workbench import Workbench
from tests.test_app import async_test, run_tab

PRESET = Path(__file__).resolve().parent.parent / "presets" / "paper-a-table1.toml"
#: The first state: relative angles whose tip is not on an axis.
THETA_DEG = [30, 45, -60, 20, 10, -15]


def tip_cell(lengths_m: list[float], theta_deg: list[float], columns: int, rows: int):
    """The cell of the arm's tip in a ``columns × rows`` drawing (the last row: the scale
    bar): the tip ``Σ l_i (cos Σθ, sin Σθ)`` in the square ``[-R, R]²``, ``R = Σ l_i``,
    fitted into ``2·columns × 4·(rows - 1)`` braille dots and centred."""
    angle, x, y = 0.0, 0.0, 0.0
    for length, theta in zip(lengths_m, theta_deg, strict=True):
        angle += math.radians(theta)
        x, y = x + length * math.cos(angle), y + length * math.sin(angle)
    reach = sum(lengths_m)
    width, height = 2 * columns, 4 * (rows - 1)
    scale = min((width - 1) / (2 * reach), (height - 1) / (2 * reach))
    return math.floor(width / 2 + x * scale) // 2, math.floor(height / 2 - y * scale) // 4


def tips_on_screen(app: WorkbenchApp) -> list[tuple[int, int]]:
    """The cells (column, row) of the drawing that show the tip glyph ``+``."""
    region = app.query_one("#torques-arm").content_region
    lines = app.export_text().splitlines()
    return [
        (column, row)
        for row in range(region.height)
        for column in range(region.width)
        if lines[region.y + row][region.x + column : region.x + column + 1] == "+"
    ]


@async_test
async def test_the_torques_tab_draws_the_arm_at_the_first_state(tmp_path):
    text = PRESET.read_text(encoding="utf-8")
    old = "theta_deg = [[0, 0, 0, 0, 0, 0], [10, 20, 30, 40, 50, 60]]"
    assert old in text
    preset = tmp_path / "table1.toml"
    preset.write_text(text.replace(old, f"theta_deg = [{THETA_DEG}, [10, 20, 30, 40, 50, 60]]"))
    lengths = tomllib.loads(text)["robot"]["lengths_m"]
    app = WorkbenchApp(Workbench.open(preset), output_dir=tmp_path)
    async with app.run_test(size=(120, 40)) as pilot:
        app.action_show_tab("torques")
        await pilot.pause()
        region = app.query_one("#torques-arm").content_region
        assert region.width >= 20 and region.height >= 8
        expected = tip_cell(lengths, THETA_DEG, region.width, region.height)
        assert tips_on_screen(app) == [expected]  # before a run: the form's first state
        await run_tab(app, pilot, "torques")
        assert app.query_one("#pane-torques").result is not None
        region = app.query_one("#torques-arm").content_region
        expected = tip_cell(lengths, THETA_DEG, region.width, region.height)
        assert tips_on_screen(app) == [expected]
        assert "state 1" in app.export_text()


@pytest.mark.slow
@async_test
async def test_the_drawing_shows_the_state_chosen_with_the_arrow_keys(tmp_path):
    """With the drawing focused, → / ← / end / home choose the state drawn: the tip is in
    the cell of the chosen row's angles (closed form), before and after a run."""
    states = [THETA_DEG, [10, 20, 30, 40, 50, 60], [-90, 30, 30, 30, 30, 30]]
    text = PRESET.read_text(encoding="utf-8")
    old = "theta_deg = [[0, 0, 0, 0, 0, 0], [10, 20, 30, 40, 50, 60]]"
    preset = tmp_path / "table1.toml"
    zeros = [0] * 6
    edited = text.replace(old, f"theta_deg = {states}")
    for key in ("omega_deg_s", "alpha_deg_s2"):  # a third row of rates
        line = next(line for line in text.splitlines() if line.startswith(f"{key} = "))
        edited = edited.replace(line, f"{line[:-1]}, {zeros}]")
    preset.write_text(edited)
    lengths = tomllib.loads(text)["robot"]["lengths_m"]
    app = WorkbenchApp(Workbench.open(preset), output_dir=tmp_path)
    async with app.run_test(size=(120, 40)) as pilot:
        app.action_show_tab("torques")
        await pilot.pause()
        app.query_one("#torques-arm").focus()
        await pilot.pause()

        async def drawn_at(keys: list[str], row: int) -> None:
            await pilot.press(*keys)
            await pilot.pause()
            region = app.query_one("#torques-arm").content_region
            assert tips_on_screen(app) == [
                tip_cell(lengths, states[row], region.width, region.height)
            ], (keys, row)
            assert f"state {row + 1}/3" in app.export_text()

        await drawn_at([], 0)
        await drawn_at(["right"], 1)
        await drawn_at(["right", "right"], 2)  # stops at the last
        await drawn_at(["left"], 1)
        await drawn_at(["home"], 0)
        await drawn_at(["left"], 0)  # stops at the first
        await drawn_at(["end"], 2)
        await run_tab(app, pilot, "torques")
        assert app.query_one("#pane-torques").result is not None
        app.query_one("#torques-arm").focus()
        await drawn_at([], 2)  # the chosen state kept after the run
        await drawn_at(["left"], 1)

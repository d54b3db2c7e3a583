"""Pilot test of the workspace map's error layer: a job with ``accuracy`` offers it (``a``),
each cell's glyph the band of the worst ``max(|Δx|, |Δy|)`` bound of the accuracy boxes
over the cell, ``?`` where one of them is not certified (computed here from the boxes),
``a`` again hides it."""

from __future__ import annotations

import numpy as np
import pytest

from planar_tui.app.app import WorkbenchApp
from planar_tui.app.workbench import Workbench
from tests.test_app import DATA, async_test, run_tab
from tests.test_app_dexterity import plot_cells

pytestmark = pytest.mark.slow  # end to end (see pyproject.toml's markers)

GLYPHS = "1234?"


def accurate_app(tmp_path):
    """The app on tiny.toml with ``accuracy`` in its workspace job."""
    text = (DATA / "tiny.toml").read_text(encoding="utf-8")
    text = text.replace(
        'form = "arc-distance"\n',
        'form = "arc-distance"\nelbow = [1, -1, 1]\n'
        "accuracy = { actuator_deg = 0.1, tolerance_cm = 0.01 }\n",
        1,
    )
    path = tmp_path / "tiny.toml"
    path.write_text(text, encoding="utf-8")
    return WorkbenchApp(Workbench.open(path), output_dir=tmp_path)


def expected_glyph(explorer, column, row, accuracy):
    """The band of the worst bound of the boxes overlapping the cell's interior: quarters
    of [0, the largest certified bound]."""
    x_lo, _, _, y_hi = explorer.extent()
    cell = explorer.cell_cm
    cx0, cx1 = x_lo + column * cell, x_lo + (column + 1) * cell
    cy1 = y_hi - row * 2 * cell
    cy0 = cy1 - 2 * cell
    b = accuracy.boxes
    over = (b[:, 1] > cx0) & (b[:, 0] < cx1) & (b[:, 3] > cy0) & (b[:, 2] < cy1)
    if not over.any():
        return " "
    error = np.maximum(accuracy.bound[:, 0], accuracy.bound[:, 1])
    worst = error[over].max()
    if not np.isfinite(worst):
        return "?"
    edges = error[np.isfinite(error)].max() * np.arange(1, 5) / 4
    return "1234"[min(3, int(np.argmax(worst <= edges)))]


@async_test
async def test_a_toggles_the_error_layer_drawn_from_the_boxes(tmp_path):
    app = accurate_app(tmp_path)
    async with app.run_test(size=(120, 40)) as pilot:
        await run_tab(app, pilot, "workspace")
        pane = app.query_one("#pane-workspace")
        explorer = pane.query_one("#workspace-map")
        accuracy = pane.result.accuracy
        assert explorer.accuracy is accuracy and len(accuracy.boxes)
        before = plot_cells(explorer)
        assert "a: error map" in str(pane.query_one("#workspace-legend").render())
        explorer.focus()
        await pilot.press("a")
        await pilot.pause()
        shown = plot_cells(explorer)
        legend = str(pane.query_one("#workspace-legend").render())
        expected = [
            [expected_glyph(explorer, column, row, accuracy) for column in range(len(line))]
            for row, line in enumerate(shown)
        ]
        await pilot.press("a")
        await pilot.pause()
        hidden = plot_cells(explorer)
    assert not any(g in line for line in before for g in GLYPHS)
    assert "? not certified" in legend and " cm" in legend
    marked = [
        (column, row, glyph)
        for row, line in enumerate(shown)
        for column, glyph in enumerate(line)
        if glyph in GLYPHS
    ]
    assert {"?"} < {g for _, _, g in marked} and len({g for _, _, g in marked}) >= 3
    for column, row, glyph in marked:
        assert glyph == expected[row][column], (column, row)
    assert not any(g in line for line in hidden for g in GLYPHS)

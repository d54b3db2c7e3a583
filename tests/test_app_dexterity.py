"""Pilot tests of the workspace map's κ layer: a job with ``kappa_max`` offers it (``k``),
each cell's glyph the band of the worst κ upper bound of the dexterity boxes over the cell
(computed here from the boxes), ``k`` again hides it."""

from __future__ import annotations

import numpy as np
import pytest

from planar_tui.app.app import WorkbenchApp
from planar_tui.app.workbench import Workbench
from planar_tui.app.widgets.workspace_explorer import LABEL_CELLS
from tests.test_app import DATA, async_test, run_tab

pytestmark = pytest.mark.slow  # end to end (see pyproject.toml's markers)

GLYPHS = "1234?"


def dexterous_app(tmp_path):
    """The app on tiny.toml with ``kappa_max = 4`` in its workspace job."""
    text = (DATA / "tiny.toml").read_text(encoding="utf-8")
    text = text.replace(
        'form = "arc-distance"\n', 'form = "arc-distance"\nkappa_max = 4\nelbow = [1, -1, 1]\n', 1
    )
    path = tmp_path / "tiny.toml"
    path.write_text(text, encoding="utf-8")
    return WorkbenchApp(Workbench.open(path), output_dir=tmp_path)


def plot_cells(explorer):
    """The map's plot cells (rows top down, without the y labels and the x axis)."""
    columns, rows = explorer.plot_size()
    return [line[LABEL_CELLS : LABEL_CELLS + columns] for line in explorer.map_lines()[:rows]]


def expected_glyph(explorer, column, row, kappa):
    """The band of the worst ``kappa_hi`` of the boxes overlapping the cell's interior."""
    x_lo, _, _, y_hi = explorer.extent()
    cell = explorer.cell_cm
    cx0, cx1 = x_lo + column * cell, x_lo + (column + 1) * cell
    cy1 = y_hi - row * 2 * cell
    cy0 = cy1 - 2 * cell
    b = kappa.boxes
    over = (b[:, 1] > cx0) & (b[:, 0] < cx1) & (b[:, 3] > cy0) & (b[:, 2] < cy1)
    if not over.any():
        return " "
    worst = kappa.kappa[over, 1].max()
    if worst > kappa.kappa_max:
        return "?"
    edges = 1.0 + (kappa.kappa_max - 1.0) * np.arange(1, 5) / 4
    return "1234"[int(np.argmax(worst <= edges))]


@async_test
async def test_k_toggles_the_kappa_layer_drawn_from_the_boxes(tmp_path):
    app = dexterous_app(tmp_path)
    async with app.run_test(size=(120, 40)) as pilot:
        await run_tab(app, pilot, "workspace")
        pane = app.query_one("#pane-workspace")
        explorer = pane.query_one("#workspace-map")
        kappa = pane.result.dexterity
        assert explorer.kappa is kappa and len(kappa.boxes)
        before = plot_cells(explorer)
        legend = str(pane.query_one("#workspace-legend").render())
        assert "k: κ map" in legend
        explorer.focus()
        await pilot.press("k")
        await pilot.pause()
        shown = plot_cells(explorer)
        legend = str(pane.query_one("#workspace-legend").render())
        expected = [
            [expected_glyph(explorer, column, row, kappa) for column in range(len(line))]
            for row, line in enumerate(shown)
        ]
        await pilot.press("k")
        await pilot.pause()
        hidden = plot_cells(explorer)
    assert not any(g in line for line in before for g in GLYPHS)
    assert "1 κ ≤ 1.75" in legend and "? not proved ≤ 4" in legend
    marked = [
        (column, row, glyph)
        for row, line in enumerate(shown)
        for column, glyph in enumerate(line)
        if glyph in GLYPHS
    ]
    assert len({g for _, _, g in marked}) >= 2  # several bands drawn
    for column, row, glyph in marked:
        assert glyph == expected[row][column], (column, row)
    assert not any(g in line for line in hidden for g in GLYPHS)

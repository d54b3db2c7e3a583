"""Pilot test of the workspace map's error layer: a job with ``accuracy`` offers it (``a``),
each cell's glyph the band of the worst ``max(|Δx|, |Δy|)`` bound of the accuracy boxes
over the cell, ``?`` where one of them is not certified (computed here from the boxes),
``a`` again hides it."""

from __future__ import annotations

import numpy as np
import pytest

from tests.test_app import async_test
from tests.test_app_dexterity import GLYPHS, app_with, over_cell, toggle_layer

pytestmark = pytest.mark.slow  # end to end (see pyproject.toml's markers)


def accurate_app(tmp_path):
    """The app on tiny.toml with ``accuracy`` in its workspace job."""
    keys = "elbow = [1, -1, 1]\naccuracy = { actuator_deg = 0.1, tolerance_cm = 0.01 }\n"
    return app_with(tmp_path, keys)


def expected_glyph(explorer, column, row, accuracy):
    """The band of the worst bound of the boxes overlapping the cell's interior: quarters
    of [0, the largest certified bound]."""
    over = over_cell(explorer, column, row, accuracy.boxes)
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
        layer = await toggle_layer(app, pilot, "a", "accuracy", "accuracy", expected_glyph)
    assert "a: error map" in layer.legend_before
    assert not any(g in line for line in layer.before for g in GLYPHS)
    assert "? not certified" in layer.legend and " cm" in layer.legend
    marked = layer.marked()
    assert {"?"} < {g for _, _, g in marked} and len({g for _, _, g in marked}) >= 3
    for column, row, glyph in marked:
        assert glyph == layer.expected[row][column], (column, row)
    assert not any(g in line for line in layer.hidden for g in GLYPHS)

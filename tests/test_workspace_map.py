"""The workspace map always labels both axes with at least two values."""

from __future__ import annotations

import re

import numpy as np
import pytest

from planar_tui.workspace.paving.map import render_map


@pytest.mark.parametrize("height", [6, 8, 9, 12, 30])
@pytest.mark.parametrize("extent", [(28, 52, 2.5, 12.5), (0, 1, 0, 0.3), (-60, 180, -60, 180)])
def test_small_and_large_maps_have_two_labels_per_axis(height, extent):
    lines = render_map(np.array([extent]), np.array([1]), width=50, height=height, extent=extent)
    rows = [line for line in lines if "┤" in line]
    y_labels = [float(line.split("┤")[0]) for line in rows if line.split("┤")[0].strip()]
    x_labels = [float(v) for v in re.findall(r"-?\d+(?:\.\d+)?", lines[len(rows) + 1])]
    assert len(y_labels) >= 2 and len(x_labels) >= 2
    assert y_labels == sorted(y_labels, reverse=True)  # top to bottom
    assert all(extent[2] <= y <= extent[3] for y in y_labels)
    assert all(extent[0] <= x <= extent[1] for x in x_labels)


@pytest.mark.parametrize("width", [80, 60, 40])
def test_the_overlay_legend_fits_the_width_and_explains_every_glyph(width):
    """The singularity legend is wrapped, not cut: ``×``, ``o`` and the centre's ``+`` are
    each explained in full on lines no wider than the map."""
    extent = (0.0, 10.0, 0.0, 10.0)
    lines = render_map(
        np.array([extent]),
        np.array([2]),
        extent=extent,
        width=width,
        singular=np.array([[1.0, 2.0, 1.0, 2.0]]),
        circle=(5.0, 5.0, 2.0),
    )
    assert all(len(line) <= width for line in lines)
    legend = lines[lines.index(next(x for x in lines if "x (cm)" in x)) + 1 :]
    words = [line.strip() for line in legend]
    assert any("× may be type II singular" in w for w in words)
    assert any("o singularity-free circle (r_in)" in w for w in words)
    assert any("+ its centre" in w for w in words)
    assert sum(line.count("+") for line in lines) == 2  # the centre on the map, the legend

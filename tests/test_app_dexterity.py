"""Pilot tests of the workspace map's κ layer: a job with ``kappa_max`` offers it (``k``),
each cell's glyph the band of the worst κ upper bound of the dexterity boxes over the cell
(computed here from the boxes), ``k`` again hides it; and of a certified path's tab: the
trace at the CSV's poses, the failing stretch marked from the certificate's
``first_failure_lo_s``, the verdict in words."""

from __future__ import annotations

import csv
from dataclasses import dataclass

import numpy as np
import pytest

from planar_tui.app.app import WorkbenchApp
from planar_tui.app.widgets.robot_drawing import render_scene
from planar_tui.app.widgets.workspace_explorer import LABEL_CELLS
from planar_tui.app.workbench import Workbench
from tests.test_app import DATA, async_test, finish, run_tab
from tests.test_path3rrr import ROBOT

pytestmark = pytest.mark.slow  # end to end (see pyproject.toml's markers)

GLYPHS = "1234?"


def app_with(tmp_path, keys: str, changes: tuple[tuple[str, str], ...] = ()):
    """The app on tiny.toml with ``keys`` (TOML lines) in its workspace job and each of
    its lines ``(old, new)`` of ``changes`` replaced."""
    text = (DATA / "tiny.toml").read_text(encoding="utf-8")
    text = text.replace('form = "arc-distance"\n', 'form = "arc-distance"\n' + keys, 1)
    for old, new in changes:
        assert old in text
        text = text.replace(old, new, 1)
    path = tmp_path / "tiny.toml"
    path.write_text(text, encoding="utf-8")
    return WorkbenchApp(Workbench.open(path), output_dir=tmp_path)


def dexterous_app(tmp_path):
    """The app on tiny.toml with ``kappa_max = 4`` in its workspace job."""
    return app_with(tmp_path, "kappa_max = 4\nelbow = [1, -1, 1]\n")


def plot_cells(explorer):
    """The map's plot cells (rows top down, without the y labels and the x axis)."""
    columns, rows = explorer.plot_size()
    return [line[LABEL_CELLS : LABEL_CELLS + columns] for line in explorer.map_lines()[:rows]]


def over_cell(explorer, column, row, boxes):
    """Which of ``boxes`` overlap the interior of the map's cell ``(column, row)``."""
    x_lo, _, _, y_hi = explorer.extent()
    cell = explorer.cell_cm
    cx0, cx1 = x_lo + column * cell, x_lo + (column + 1) * cell
    cy1 = y_hi - row * 2 * cell
    cy0 = cy1 - 2 * cell
    return (boxes[:, 1] > cx0) & (boxes[:, 0] < cx1) & (boxes[:, 3] > cy0) & (boxes[:, 2] < cy1)


@dataclass
class Toggled:
    """A map layer's cells before it is shown, shown (with the legend then and the glyphs
    each cell should hold) and hidden again."""

    before: list
    legend_before: str
    shown: list
    legend: str
    expected: list
    hidden: list

    def marked(self) -> list:
        """The shown cells holding a layer glyph: ``(column, row, glyph)``."""
        return [
            (column, row, glyph)
            for row, line in enumerate(self.shown)
            for column, glyph in enumerate(line)
            if glyph in GLYPHS
        ]


async def toggle_layer(app, pilot, key, outcome, attribute, expected_glyph):
    """Run the workspace tab, check its map holds the result's ``outcome`` as its
    ``attribute`` and press ``key`` on it twice: the cells each time, and the glyph
    :func:`expected_glyph` gives each cell from the outcome's boxes."""
    await run_tab(app, pilot, "workspace")
    pane = app.query_one("#pane-workspace")
    explorer = pane.query_one("#workspace-map")
    result = getattr(pane.result, outcome)
    assert getattr(explorer, attribute) is result
    assert len(result.boxes)
    before = plot_cells(explorer)
    legend_before = str(pane.query_one("#workspace-legend").render())
    explorer.focus()
    await pilot.press(key)
    await pilot.pause()
    shown = plot_cells(explorer)
    legend = str(pane.query_one("#workspace-legend").render())
    expected = [
        [expected_glyph(explorer, column, row, result) for column in range(len(line))]
        for row, line in enumerate(shown)
    ]
    await pilot.press(key)
    await pilot.pause()
    return Toggled(before, legend_before, shown, legend, expected, plot_cells(explorer))


def expected_glyph(explorer, column, row, kappa):
    """The band of the worst ``kappa_hi`` of the boxes overlapping the cell's interior."""
    over = over_cell(explorer, column, row, kappa.boxes)
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
        layer = await toggle_layer(app, pilot, "k", "dexterity", "kappa", expected_glyph)
    assert "k: κ map" in layer.legend_before
    assert not any(g in line for line in layer.before for g in GLYPHS)
    assert "1 κ ≤ 1.75" in layer.legend and "? not proved ≤ 4" in layer.legend
    marked = layer.marked()
    assert len({g for _, _, g in marked}) >= 2  # several bands drawn
    for column, row, glyph in marked:
        assert glyph == layer.expected[row][column], (column, row)
    assert not any(g in line for line in layer.hidden for g in GLYPHS)


#: A 3-RRR path whose κ rises above 20 (tests/test_certified_path.py's "kappa" path).
FAILING_PATH = """[[path3rrr]]
from_pose = [40, 7, 0]
to_pose = [36, 5, -2]
duration_s = 1.0
steps = 40
elbow = [1, -1, -1]
joint_limits_deg = [[20, 70], [110, 160], [245, 295]]
kappa_max = 20
output = "p.csv"
"""


@async_test
async def test_a_certified_path_job_draws_its_trace_with_the_failing_stretch_marked(tmp_path):
    path = tmp_path / "path.toml"
    path.write_text(ROBOT + FAILING_PATH, encoding="utf-8")
    app = WorkbenchApp(Workbench.open(path), output_dir=tmp_path)
    async with app.run_test(size=(110, 34)) as pilot:
        app.action_show_tab("path3rrr")
        await pilot.pause()
        pane = app.query_one("#pane-path3rrr")
        await pilot.press("f5")
        await finish(app, pilot)
        assert pane.result is not None, pane.query_one("#result-text").render().plain
        files = app.export_csv(pane, tmp_path)
        view = pane.query_one("#path-robot")
        scene = view.scene
        words = str(pane.query_one("#path-certificate").render())
        drawn = "\n".join(render_scene(scene, 60, 20).lines())
    (written,) = [f for f in files if not str(f).endswith("-certificate.csv")]
    (certificate_csv,) = [f for f in files if str(f).endswith("-certificate.csv")]
    with open(certificate_csv, newline="", encoding="utf-8") as handle:
        (certificate,) = list(csv.DictReader(handle))
    with open(written, newline="", encoding="utf-8") as handle:
        rows = list(csv.DictReader(handle))
    lo = float(certificate["first_failure_lo_s"])
    assert certificate["certified"] == "no" and certificate["reason"] == "kappa"
    trace = [(p, g) for p, g, _ in scene.joints if g in ("·", "x")]
    assert len(trace) == len(rows) == 41
    for (point, glyph), row in zip(trace, rows, strict=True):
        assert point == pytest.approx((float(row["x_cm"]) / 100, float(row["y_cm"]) / 100))
        assert glyph == ("x" if float(row["t_s"]) >= lo else "·")
    assert "·" in drawn and "x" in drawn
    assert words.startswith("Not certified") and "κ rises above kappa_max" in words
    assert f"{lo:.6g}" in words


#: tiny.toml's workspace job over φ ∈ [-4, 6]° (tests/test_dexterity_orientation.py's).
RANGED = (
    ("orientation_deg = 0\n", 'orientation_deg = [-4, 6]\norientation_mode = "total"\n'),
    (
        "joint_limits_deg = [[20, 70], [110, 160], [245, 295]]\n",
        "joint_limits_deg = [[-180, 180], [-180, 180], [-180, 180]]\n",
    ),
    ("precision_cm = 0.9375\n", "precision_cm = 1.0\n"),
)


@async_test
async def test_a_ranged_jobs_kappa_layer_is_drawn_from_its_boxes(tmp_path):
    """``orientation_deg = [lo, hi]`` with ``kappa_max`` (κ the worst over the range):
    the map offers the κ layer of the ranged result and draws each cell's band from its
    boxes, bands up to ``?`` where a box over the cell is not proved ≤ kappa_max."""
    app = app_with(tmp_path, "kappa_max = 6\nelbow = [1, -1, 1]\n", RANGED)
    async with app.run_test(size=(120, 40)) as pilot:
        layer = await toggle_layer(app, pilot, "k", "dexterity", "kappa", expected_glyph)
        spec = app.query_one("#pane-workspace").job.spec
    assert spec.orientation_deg == (-4.0, 6.0) and spec.kappa_max == 6
    assert "k: κ map" in layer.legend_before and "? not proved ≤ 6" in layer.legend
    marked = layer.marked()
    glyphs = {g for _, _, g in marked}
    assert "?" in glyphs and len(glyphs) >= 2
    for column, row, glyph in marked:
        assert glyph == layer.expected[row][column], (column, row)
    drawn = sum(g != " " for row in layer.expected for g in row)
    assert len(marked) == drawn  # every cell over a box holds its band
    assert not any(g in line for line in layer.hidden for g in GLYPHS)

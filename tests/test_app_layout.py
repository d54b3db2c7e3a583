"""Layout of the workbench's results at 80 columns, without running the app or a job.

* The sensitivity tables (``fit_tables``) fit the pane for 1R…6R robots (up to 12
  parameters, Sobol' and eFAST together) in every view, print every number in full (no
  "…"), and mark the dominant parameter of each torque in bold (survives NO_COLOR).
* The workspace map is aspect-true and fits the pane; only labelled rows carry a tick.
* The help screen lists every key binding.
"""

from __future__ import annotations

import io
import json
import re
from pathlib import Path

import numpy as np
import pytest
from rich.console import Console

from planar_tui.sensitivity.results import Analysis
from planar_tui.sensitivity.tables import VIEWS, build_grid, fit_tables, heat_style

pytestmark = pytest.mark.slow  # end to end (see pyproject.toml's markers)

DATA = Path(__file__).parent / "data" / "app"
#: Results area at 80×24: beside the 30-cell form, and with the form hidden (ctrl+f).
WIDTH_WITH_FORM, WIDTH_WITHOUT_FORM = 48, 78


def load_6r() -> list[Analysis]:
    """A real 6R run of the app's default job (see the file's comment)."""
    data = json.loads((DATA / "sensitivity-6r.json").read_text())
    return [
        Analysis(
            a["method"],
            a["posture"],
            a["speed_rad_s"],
            tuple(a["names"]),
            np.array(a["indices"]),
            np.array(a["percent"]),
        )
        for a in data["analyses"]
    ]


def synthetic(n_links: int, methods=("sobol", "efast"), speeds=(1.0,), seed=3) -> list[Analysis]:
    """Random index tables (each torque's ST sums to 1) with one 100 % cell, the widest."""
    rng = np.random.default_rng(seed)
    names = tuple([f"l{i + 1}" for i in range(n_links)] + [f"m{i + 1}" for i in range(n_links)])
    analyses = []
    for speed in speeds:
        for method in methods:
            st = rng.dirichlet(np.full(2 * n_links, 0.5), size=n_links)
            st[0] = 0.0
            st[0, -1] = 1.0
            indices = np.stack([0.9 * st - 0.01, 0.05 * st, st, 0.06 * st])
            analyses.append(Analysis(method, "singular", speed, names, indices, 100 * st))
    return analyses


def render(fitted, width: int) -> str:
    console = Console(width=max(width, fitted.width), file=io.StringIO(), color_system=None)
    console.print(fitted.renderable)
    return console.file.getvalue()


def numbers(text: str) -> list[str]:
    return re.findall(r"-?\d+\.\d+", text)


@pytest.mark.parametrize("n_links", [1, 2, 3, 4, 6])
@pytest.mark.parametrize("width", [WIDTH_WITH_FORM, WIDTH_WITHOUT_FORM])
@pytest.mark.parametrize("view", VIEWS, ids=lambda v: v.key)
def test_tables_fit_80_columns_and_print_every_number(n_links, width, view):
    analyses = synthetic(n_links)
    fitted = fit_tables(analyses, view, width)
    assert fitted.width <= width
    text = render(fitted, width)
    assert "…" not in text
    assert max(len(line.rstrip()) for line in text.splitlines()) <= width
    shown = numbers(text)
    for analysis in analyses:  # every value, rounded as the view says, is on screen
        values = analysis.percent if view.row is None else analysis.indices[view.row]
        for value in values.ravel():
            assert f"{value:.{view.decimals}f}" in shown


def test_6r_is_table_4_without_the_form_and_transposed_beside_it():
    analyses = load_6r()
    wide = fit_tables(analyses, VIEWS[0], WIDTH_WITHOUT_FORM)
    narrow = fit_tables(analyses, VIEWS[0], WIDTH_WITH_FORM)
    assert not wide.transposed and not wide.short  # paper A's Table 4, methods spelt out
    assert narrow.transposed
    header = next(line for line in render(wide, 78).splitlines() if "l1" in line)
    assert header.split() == ["τ"] + [f"{p}{i}" for p in "lm" for i in range(1, 7)]
    rows = [line for line in render(wide, 78).splitlines() if line.startswith("τ1 ")]
    assert rows and rows[0].split()[:3] == ["τ1", "Sobol'", "34.9"]  # l1 dominates τ1


def test_the_dominant_parameter_of_each_torque_is_bold():
    analyses = load_6r()
    for transposed in (False, True):
        grid = build_grid(analyses, VIEWS[0], transposed, short=False)
        bold = [
            (r, c)
            for r, row in enumerate(grid.rows)
            for c, cell in enumerate(row)
            if "bold" in str(cell.style)
        ]
        assert len(bold) == 6 * len(analyses)  # one per torque and method
        for a_index, analysis in enumerate(analyses):
            for torque in range(6):
                j = int(np.argmax(analysis.percent[torque]))
                row, column = (
                    (torque * 2 + a_index, 2 + j)
                    if not transposed
                    else (j * 2 + a_index, 2 + torque)
                )
                assert (row, column) in bold
    confidence = build_grid(analyses, VIEWS[3], False, short=False)
    assert not any("bold" in str(cell.style) for row in confidence.rows for cell in row)


def test_when_nothing_fits_the_narrowest_layout_keeps_its_numbers_whole():
    analyses = synthetic(6, speeds=(0.5, 1.0))
    fitted = fit_tables(analyses, VIEWS[3], 30)
    assert fitted.transposed and fitted.short and fitted.width > 30
    text = render(fitted, 30)
    assert "…" not in text
    assert text.count("rad/s") == 2  # one table per speed
    assert len(re.findall(r"\b\d\.\d{3}\b", text)) == 2 * 2 * 6 * 12  # speed × method × τ × p


def test_heat_levels():
    assert heat_style(0.6) == "black on red"
    assert heat_style(0.3) == "black on yellow"
    assert heat_style(0.1) == "black on green"
    assert heat_style(0.01) == ""


def square_boxes(side_cm: float = 10.0, count: int = 40) -> tuple[np.ndarray, np.ndarray]:
    """A square of inside boxes, ``count`` × ``count``, from (0, 0) to (side, side)."""
    edges = np.linspace(0.0, side_cm, count + 1)
    x0, y0 = np.meshgrid(edges[:-1], edges[:-1])
    step = side_cm / count
    boxes = np.column_stack([x0.ravel(), x0.ravel() + step, y0.ravel(), y0.ravel() + step])
    return boxes, np.full(len(boxes), 2)


@pytest.mark.parametrize(("width", "height"), [(48, 16), (78, 16), (110, 32)])
def test_workspace_map_is_aspect_true_and_fits(width, height):
    from planar_tui.app.widgets.workspace_pane import fitted_map

    lines = fitted_map(*square_boxes(), width, height)
    assert len(lines) <= height and max(map(len, lines)) <= width
    assert not lines[-1].lstrip().startswith("x (cm)")  # the legend is shown apart, wrapped
    full = [line for line in lines if "█" in line]
    columns = max(line.count("█") for line in full)
    # a square: twice as many columns as rows (a cell is twice as tall as wide), ±1 cell
    assert abs(columns - 2 * len(full)) <= 3
    plot = [line for line in lines if "┤" in line or "│" in line]
    for line in plot:  # a tick only where there is a label
        head = line[: max(line.find("┤"), line.find("│"))]
        assert ("┤" in line) == bool(head.strip())
    assert sum("┤" in line for line in plot) >= 2


def test_help_lists_every_binding():
    from planar_tui.app.app import WorkbenchApp
    from planar_tui.app.screens.dialogs import help_text

    text = help_text(WorkbenchApp.binding_sources())  # generated from the bindings
    names = {"question_mark": "?", "f1": "F1", "f5": "F5"}
    keys = {"ctrl+p", "ctrl+q", "enter", "y", "n", "tab", "shift+tab"}  # Textual's, dialogs
    for binding in WorkbenchApp.BINDINGS:
        keys.update(binding.key.split(","))
    for key in keys:
        shown = names.get(key, key.upper() if re.fullmatch(r"f\d+", key) else key)
        assert re.search(rf"(^|[\s,(]){re.escape(shown)}[\s,)]", text), key


def test_the_app_uses_public_textual_hooks_and_panes_post_messages():
    """No private Textual API where a public hook serves; panes never call the app."""
    app_folder = Path(__file__).resolve().parent.parent / "planar_tui" / "app"
    for path in app_folder.rglob("*.py"):
        source = path.read_text(encoding="utf-8")
        for private in ("_compositor", "_background_screens", "_on_key", "planar_tui.cli"):
            assert private not in source, f"{path.name} uses {private}"
    for path in (app_folder / "widgets").glob("*.py"):
        assert "self.app" not in path.read_text(encoding="utf-8"), path.name

"""Pilot tests of the explorable workspace map: the read-out at a known inside and a known
outside point (the leg angles checked by forward kinematics here), the cursor, zoom, pan,
the overlays, re-paving the view and the live preview after an edit (a newer edit
replaces an older preview)."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from planar_tui.app.widgets.workspace_explorer import cell_status, wrapped_legend
from tests.test_app import SIZE, async_test, make_app, run_tab, until

pytestmark = pytest.mark.slow  # end to end (see pyproject.toml's markers)

#: tiny.toml's 3-RRR (paper B Table 2) and joint limits (deg).
A = ((0.0, 0.0), (120.0, 0.0), (60.0, 60.0 * math.sqrt(3.0)))
Q = ((0.0, 0.0), (40.0, 0.0), (20.0, 40.0))
L1 = L2 = 30.0
LIMITS_DEG = ((20, 70), (110, 160), (245, 295))


def test_cell_status_prefers_singular_then_inside():
    boxes = np.array([[0.0, 1.0, 0.0, 1.0], [1.0, 2.0, 0.0, 1.0]])
    status = np.array([2, 1])
    assert cell_status((0.5, 0.5), boxes, status) == "inside"
    assert cell_status((1.5, 0.5), boxes, status) == "boundary"
    assert cell_status((1.0, 0.5), boxes, status) == "inside"  # on the shared edge
    assert cell_status((3.0, 0.5), boxes, status) == "outside"
    assert cell_status((1.5, 0.5), boxes, status, np.array([[1.2, 1.8, 0.2, 0.8]])) == "singular"


def test_the_legend_fits_80_columns():
    from planar_tui.app.widgets.workspace_explorer import EXACT_ITEM, LEGEND_ITEMS, MODE_ITEM
    from planar_tui.workspace.paving.map import SINGULAR_LEGEND_ITEMS

    items = [*LEGEND_ITEMS, EXACT_ITEM, MODE_ITEM, *SINGULAR_LEGEND_ITEMS]
    assert all(len(line) <= 80 for line in wrapped_legend(items, 80).splitlines())
    assert all(len(line) <= 46 for line in wrapped_legend(items, 46).splitlines())


def margin(x: float, y: float) -> float:
    """The smallest distance (deg) of a leg's best active angle to its limits at the
    platform position (x, y) (< 0: some leg cannot close within its limits)."""
    if True:
        worst = math.inf
        for (ax, ay), (qx, qy), (lo, hi) in zip(A, Q, LIMITS_DEG, strict=True):
            cx, cy = x + qx - ax, y + qy - ay  # C_i - A_i
            rho = math.hypot(cx, cy)
            if rho == 0:
                return -math.inf
            cosine = (rho * rho + L1 * L1 - L2 * L2) / (2 * L1 * rho)
            if abs(cosine) >= 1:
                return -math.inf
            alpha, beta = math.atan2(cy, cx), math.acos(cosine)
            best = -math.inf
            for theta in (alpha + beta, alpha - beta):
                angle = math.degrees(theta) % 360
                best = max(best, min(angle - lo, hi - angle))
            worst = min(worst, best)
        return worst


def angles_in(readout: str) -> list[float]:
    match = re.search(r"θ = ([-\d.]+)°, ([-\d.]+)°, ([-\d.]+)°", readout)
    assert match, readout
    return [float(v) for v in match.groups()]


@async_test
async def test_read_out_at_an_inside_and_an_outside_point(tmp_path):
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        await run_tab(app, pilot, "workspace")
        pane = app.query_one("#pane-workspace")
        explorer = pane.query_one("#workspace-map")
        explorer.focus()
        outcome = pane.result.outcome
        row = outcome.boxes[np.flatnonzero(outcome.status == 2)[0]]
        point = (0.5 * (row[0] + row[1]), 0.5 * (row[2] + row[3]))  # a proved box's centre
        assert margin(*point) > 0  # inside the workspace, by the legs' closure here
        explorer.cursor_cm = point
        explorer.changed()
        await pilot.pause()
        readout = str(pane.query_one("#workspace-readout").render())
        assert f"(x, y) = ({point[0]:.2f}, {point[1]:.2f}) cm  inside" in readout
        for theta_deg, (ax, ay), (qx, qy), (lo, hi) in zip(
            angles_in(readout), A, Q, LIMITS_DEG, strict=True
        ):
            assert lo <= theta_deg <= hi
            bx = ax + L1 * math.cos(math.radians(theta_deg))
            by = ay + L1 * math.sin(math.radians(theta_deg))
            # the distal link closes (the angle is read to 0.05°: 30 cm · 0.05° ≈ 0.03 cm)
            assert math.hypot(point[0] + qx - bx, point[1] + qy - by) == pytest.approx(L2, abs=0.05)
        drawing = pane.query_one("#workspace-robot").scene
        assert sum(glyph == "o" for _, glyph, _ in drawing.joints) == 3  # three legs closed
        explorer.cursor_cm = (0.0, 100.0)
        explorer.changed()
        await pilot.pause()
        readout = str(pane.query_one("#workspace-readout").render())
        assert readout == "(x, y) = (0.00, 100.00) cm  outside"
        # keys: a cell to the right, zoom in about the cursor, pan, fit
        explorer.cursor_cm = point
        explorer.changed()
        cell = explorer.cell_cm
        await pilot.press("right")
        assert explorer.cursor_cm[0] > point[0] and explorer.cursor_cm[0] - point[0] <= 1.5 * cell
        await pilot.press("plus")
        assert explorer.cell_cm == pytest.approx(cell / 2)
        before = explorer.centre_cm
        await pilot.press("shift+left")
        assert explorer.centre_cm[0] < before[0]
        await pilot.press("b", "0")
        await pilot.pause()
        assert explorer.cell_cm == pytest.approx(cell)
        assert "· exact boundary" in str(pane.query_one("#workspace-legend").render())
        assert "·" in str(explorer.render())
        # re-pave the view, finer
        boxes_before = len(explorer.boxes)
        await pilot.press("plus", "r")
        await until(pilot, lambda: "re-paved" in explorer.note, timeout_s=300)
        assert len(explorer.boxes) > boxes_before or explorer.note
        assert "@" in str(explorer.render())


async def limits_field(app, pilot):
    """The Workspace tab's pane and its joint-limits field, focused."""
    app.action_show_tab("workspace")
    await pilot.pause()
    field = app.query_one("#pane-workspace #field-joint_limits_deg")
    field.focus()
    return app.query_one("#pane-workspace"), field


@async_test
async def test_an_edit_of_the_joint_limits_redraws_a_coarse_map(tmp_path):
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        pane, field = await limits_field(app, pilot)
        field.value = "[[10, 80], [100, 170], [235, 305]]"
        await until(pilot, lambda: "preview" in pane.query_one("#workspace-map").note, 300)
        await until(pilot, lambda: "preview ε" in str(pane.query_one("#workspace-legend").render()))
        assert "█" in str(pane.query_one("#workspace-map").render())
        # the preview's boxes are those of the edited limits: wider limits, a larger map
        # than the job's (106.75 cm² at the preset's limits, paper B Table 3)
        boxes = pane.query_one("#workspace-map").boxes
        kept_cm2 = float(np.sum((boxes[:, 1] - boxes[:, 0]) * (boxes[:, 3] - boxes[:, 2])))
        assert kept_cm2 > 106.75


@async_test
async def test_a_newer_edit_replaces_an_older_preview(tmp_path):
    from planar_tui.app.widgets.workspace_pane import Paved, pave, preview_job

    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        pane, field = await limits_field(app, pilot)
        older = ((15, 75), (105, 165), (240, 300))
        newer = ((10, 80), (100, 170), (235, 305))
        field.value = str([list(pair) for pair in older])
        await until(pilot, lambda: pane._preview_key is not None and pane._preview_key[1] == older)
        older_job = pane._valid_job()
        field.value = str([list(pair) for pair in newer])  # before the older map is drawn
        explorer = pane.query_one("#workspace-map")

        def newer_shown() -> bool:
            shown = pane._shown_job
            return "preview" in explorer.note and shown.spec.joint_limits_deg == newer

        await until(pilot, newer_shown, 300)
        # the older edit's map, arriving late from its worker, is not drawn over it
        boxes = explorer.boxes.copy()
        late = pave(preview_job(older_job), lambda: False)
        pane.post_message(Paved("preview", preview_job(older_job), late))
        await pilot.pause(0.2)
        assert newer_shown() and np.array_equal(explorer.boxes, boxes)
        assert not [w for w in pane.workers if w.group == "preview" and w.is_running]


def test_the_preview_paves_the_same_boxes_on_one_thread():
    import numba

    from planar_tui.app.widgets.workspace_pane import pave, preview_job
    from planar_tui.presets import load_preset

    job = next(j for j in load_preset("tests/data/app/tiny.toml").jobs if j.kind == "workspace")
    coarse = preview_job(job, (40, 12))
    x_lo, x_hi, y_lo, y_hi = job.robot.reach_box_cm(job.spec.orientation_rad)
    cell_cm = max((x_hi - x_lo) / 40, (y_hi - y_lo) / 24)  # the reach box fills 40×12 cells
    before = numba.get_num_threads()
    every, one = pave(coarse, lambda: False), pave(coarse, lambda: False, 1)
    assert numba.get_num_threads() == before  # the caller's thread count is restored
    assert len(one.boxes) and np.array_equal(one.boxes, every.boxes)
    assert np.array_equal(one.status, every.status)
    # no box narrower than a map cell, none wider than two
    widths = one.boxes[:, 1] - one.boxes[:, 0]
    assert np.min(widths) >= cell_cm * (1 - 1e-9) and np.max(widths) <= 2 * cell_cm * (1 + 1e-9)


@async_test
async def test_a_tolerance_job_shows_the_nominal_and_some_layers_as_the_cli_map(tmp_path):
    """Issue 25: the tab draws a tolerance-certified job's robust boxes with the nominal and
    "some" workspaces as layers (their glyphs and legends), fitted to the widest layer, as
    the CLI's map does."""
    from planar_tui.workspace.paving.tolerance import MAP_LAYERS

    app = make_app(tmp_path, "workspace-tolerance.toml")
    async with app.run_test(size=(120, 40)) as pilot:
        await run_tab(app, pilot, "workspace")
        pane = app.query_one("#pane-workspace")
        explorer = pane.query_one("#workspace-map")
        await pilot.pause()
        legend = str(pane.query_one("#workspace-legend").render())
        drawn = str(explorer.render())
        some = pane.result.companions["some"].boxes
        robust = explorer.boxes
        x_lo, x_hi, y_lo, y_hi = explorer.extent()
        cli = cli_map(pane.job, pane.result)
    for _, glyph, text in MAP_LAYERS:
        assert f"{glyph} {text}" in legend
        assert glyph in drawn and glyph in cli  # ±1 mm: cells only the nominal or some reach
    assert len(robust) and np.array_equal(robust, pane.result.outcome.boxes)
    assert x_lo <= some[:, 0].min() and some[:, 1].max() <= x_hi  # fitted to the widest layer
    assert y_lo <= some[:, 2].min() and some[:, 3].max() <= y_hi


def cli_map(job, result) -> str:
    """The CLI's map of the same job and result (its kind's terminal view, what
    ``planar-tui workspace`` prints)."""
    import io

    from rich.console import Console

    from planar_tui.registry import JOB_KINDS

    out = io.StringIO()
    JOB_KINDS["workspace"].render(job, result, Console(file=out, width=120))
    return out.getvalue()

"""The Motion tab: a run shows the summary, the band plot (ctrl+t steps through the
outputs) and the indices table; the CLI writes the same band from the saved preset."""

from __future__ import annotations

import csv

import numpy as np
import pytest

from tests.test_app import SIZE, async_test, make_app, run_tab

pytestmark = pytest.mark.slow  # end to end (see pyproject.toml's markers)


@async_test
async def test_motion_run_plots_the_band_and_shows_the_tables(tmp_path, cli):
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        await run_tab(app, pilot, "motion_uncertainty")
        await pilot.press("ctrl+f")  # hide the form: the results take the width
        await pilot.pause(0.2)
        pane = app.query_one("#pane-motion_uncertainty")
        result = pane.result
        assert result is not None and result.robots == 128 + 128 * 6
        assert [a.context for a in result.analyses] == ["t = 0.5 s"]
        screen = app.export_text()
        assert "robots × 500 steps on cpu" in " ".join(screen.split())
        assert "θ1 (rad) vs t (s)" in screen and "oo mean" in screen  # title and legend
        results = pane.query_one("#motion-results")
        results.scroll_to(y=16, animate=False)  # below the plot: the band table
        await pilot.pause(0.2)
        row = next(line for line in app.export_text().splitlines() if " tip x " in line)
        assert f"{result.band[-1, 0, 2]:.5g}" in row  # the mean, never cut to "…"
        assert f"{result.band[-1, 4, 2]:.5g}" in row  # the 95th percentile, last column
        results.scroll_end(animate=False)
        await pilot.pause(0.2)
        tables = app.export_text()
        assert "% of ST per output · t = 0.5 s" in tables and "tip y" in tables
        # the band table equals the band CSV's last row
        last = dict(zip(result.table.header, list(result.table.records())[-1], strict=True))
        assert float(last["tip_x_m_mean"]) == float(f"{result.band[-1, 0, 2]:.17g}")
        results.scroll_home(animate=False)
        # the band's arms at the scrubbed time: the last row, then the first after home
        arms = pane.query_one("#band-arms")
        assert arms.row == len(result.t_s) - 1
        arms.focus()
        await pilot.press("home")
        await pilot.pause(0.2)
        assert arms.row == 0 and "t = 0 s" in str(pane.query_one("#band-readout").render())
        await pilot.press("right")
        median = [float(v) for v in result.band[arms.row, 3, :2]]  # θ1, θ2 medians (rad)
        tip = (
            0.303 * np.cos(median[0]) + 0.214 * np.cos(median[0] + median[1]),
            0.303 * np.sin(median[0]) + 0.214 * np.sin(median[0] + median[1]),
        )
        assert arms.scene.joints[-1][0] == pytest.approx(tip, abs=1e-12)
        await pilot.press("ctrl+t")
        await pilot.pause(0.2)
        assert "θ2 (rad) vs t (s)" in app.export_text()
        await pilot.press("ctrl+s")  # the preset's own file, now with the motion table
        await pilot.pause(0.2)
    saved = tmp_path / "tiny.toml"
    assert "[motion_uncertainty]" in saved.read_text()
    done = cli("motion", saved, "--out", tmp_path / "cli.csv", "--out-dir", tmp_path)
    assert done.exit_code == 0, done.stderr
    with open(tmp_path / "cli.csv", newline="") as stream:
        header, *records = list(csv.reader(stream))
    assert tuple(header) == result.table.header
    band = np.array(records, dtype=float)  # (R, 1 + 5 per output)
    assert np.array_equal(band[:, 0], result.t_s)
    assert np.array_equal(band[:, 1:].reshape(len(band), -1, 5), result.band.transpose(0, 2, 1))
    # and the on-screen band row holds the CLI's last-row tip x statistics
    cells = row.split()[2:]  # "tip x" and then the mean, std, p5, p50, p95
    assert cells == [f"{value:.5g}" for value in band[-1, 11:16]]


def test_the_docs_name_the_tab_keys_the_app_binds():
    """docs/app.md's tab keys and docs/motion.md's Motion-tab key are the app's bindings: the
    function keys anywhere, the digits on the tab bar only (F8 is the sweep, not a tab)."""
    from planar_tui.app.app import WorkbenchApp
    from tests.conftest import REPO

    function_keys, digits = {}, {}  # tab number -> its key
    for binding in WorkbenchApp.BINDINGS:
        if binding.action.startswith("show_tab_number("):
            function_keys[int(binding.action[16:-1])] = binding.key.upper()
        elif binding.action.startswith("digit_tab("):
            digits[int(binding.action[10:-1])] = binding.key
    listed = " ".join(f"`{function_keys[k]}`" for k in sorted(function_keys))
    app = " ".join((REPO / "docs" / "app.md").read_text(encoding="utf-8").split())
    assert f"keys {listed} anywhere for the first six" in app
    assert f"`{digits[1]}`…`{digits[6]}` on the tab bar, never in a form" in app
    motion = " ".join((REPO / "docs" / "motion.md").read_text(encoding="utf-8").split())
    assert f"(Motion tab, key `{digits[6]}` / `{function_keys[6]}`)" in motion


@async_test
async def test_a_wide_results_area_puts_the_tables_beside_the_plot(tmp_path):
    """From 150 columns of results the band and index tables stand beside the plot (the
    issue's "band plot beside the table"); narrower, below it."""
    app = make_app(tmp_path)
    async with app.run_test(size=(170, 40)) as pilot:
        await run_tab(app, pilot, "motion_uncertainty")
        pane = app.query_one("#pane-motion_uncertainty")
        plot, tables = pane.query_one("#band-plot"), pane.query_one("#motion-tables")
        # with the form: about 137 columns of results, the tables below the plot
        assert pane.query_one("#motion-results").scrollable_content_region.width < 150
        assert not pane.query_one("#motion-body").has_class("beside")
        assert plot.region.bottom <= tables.region.y
        await pilot.press("ctrl+f")  # without the form: the whole width
        await pilot.pause(0.3)
        assert pane.query_one("#motion-results").scrollable_content_region.width >= 150
        assert pane.query_one("#motion-body").has_class("beside")
        assert plot.region.y == tables.region.y and plot.region.right < tables.region.x
        assert plot.region.width >= 60
        result = pane.result
        screen = app.export_text()
        row = next(line for line in screen.splitlines() if " tip x " in line and "±" not in line)
        assert row.rstrip().endswith(f"{result.band[-1, 4, 2]:.5g}")  # whole, at the right
        assert "θ1 (rad) vs t (s)" in screen

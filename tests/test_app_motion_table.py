"""The Motion tab's band table at 80×24 with the form shown: every output's column and
every statistic visible (turned and wrapped when the plain table is wider than the pane).
A stub result stands for the study (only the table's rendering is tested here; the study
itself end to end: tests/test_app_motion.py)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from tests.test_app import SIZE, async_test, make_app

NAMES = ("theta1_rad", "theta2_rad", "tip_x_m", "tip_y_m")


def stub_result():
    """Two recorded times; at the last, output k's statistics ``(k+1)·[1.1, 0.0012, ...]``
    with 5 significant digits that need the full width of the plain table."""
    band = np.zeros((2, 5, len(NAMES)))
    base = np.array([-1.7975, 0.0029778, -1.802, -1.7976, -1.7925])
    for k in range(len(NAMES)):
        band[:, :, k] = base * (k + 1) / 3.0
    return SimpleNamespace(
        t_s=np.array([0.0, 0.5]),
        band=band,
        names=NAMES,
        summary="stub study",
        analyses=[],
        notes=[],
    )


@async_test
async def test_the_band_table_shows_every_output_and_statistic_at_80x24(tmp_path):
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        app.action_show_tab("motion_uncertainty")
        await pilot.pause()
        pane = app.query_one("#pane-motion_uncertainty")
        assert pane.query_one("#job-form").display  # the form shown: a narrow pane
        result = stub_result()
        pane.show_result(pane.current_job(), result)
        await pilot.pause(0.2)
        results = pane.query_one("#motion-results")
        seen = []
        for y in range(0, 60, 4):  # the whole scrolled area, no sideways scroll
            results.scroll_to(x=0, y=y, animate=False)
            await pilot.pause(0.05)
            seen += [line.split("▕", 1)[-1] for line in app.export_text().splitlines()]
        text = "\n".join(seen)
        assert "band at t = 0.5 s" in text
        for label in ("θ1", "θ2", "tip x", "tip y"):
            assert label in text, label
        for k in range(len(NAMES)):  # every statistic of every output, as printed (.5g)
            for value in result.band[-1, :, k]:
                assert f"{value:.5g}" in text, (k, value)
        assert results.max_scroll_x == 0

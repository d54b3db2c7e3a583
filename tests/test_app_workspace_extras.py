"""The Workspace tab with an orientation range and with the singularities (issue 12)."""

from __future__ import annotations

import pytest

from tests.test_app import SIZE, async_test, make_app, run_tab

pytestmark = pytest.mark.slow  # end to end (see pyproject.toml's markers)


async def _type(app, pilot, key: str, text: str) -> None:
    field = app.query_one(f"#pane-workspace #field-{key}")
    field.focus()
    field.value = text
    await pilot.pause()


@async_test
async def test_orientation_range_and_singularities_from_the_form(tmp_path):
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        app.action_show_tab("workspace")
        await pilot.pause()
        await _type(app, pilot, "geometric_reference", "false")
        await _type(app, pilot, "orientation_deg", "[-5, 5]")
        assert "orientation_mode: missing key" in str(app.query_one("#validation").render())
        await _type(app, pilot, "orientation_mode", "maximal")
        assert app.workbench.document["workspace"]["orientation_deg"] == [-5, 5]
        await run_tab(app, pilot, "workspace")
        result = app.query_one("#pane-workspace").result
        assert result.table.rows[0][result.table.header.index("orientation_mode")] == "maximal"
        outcome = result.outcome
        # the maximal workspace over [-5, 5]° holds the φ = 0 one (106.75 cm², paper B)
        assert outcome.area_kept_cm2 > 106.75
        assert "█" in app.export_text()

        await _type(app, pilot, "orientation_deg", "0")
        await _type(app, pilot, "orientation_mode", "")
        await _type(app, pilot, "singularities", "true")
        await _type(app, pilot, "elbow", "[1, -1, 1]")
        await run_tab(app, pilot, "workspace")
        result = app.query_one("#pane-workspace").result
        assert result.singularity is not None
        screen = app.export_text()
        assert "o" in screen and "+" in screen and "singularity-free" in screen
        # the circle's working mode (shown with it): its centre is reachable in it
        explorer = app.query_one("#workspace-map")
        assert explorer.show_mode and explorer.in_mode(result.singularity.centre_cm)
        assert "░ not in the circle's working mode" in str(
            app.query_one("#workspace-legend").render()
        )

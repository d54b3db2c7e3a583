"""The app's optimisations: the palette's Run optimisation on the workspace tab opens the
optimise screen with the first generation, follows it to the end (the same evaluations as
the CLI's run of the table) and exports both CSVs; ``x`` cancels, keeping what finished."""

from __future__ import annotations

import csv

import pytest
from textual.widgets import DataTable

from planar_tui.app.app import WorkbenchApp
from planar_tui.app.screens.optimise import OptimiseScreen
from planar_tui.app.workbench import Workbench
from planar_tui.optimise.run import run_optimisation
from planar_tui.optimise.spec import parse_optimisations
from planar_tui.presets import load_preset
from tests.test_app import DATA, SIZE, async_test, finish

OPTIMISE = """
[[optimise]]
job = "workspace"
variables.orientation_deg = { from = -45, to = 45 }
maximise = "area_inside_cm2"
budget = BUDGET
population = 8
output = "opt.csv"
"""


def app_on(tmp_path, budget: int) -> WorkbenchApp:
    path = tmp_path / "tiny-opt.toml"
    text = (DATA / "tiny.toml").read_text(encoding="utf-8")
    path.write_text(text + OPTIMISE.replace("BUDGET", str(budget)), encoding="utf-8")
    return WorkbenchApp(Workbench.open(path), output_dir=tmp_path)


async def start(app: WorkbenchApp, pilot) -> None:
    """Run the optimisation of the workspace tab (the palette's Run optimisation)."""
    app.action_show_tab("workspace")
    await pilot.pause()
    app.action_optimise()


@pytest.mark.slow
@async_test
async def test_the_optimise_screen_follows_the_run_and_exports_the_cli_result(tmp_path):
    app = app_on(tmp_path, 24)
    async with app.run_test(size=SIZE) as pilot:
        await start(app, pilot)
        await finish(app, pilot)
        assert isinstance(app.screen, OptimiseScreen)
        run = app.screen.run
        assert len(run.evaluations) == 24 and run.generations == 3 and run.certified
        assert (
            app.screen.query_one("#sweep-title")
            .render()
            .plain.startswith(
                "tiny-opt:optimise[1] (done): generation 3, 24/24 evaluations; best area_inside_cm2"
            )
        )
        assert app.screen.query_one(DataTable).row_count == 24
        app.screen.export(run)
        await pilot.pause()
        await pilot.press("enter")
        await pilot.pause()
    (optimisation,) = parse_optimisations(load_preset(tmp_path / "tiny-opt.toml"))
    alone = run_optimisation(optimisation)
    with open(tmp_path / "opt.csv", newline="") as stream:
        rows = list(csv.reader(stream))
    assert rows[0] == list(alone.table.header)
    assert rows[1:] == [[str(cell) for cell in row] for row in alone.table.rows]
    assert (tmp_path / "opt-optimum.csv").exists()


@pytest.mark.slow
@async_test
async def test_cancel_keeps_the_finished_evaluations(tmp_path):
    app = app_on(tmp_path, 4000)
    async with app.run_test(size=SIZE) as pilot:
        await start(app, pilot)
        while not isinstance(app.screen, OptimiseScreen):
            await pilot.pause(0.05)
        await pilot.press("x")
        await finish(app, pilot)
        run = app.screen.run
        assert run.cancelled and 8 <= len(run.evaluations) < 4000
        assert "(cancelled)" in app.screen.query_one("#sweep-title").render().plain

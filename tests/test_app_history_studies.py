"""Sweeps and optimisations in the run history: their CSVs (written by ``planar-tui sweep``
and ``planar-tui optimise``) carry provenance sidecars and open into the history (as
``planar-tui tui --open`` opens them) with their settings; an optimisation's CSV without
its sidecar is still recognised by its header; a sweep run in the app is kept, and two
sweeps compare point by point."""

from __future__ import annotations

import csv
import shutil
from pathlib import Path

import pytest

from planar_tui.app.compare import compare_runs
from planar_tui.app.runs import NO_SIDECAR, RunHistory
from planar_tui.provenance import sidecar_path
from tests.test_app_history import DATA, async_test, compare_latest, make_app, squeezed, until

STUDIES = """
[[sweep]]
job = "simulate"
values.duration_s = [0.1, 0.2]
output = "durations.csv"

[[optimise]]
job = "workspace"
variables.orientation_deg = { from = -45, to = 45 }
maximise = "area_inside_cm2"
budget = 8
population = 4
output = "opt.csv"
"""


def rows_of(path: Path) -> list[list[str]]:
    with path.open(encoding="utf-8", newline="") as stream:
        return list(csv.reader(stream))


@pytest.fixture
def studies(tmp_path, cli) -> Path:
    """tiny.toml with a sweep of its simulation and an optimisation of its workspace,
    both run by the CLI into ``tmp_path/out``."""
    preset = tmp_path / "studies.toml"
    preset.write_text((DATA / "tiny.toml").read_text("utf-8") + STUDIES, "utf-8")
    out = tmp_path / "out"
    for command in ("sweep", "optimise"):
        result = cli(command, preset, "--workers", 1, "--out-dir", out)
        assert result.exit_code == 0, result.output
    return out


@pytest.mark.slow
def test_sweep_and_optimisation_csvs_open_into_the_history_with_their_settings(studies):
    files = [studies / name for name in ("durations.csv", "opt.csv", "opt-optimum.csv")]
    assert all(sidecar_path(path).is_file() for path in files)  # each CSV has its sidecar
    history = RunHistory()
    sweep, evaluations, optimum = (history.add_csv(path) for path in files)
    assert (sweep.kind, evaluations.kind, optimum.kind) == ("sweep", "optimise", "optimise")
    assert not sweep.note and not evaluations.note and not optimum.note
    assert sweep.settings["job_kind"] == "simulate"
    assert sweep.settings["values"] == {"duration_s": [0.1, 0.2]}  # the table as written
    assert sweep.settings["job_settings"]["torques_Nm"] == [0.5, 0.1]  # the base job's
    assert evaluations.settings["job_kind"] == "workspace"
    assert evaluations.settings["budget"] == 8 and evaluations.provenance.form == "arc-distance"
    assert evaluations.provenance.precision_cm == 0.9375  # the base job's ε, in the row
    assert len(evaluations.table.rows) == len(rows_of(files[1])) - 1 == 8
    assert "budget = 8" in evaluations.describe()
    # without its sidecar, an optimisation's CSV is recognised by its header, and said
    bare = studies / "bare-opt.csv"
    shutil.copy(files[1], bare)
    run = RunHistory().add_csv(bare)
    assert run.kind == "optimise" and run.note == NO_SIDECAR
    # two sweeps compare point by point: the same CSV against itself differs nowhere
    again = history.add_csv(files[0])
    comparison = compare_runs(sweep, again)
    header = rows_of(files[0])[0]
    assert comparison.header[0] == "point" and comparison.header[1:4] == (
        f"{header[1]} A",
        f"{header[1]} B",
        f"{header[1]} B−A",
    )
    assert [row[0] for row in comparison.rows] == ["1", "2"]
    assert [row[1:4] for row in comparison.rows] == [("0.1", "0.1", "+0"), ("0.2", "0.2", "+0")]


@pytest.mark.slow
@async_test
async def test_tui_open_lists_sweeps_and_optimisations_in_the_history(tmp_path, studies):
    from textual.widgets import DataTable

    app = make_app(tmp_path)
    app.open_results([studies / "durations.csv", studies / "opt.csv"])
    async with app.run_test(size=(120, 40)) as pilot:
        await until(pilot, lambda: "Run history: 2 runs" in app.export_text())
        table = app.screen.query_one(DataTable)
        rows = [[str(cell) for cell in table.get_row_at(k)] for k in range(2)]
        assert [row[2:4] for row in rows] == [
            ["sweep", "studies:sweep[1]"],
            ["optimise", "studies:optimise[1]"],
        ]
        assert rows[1][7:9] == ["arc-distance", "0.9375"]  # form and ε of its base job
        text = squeezed(app.export_text())
        assert squeezed("job_kind = 'workspace'") in text  # the highlighted (latest) run
        assert squeezed("maximise = 'area_inside_cm2'") in text


@pytest.mark.slow
@async_test
async def test_a_sweep_run_in_the_app_is_kept_in_the_history_and_compared(tmp_path):
    from textual.widgets import Input

    from planar_tui.app.screens.sweep import SweepDialog, SweepScreen

    app = make_app(tmp_path)
    async with app.run_test(size=(80, 24)) as pilot:
        app.action_show_tab("simulate")
        await pilot.pause()
        for values in ("0.1, 0.2", "0.1, 0.15"):
            await pilot.press("f8")
            await until(pilot, lambda: isinstance(app.screen, SweepDialog))
            app.screen.query_one("#sweep-key-1", Input).value = "duration_s"
            app.screen.query_one("#sweep-values-1", Input).value = values
            await pilot.press("enter")
            await until(pilot, lambda: isinstance(app.screen, SweepScreen), 600)
            await app.workers.wait_for_complete()
            await pilot.pause(0.1)
            await pilot.press("escape")
            await until(pilot, lambda: not isinstance(app.screen, SweepScreen))
        runs = list(app.run_history)
        assert [run.kind for run in runs] == ["sweep", "sweep"]
        assert runs[0].settings["job_kind"] == "simulate" and runs[0].summary == "2 points"
        assert runs[0].provenance.duration_s > 0
        comparison = await compare_latest(app, pilot)
        column = comparison.header.index("duration_s B−A")
        assert [row[column] for row in comparison.rows] == ["+0", "-0.05"]
        theta = comparison.header.index("theta1_end_rad A")
        a_rows, b_rows = (run.table for run in runs)
        end = a_rows.header.index("theta1_end_rad")
        assert comparison.rows[0][theta : theta + 3][2] == "+0"  # the same point
        assert comparison.rows[1][theta] == f"{a_rows.rows[1][end]:.6g}"
        assert comparison.rows[1][theta + 1] == f"{b_rows.rows[1][end]:.6g}"

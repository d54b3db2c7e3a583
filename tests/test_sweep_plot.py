"""A sweep's figure: the ``plot`` key of a ``[[sweep]]`` table and ``planar-tui sweep
--plot FILE`` draw the sweep CSV's figure (a line against one varied key) beside the CSV;
a bad suffix is refused before anything runs; a sweep the figure cannot show is one line."""

from __future__ import annotations

import csv
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from tests.sweep_presets import TORQUES, TORQUES_BASE, write
from tests.test_app import async_test

SWEEP = """[[sweep]]
job = "torques"
values."robot.masses_kg[2]" = [1.0, 1.5, 2.0]
output = "masses.csv"
"""


def _is_svg(path) -> bool:
    return ET.parse(path).getroot().tag.endswith("svg")


def test_plot_key_draws_the_sweep_figure_beside_its_csv(tmp_path, cli):
    preset = write(tmp_path, "p.toml", TORQUES, SWEEP + 'plot = "masses.svg"\n', **TORQUES_BASE)
    result = cli("sweep", preset, "--workers", "1", "--out-dir", tmp_path / "out")
    assert result.exit_code == 0, result.output
    assert _is_svg(tmp_path / "out" / "masses.svg")
    assert "figure " in result.stdout and "masses.svg" in result.stdout
    rows = list(csv.DictReader((tmp_path / "out" / "masses.csv").read_text().splitlines()))
    assert [row["robot.masses_kg[2]"] for row in rows] == ["1.0", "1.5", "2.0"]


def test_plot_option_overrides_the_key_and_checks_the_suffix(tmp_path, cli):
    preset = write(tmp_path, "p.toml", TORQUES, SWEEP + 'plot = "masses.svg"\n', **TORQUES_BASE)
    out = tmp_path / "out"
    bad = cli("sweep", preset, "--workers", "1", "--out-dir", out, "--plot", "fig.gif")
    assert bad.exit_code == 2 and not out.exists()
    assert "fig.gif" in bad.output and ".svg" in bad.output and "Traceback" not in bad.output
    good = cli("sweep", preset, "--workers", "1", "--out-dir", out, "--plot", out / "f.png")
    assert good.exit_code == 0, good.output
    assert (out / "f.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert not (out / "masses.svg").exists()


def test_plot_option_is_taken_from_the_current_folder_not_the_out_dir(tmp_path, cli, monkeypatch):
    preset = write(tmp_path, "p.toml", TORQUES, SWEEP, **TORQUES_BASE)
    monkeypatch.chdir(tmp_path)
    result = cli("sweep", preset, "--workers", "1", "--out-dir", "out", "--plot", "out/f.svg")
    assert result.exit_code == 0, result.output
    assert _is_svg(tmp_path / "out" / "f.svg")
    assert not (tmp_path / "out" / "out").exists()


def test_bad_plot_key_is_one_line_and_nothing_runs(tmp_path, cli):
    preset = write(tmp_path, "p.toml", TORQUES, SWEEP + 'plot = "masses.txt"\n', **TORQUES_BASE)
    result = cli("sweep", preset, "--workers", "1", "--out-dir", tmp_path / "out")
    assert result.exit_code == 2
    (line,) = result.output.strip().splitlines()
    assert "sweep[1].plot" in line and ".svg, .png, .pdf" in line
    assert not (tmp_path / "out").exists()


def test_a_sweep_the_figure_cannot_show_is_refused_before_anything_runs(tmp_path, cli):
    # one point: no column varies, so there is nothing to draw against
    sweep = """[[sweep]]
job = "torques"
values."theta_deg[1]" = [[10, 20]]
output = "postures.csv"
plot = "postures.svg"
"""
    preset = write(tmp_path, "p.toml", TORQUES, sweep, **TORQUES_BASE)
    result = cli("sweep", preset, "--workers", "1", "--out-dir", tmp_path / "out")
    assert result.exit_code == 2
    assert result.stderr.strip().splitlines() == [result.stderr.strip()]
    assert "sweep[1].plot: the sweep has 1 point" in result.stderr
    assert "Traceback" not in result.output
    assert not (tmp_path / "out").exists()


@pytest.mark.slow
@async_test
async def test_app_figure_key_on_the_sweep_screen_writes_the_sweep_figure(tmp_path):
    """ctrl+l on a finished sweep (a text key: the workspace form) writes the sweep's
    figure beside the CSV the sweep screen exports, the forms on the x axis."""
    from planar_tui.app.screens.sweep import SweepScreen
    from tests.test_app import SIZE, finish, make_app
    from tests.test_app_sweep import _fill, _open_dialog

    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        dialog = await _open_dialog(app, pilot, "workspace")
        _fill(dialog, [("form", '"natural", "slope"')])
        await pilot.press("enter")
        await finish(app, pilot)
        await pilot.pause(0.2)
        screen = app.screen
        assert isinstance(screen, SweepScreen), screen
        assert "ctrl+l writes the figure" in str(screen.query_one("#sweep-heat").render())
        await pilot.press("ctrl+l")
        await app.workers.wait_for_complete()
        await pilot.pause(0.1)
        figure = tmp_path / Path(screen.run.sweep.output).with_suffix(".png")
        assert any(f"Wrote {figure}" in n.message for n in app._notifications)
        assert app.screen is screen
    assert figure.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    from planar_tui.figures import figure_for_table

    ax = figure_for_table(screen.run.table).axes[0]
    assert [t.get_text() for t in ax.get_xticklabels()] == ["natural", "slope"]


def test_a_figure_write_that_fails_is_one_line_and_the_later_sweeps_still_run(
    tmp_path, cli, monkeypatch
):
    import planar_tui.figures.dispatch as dispatch

    def full(table, path, title=""):
        raise OSError(28, "No space left on device", str(path))

    monkeypatch.setattr(dispatch, "save_table_figure", full)
    sweep = """[[sweep]]
job = "torques"
values."robot.masses_kg[2]" = [1.0, 2.0]
output = "one.csv"
plot = "one.svg"

[[sweep]]
job = "torques"
values."robot.masses_kg[1]" = [1.0, 2.0]
output = "two.csv"
"""
    preset = write(tmp_path, "p.toml", TORQUES, sweep, **TORQUES_BASE)
    out = tmp_path / "out"
    result = cli("sweep", preset, "--workers", "1", "--out-dir", out)
    assert result.exit_code == 1
    assert "Traceback" not in result.output
    assert "one.svg: cannot write: No space left on device" in result.stderr
    assert (out / "one.csv").exists() and (out / "two.csv").exists()
    assert sorted(p.name for p in out.iterdir()) == [  # no checkpoint
        "one.csv",
        "one.csv.json",
        "two.csv",
        "two.csv.json",
    ]

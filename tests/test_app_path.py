"""Pilot tests of the path tabs: a small ``[[path3rrr]]`` job run in the app plays the
3-RRR back along its path (the drawing changes between frames; the drawn joints are the
exported CSV's pose and joint angles, by the closed form written here) and plots the
efforts the CSV holds; a 3-PRR path's frames put each slider at the CSV's stroke (cm)."""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest

from planar_tui import batch
from planar_tui.app.app import WorkbenchApp
from planar_tui.app.widgets.path_pane import PathFrames
from planar_tui.app.widgets.robot_drawing import render_scene
from planar_tui.app.workbench import Workbench
from planar_tui.presets import load_preset
from tests.test_app import async_test, finish
from tests.test_path3rrr import JOB, ROBOT
from tests.test_path_prismatic import PRR_PRESET

pytestmark = pytest.mark.slow  # end to end (see pyproject.toml's markers)


def read(path) -> list[dict[str, float]]:
    with open(path, newline="", encoding="utf-8") as handle:
        return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(handle)]


def drawing(view) -> str:
    return "\n".join(render_scene(view.scene, 40, 16).lines())


@async_test
async def test_a_path_job_plays_back_the_robot_and_plots_the_csv_efforts(tmp_path):
    path = tmp_path / "path.toml"
    path.write_text(ROBOT + JOB.replace('plot = "p.png"\n', ""), encoding="utf-8")
    app = WorkbenchApp(Workbench.open(path), output_dir=tmp_path)
    async with app.run_test(size=(100, 30)) as pilot:
        app.action_show_tab("path3rrr")
        await pilot.pause()
        pane = app.query_one("#pane-path3rrr")
        view = pane.query_one("#path-robot")
        assert view.scene is None  # nothing drawn before a run
        await pilot.press("f5")
        await finish(app, pilot)
        assert pane.result is not None, pane.query_one("#result-text").render().plain
        (written,) = app.export_csv(pane, tmp_path)
        rows = read(written)
        assert len(rows) == 21 and len(view.times) == 21
        first = drawing(view)
        assert first.count("#") == 3 and first.count("*") == 3
        view.focus()
        await pilot.pause()
        await pilot.press("end")
        assert view.row == 20
        assert drawing(view) != first  # the robot moved along the path

        # the last frame's joints are the CSV's last row, by the closed form
        last = rows[-1]
        robot = pane.job.robot
        phi = math.radians(last["phi_deg"])
        c, s = math.cos(phi), math.sin(phi)
        platform = [
            ((last["x_cm"] + c * qx - s * qy) / 100, (last["y_cm"] + s * qx + c * qy) / 100)
            for qx, qy in robot.platform_points_cm()
        ]
        elbows = [
            (
                (ax + robot.proximal_cm * math.cos(last[f"theta{i}_rad"])) / 100,
                (ay + robot.proximal_cm * math.sin(last[f"theta{i}_rad"])) / 100,
            )
            for i, (ax, ay) in enumerate(robot.base_joints_cm(), start=1)
        ]
        drawn = {glyph: [] for glyph in "#o*"}
        for point, glyph, _ in view.scene.joints:
            drawn[glyph].append(point)
        np.testing.assert_allclose(drawn["*"], platform, atol=1e-12)
        np.testing.assert_allclose(drawn["o"], elbows, atol=1e-12)
        for elbow, tip in zip(elbows, platform, strict=True):  # the distal links close
            assert math.dist(elbow, tip) == pytest.approx(robot.distal_cm / 100, rel=1e-9)

        # the plot's curves and the read-out are the CSV's efforts
        series = pane.effort_series()
        assert series["t_s"] == pytest.approx([r["t_s"] for r in rows], abs=1e-15)
        for i in (1, 2, 3):
            assert series[f"tau{i}_Nm"] == pytest.approx([r[f"tau{i}_Nm"] for r in rows], rel=1e-12)
        readout = pane.query_one("#path-readout").render().plain
        assert "t = 0.5 s / 0.5 s" in readout
        for i in (1, 2, 3):
            assert f"tau{i} {last[f'tau{i}_Nm']:.6g}" in readout
        await pilot.press("home")
        assert view.row == 0 and drawing(view) == first
        for _ in range(6):  # × 0.01: the 0.5 s path plays for 50 s
            await pilot.press("left_square_bracket")
        await pilot.press("space")
        assert view.playing and "▶ ×0.01" in pane.query_one("#path-readout").render().plain
        await pilot.press("space")
        assert not view.playing


def test_a_prismatic_paths_frames_put_the_sliders_at_the_csv_strokes(tmp_path):
    preset = tmp_path / "prr.toml"
    preset.write_text(PRR_PRESET.replace('plot = "prr.svg"\n', ""), encoding="utf-8")
    (job,) = load_preset(preset).jobs
    result = batch.run_job(job)
    header = list(result.table.header)
    table = np.asarray(result.table.rows)
    frames = PathFrames(job, result)
    robot = job.robot
    for row in (0, len(table) // 2, len(table) - 1):
        scene = frames.scene(row)
        sliders = [point for point, glyph, _ in scene.joints if glyph == "#"]
        for (bx, by), angle, point, leg in zip(
            robot.slider_points_cm, robot.slider_angles_deg, sliders, (1, 2, 3), strict=True
        ):
            stroke = table[row, header.index(f"rho{leg}_cm")]
            expected = (
                (bx + stroke * math.cos(math.radians(angle))) / 100,
                (by + stroke * math.sin(math.radians(angle))) / 100,
            )
            assert point == pytest.approx(expected, abs=1e-12)
    x_lo, x_hi, y_lo, y_hi = frames.extent_m  # every frame's points inside the fixed extent
    for row in range(len(table)):
        for x, y in frames.linkage(row).points():
            assert x_lo <= x / 100 <= x_hi and y_lo <= y / 100 <= y_hi

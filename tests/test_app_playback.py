"""Pilot tests of the Simulate tab's playback: the frame at t = 0.5 s equals the simulate
CSV's state, the drawn arm is that state's, the keys step, play, change speed, hide joints
and wrap angles."""

from __future__ import annotations

import csv
import math
from pathlib import Path

import pytest

from planar_tui.app.app import WorkbenchApp
from planar_tui.app.widgets.playback import wrap_deg
from planar_tui.app.widgets.robot_drawing import render_scene
from planar_tui.app.workbench import Workbench
from tests.test_app import async_test, finish, until

pytestmark = pytest.mark.slow  # end to end (see pyproject.toml's markers)

PRESET = """\
[robot]
name = "2R"
gravity_m_s2 = 9.81
lengths_m = [0.303, 0.214]
masses_kg = [1.126, 0.796]
inertias_kgm2 = [0.129, 0.045]

[simulate]
duration_s = 1.0
step_s = 0.001
theta0_deg = [30, -60]
torques_Nm = [0.5, 0.1]
every = 10
output = "playback.csv"
"""


def make_app(tmp_path):
    path = tmp_path / "playback.toml"
    path.write_text(PRESET)
    return WorkbenchApp(Workbench.open(path), output_dir=tmp_path)


def test_wrap_deg_maps_into_minus_180_exclusive_to_180_inclusive():
    assert wrap_deg([180.0, -180.0, 540.0, 190.0, -190.0, 0.0, 359.0]).tolist() == [
        180.0,
        180.0,
        180.0,
        -170.0,
        170.0,
        0.0,
        -1.0,
    ]


async def run_simulation(app, pilot):
    app.action_show_tab("simulate")
    await pilot.pause()
    await pilot.press("f5")
    await finish(app, pilot)


@async_test
async def test_the_frame_at_half_a_second_is_the_csv_state(tmp_path):
    app = make_app(tmp_path)
    async with app.run_test(size=(80, 24)) as pilot:
        pane = app.query_one("#pane-simulate")
        start = "\n".join(render_scene(pane.query_one("#simulate-arm").scene, 20, 8).lines())
        assert start.count("#") == 1 and "+" in start  # the start posture before a run
        await run_simulation(app, pilot)
        view = pane.query_one("#simulate-arm")
        view.focus()
        await pilot.pause()
        for _ in range(50):  # 101 rows: a step is one row of 10 ms
            await pilot.press("right")
        await until(
            pilot, lambda: "t = 0.5 s" in pane.query_one("#playback-readout").render().plain
        )
        written = app.export_csv(pane, tmp_path)
        with open(written[0], newline="") as handle:
            rows = {row["t_s"]: row for row in csv.DictReader(handle)}
        row = next(r for t, r in rows.items() if abs(float(t) - 0.5) < 1e-9)
        assert view.t_s == pytest.approx(0.5, abs=1e-12)
        theta = [float(row["theta1_rad"]), float(row["theta2_rad"])]
        assert pane.result.theta_rad[view.row].tolist() == pytest.approx(theta, rel=1e-12)
        # the drawn tip is the CSV state's, by the closed form (relative angles)
        tip = (
            0.303 * math.cos(theta[0]) + 0.214 * math.cos(theta[0] + theta[1]),
            0.303 * math.sin(theta[0]) + 0.214 * math.sin(theta[0] + theta[1]),
        )
        (drawn_tip, glyph, _) = view.scene.joints[-1]
        assert glyph == "+" and drawn_tip == pytest.approx(tip, abs=1e-12)
        readout = pane.query_one("#playback-readout").render().plain
        assert f"θ1 {math.degrees(theta[0]):.4g}°" in readout
        energy = float(row["energy_J"])
        assert f"E {energy:.5g} J" in readout
        # speed, play to the end, home
        await pilot.press("right_square_bracket")
        assert view.speed == 2.0
        await pilot.press("left_square_bracket", "left_square_bracket", "left_square_bracket")
        assert view.speed == 0.25
        await pilot.press("home", "space")  # 1 s of run at 0.25 × real time: 4 s
        assert view.playing and "▶ ×0.25" in pane.query_one("#playback-readout").render().plain
        await until(pilot, lambda: view.row > 0)
        await until(pilot, lambda: not view.playing, timeout_s=60)
        assert view.row == len(view.times) - 1
        await pilot.press("home")
        assert view.row == 0
        # hide joint 1, wrap the angles
        await pilot.press("1")
        assert pane.hidden == {1} and "θ1" not in pane.query_one("#playback-readout").render().plain
        await pilot.press("a")
        assert pane.hidden == frozenset()
        await pilot.press("w")
        assert pane.wrap and "(wrapped)" in pane.query_one("#playback-readout").render().plain


@async_test
async def test_the_sensitivity_tab_draws_the_solved_isotropic_posture(tmp_path):
    from planar_tui.sensitivity.postures import isotropic_posture
    from planar_tui.sensitivity.results import csv_table
    from planar_tui.sensitivity.runner import SensitivityResult
    from tests.test_app_layout import load_6r

    app = WorkbenchApp(Workbench.open(Path(__file__).parent / "data" / "app" / "tiny.toml"))
    async with app.run_test(size=(80, 24)) as pilot:
        app.action_show_tab("sensitivity")
        await pilot.pause()
        pane = app.query_one("#pane-sensitivity")
        arm = pane.query_one("#sensitivity-arm")
        assert not arm.display  # no posture before a run
        posture = isotropic_posture([0.303, 0.214])
        analyses = load_6r()
        result = SensitivityResult(
            table=csv_table("2R", analyses),
            summary="recorded",
            robot_label="2R",
            posture=posture,
            analyses=analyses,
            samples={"sobol": 1024},
        )
        pane.show_result(pane.current_job(), result)
        await pilot.pause()
        assert arm.display
        t1, t2 = posture.theta_rad
        elbow = (0.303 * math.cos(t1), 0.303 * math.sin(t1))
        tip = (elbow[0] + 0.214 * math.cos(t1 + t2), elbow[1] + 0.214 * math.sin(t1 + t2))
        points = [point for point, _, _ in arm.scene.joints]
        assert points == [
            (0.0, 0.0),
            pytest.approx(elbow, abs=1e-12),
            pytest.approx(tip, abs=1e-12),
        ]
        assert "├" in str(arm.render()) and " m" in str(arm.render())  # the scale bar

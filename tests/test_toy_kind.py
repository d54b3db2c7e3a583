"""A job kind defined in this file alone (kinetic energy ½ θ̇ᵀ M(θ) θ̇ of the serial robot
at listed states), registered for the test, works everywhere a kind does: ``planar-tui
run``, its own command (listed by ``--help``), a ``[[sweep]]`` and the app's tabs. Its
energies are checked against the closed form of a 2-link arm."""

from __future__ import annotations

import asyncio
import csv
import math
from dataclasses import dataclass

import pytest
from typer.testing import CliRunner

from planar_tui.csvio import CsvTable
from planar_tui.jobkind import Command, Job, JobKind, JobResult, Option, Tab
from planar_tui.progress import Progress
from planar_tui.registry import registered
from planar_tui.schema import PER_LINK, number, number_rows, setting


@dataclass(frozen=True, kw_only=True)
class KineticSpec:
    theta_deg: tuple[tuple[float, ...], ...] = setting(
        number_rows(columns=PER_LINK), type_doc="rows", doc="relative joint angles"
    )
    omega_deg_s: tuple[tuple[float, ...], ...] = setting(
        number_rows(columns=PER_LINK), type_doc="rows", doc="joint rates"
    )
    speed_scale: float = setting(number(positive=True), type_doc="number", doc="x", default=1.0)


@dataclass(frozen=True, kw_only=True)
class KineticResult(JobResult):
    energies_J: tuple[float, ...]


def run_kinetic(job: Job, progress: Progress) -> KineticResult:
    import numpy as np
    from planar_tui.kernels.noc_matrices import mass_matrix

    lengths, masses, inertias = job.robot.arrays()
    energies = []
    for theta, omega in zip(job.spec.theta_deg, job.spec.omega_deg_s, strict=True):
        rate = np.radians(np.array(omega)) * job.spec.speed_scale
        matrix = mass_matrix(lengths, masses, inertias, np.radians(np.array(theta)))
        energies.append(float(0.5 * rate @ matrix @ rate))
    rows = [[*theta, energy] for theta, energy in zip(job.spec.theta_deg, energies, strict=True)]
    header = (*(f"theta{i + 1}_deg" for i in range(job.robot.n_links)), "kinetic_J")
    return KineticResult(
        table=CsvTable(header, rows), summary=f"{len(rows)} states", energies_J=tuple(energies)
    )


TOY = JobKind(
    name="kinetic",
    robot_kind="robot",
    settings=KineticSpec,
    run=run_kinetic,
    summary="kinetic energy at listed states",
    point_figures=lambda job, result: {"max_kinetic_J": max(result.energies_J)},
    command=Command(
        "kinetic",
        "Kinetic energy of the arm at the listed states of every kinetic job.",
        options=(Option("--speed-scale", "speed_scale", "Scales the rates.", float),),
    ),
    tab=Tab("Kinetic", 9),
)

L1, L2, M1, M2, I1, I2 = 0.3, 0.2, 1.0, 0.8, 0.01, 0.004
STATES = [((0.0, 0.0), (10.0, 20.0)), ((30.0, 90.0), (-40.0, 15.0))]
PRESET = f"""[robot]
lengths_m = [{L1}, {L2}]
masses_kg = [{M1}, {M2}]
inertias_kgm2 = [{I1}, {I2}]

[kinetic]
theta_deg = {[list(t) for t, _ in STATES]}
omega_deg_s = {[list(w) for _, w in STATES]}
output = "kinetic.csv"
"""
SWEEP = """
[[sweep]]
job = "kinetic"
values.speed_scale = [1.0, 2.0]
output = "kinetic-sweep.csv"
"""


def closed_form_J(theta_deg, omega_deg_s, scale=1.0) -> float:
    """T = ½ θ̇ᵀ M θ̇ of a 2-link arm, centres of mass at mid-link, relative angles:
    M11 = I1 + I2 + m1 c1² + m2 (l1² + c2² + 2 l1 c2 cos θ2), M12 = I2 + m2 (c2² + l1 c2
    cos θ2), M22 = I2 + m2 c2²."""
    c1, c2 = L1 / 2, L2 / 2
    cos2 = math.cos(math.radians(theta_deg[1]))
    w1, w2 = (math.radians(w) * scale for w in omega_deg_s)
    m11 = I1 + I2 + M1 * c1**2 + M2 * (L1**2 + c2**2 + 2 * L1 * c2 * cos2)
    m12 = I2 + M2 * (c2**2 + L1 * c2 * cos2)
    m22 = I2 + M2 * c2**2
    return 0.5 * (m11 * w1**2 + 2 * m12 * w1 * w2 + m22 * w2**2)


@pytest.fixture
def toy():
    with registered(TOY) as kind:
        yield kind


def invoke(*args):
    from planar_tui.cli import build_app

    return CliRunner().invoke(build_app(), [str(a) for a in args], catch_exceptions=False)


def energies(path) -> list[float]:
    with open(path, newline="", encoding="utf-8") as stream:
        return [float(row["kinetic_J"]) for row in csv.DictReader(stream)]


def test_the_toy_kind_runs_from_run_with_the_closed_form_energies(toy, tmp_path):
    (tmp_path / "toy.toml").write_text(PRESET, encoding="utf-8")
    result = invoke("run", tmp_path / "toy.toml", "--out-dir", tmp_path)
    assert result.exit_code == 0, result.output
    expected = [closed_form_J(t, w) for t, w in STATES]
    assert energies(tmp_path / "kinetic.csv") == pytest.approx(expected, rel=1e-12)


def test_the_toy_kind_has_its_own_command_and_options(toy, tmp_path):
    (tmp_path / "toy.toml").write_text(PRESET, encoding="utf-8")
    assert "kinetic " in invoke("--help").stdout
    result = invoke("kinetic", tmp_path / "toy.toml", "--speed-scale", "2", "-d", tmp_path)
    assert result.exit_code == 0, result.output
    expected = [closed_form_J(t, w, 2.0) for t, w in STATES]
    assert energies(tmp_path / "kinetic--speed-scale-2.0.csv") == pytest.approx(expected)
    bad = invoke("kinetic", tmp_path / "toy.toml", "--speed-scale", "0", "-d", tmp_path)
    assert bad.exit_code == 2 and bad.stderr.startswith("error: command line: --speed-scale: ")


def test_a_plot_for_the_toy_kind_is_refused_before_anything_runs(toy, tmp_path):
    (tmp_path / "toy.toml").write_text(PRESET, encoding="utf-8")
    result = invoke("kinetic", tmp_path / "toy.toml", "-d", tmp_path, "--plot", tmp_path / "k.png")
    assert result.exit_code == 2
    assert result.stderr == (
        "error: command line: --plot: toy:kinetic: the kinetic job kind draws no figure "
        "(expected no --plot for a kinetic job)\n"
    )
    again = invoke("run", tmp_path / "toy.toml", "-d", tmp_path, "--plot", tmp_path / "k.png")
    assert again.exit_code == 2 and again.stderr == result.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["toy.toml"]


def test_the_toy_kind_runs_in_a_sweep(toy, tmp_path):
    (tmp_path / "toy.toml").write_text(PRESET + SWEEP, encoding="utf-8")
    result = invoke("sweep", tmp_path / "toy.toml", "--workers", "1", "-d", tmp_path)
    assert result.exit_code == 0, result.output
    with open(tmp_path / "kinetic-sweep.csv", newline="", encoding="utf-8") as stream:
        rows = list(csv.DictReader(stream))
    assert [row["status"] for row in rows] == ["ok", "ok"]
    peak = max(closed_form_J(t, w) for t, w in STATES)
    got = [float(row["max_kinetic_J"]) for row in rows]
    assert got == pytest.approx([peak, 4 * peak], rel=1e-12)


@pytest.mark.slow  # an end-to-end app test
def test_the_toy_kind_has_an_app_tab(toy, tmp_path):
    asyncio.run(_app_tab(tmp_path))


async def _app_tab(tmp_path):
    from planar_tui.app.app import WorkbenchApp
    from planar_tui.app.widgets.panes import JobPane
    from planar_tui.app.workbench import Workbench

    (tmp_path / "toy.toml").write_text(PRESET, encoding="utf-8")
    app = WorkbenchApp(Workbench.open(tmp_path / "toy.toml"), output_dir=tmp_path)
    async with app.run_test(size=(120, 40)) as pilot:
        assert ("Kinetic", "kinetic") in app.tabs()
        pane = app.query_one("#pane-kinetic", JobPane)
        app.action_show_tab("kinetic")
        await pilot.pause()
        assert "1 job valid" in str(app.query_one("#validation").render())
        assert pane.available()

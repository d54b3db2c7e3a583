"""``[[optimise]]`` tables and ``planar-tui optimise``: known optima of a 2-link arm's
static torques (closed form ``τ1 = g[(m1 l1/2 + m2 l1) cos θ1 + m2 l2/2 cos(θ1 + θ2)]``,
``τ2 = g m2 l2/2 cos(θ1 + θ2)``) and of paper B's workspace against its orientation (a
grid sweep of the same job), constraints held, a Pareto set against a grid, the same CSV
on 1 worker and on a 2-process cluster and after Ctrl-C + ``--resume``, bad tables."""

from __future__ import annotations

import csv
import math
import os
import signal
import subprocess
import sys
import time

import pytest

from planar_tui.errors import ExitCode
from tests.conftest import REPO

G, L1, L2, M1, M2 = 9.81, 0.5, 0.4, 2.0, 1.0
#: ``τ1 = A cos θ1 + B cos(θ1 + θ2)``, ``τ2 = B cos(θ1 + θ2)`` at rest (closed form).
A = G * (M1 * L1 / 2 + M2 * L1)
B = G * M2 * L2 / 2

ARM = f"""[robot]
gravity_m_s2 = {G}
lengths_m = [{L1}, {L2}]
masses_kg = [{M1}, {M2}]
inertias_kgm2 = [0.04, 0.01]

[torques]
theta_deg = [[0, 0]]
omega_deg_s = [[0, 0]]
alpha_deg_s2 = [[0, 0]]
output = "t.csv"
"""

PAPER_B = """[robot3rrr]
base_side_cm = 120
platform_side_cm = 40
proximal_cm = 30
distal_cm = 30

[[workspace]]
form = "arc-distance"
precision_cm = 0.46875
joint_limits_deg = [[20, 70], [110, 160], [245, 295]]
orientation_deg = 0
geometric_reference = false
output = "w.csv"
"""

CONSOLE_SCRIPT = "from planar_tui.entry import main; main()"


def write(tmp_path, text: str, name: str = "p.toml"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def rows(path):
    with open(path, newline="") as stream:
        return list(csv.DictReader(stream))


def torques(theta1_deg: float, theta2_deg: float) -> tuple[float, float]:
    """|τ1|, |τ2| in closed form."""
    t1, t12 = math.radians(theta1_deg), math.radians(theta1_deg + theta2_deg)
    return abs(A * math.cos(t1) + B * math.cos(t12)), abs(B * math.cos(t12))


def test_one_variable_finds_the_closed_form_maximum_and_certifies_it(tmp_path, cli):
    preset = write(
        tmp_path,
        ARM
        + """
[[optimise]]
job = "torques"
variables."theta_deg[1][1]" = { from = -60, to = 30 }
maximise = "tau1_abs_max_Nm"
budget = 60
population = 12
output = "opt.csv"
plot = "opt.png"
""",
    )
    result = cli("optimise", preset, "--out-dir", tmp_path, "--workers", "1")
    assert result.exit_code == 0, result.output
    assert (
        "60 evaluations in 5 generations, 0 infeasible, 0 failed; optimum: evaluation"
        in result.stdout
    )
    (best,) = rows(tmp_path / "opt-optimum.csv")
    assert abs(float(best["theta_deg[1][1]"])) < 3.0
    assert float(best["tau1_abs_max_Nm"]) == pytest.approx(A + B, rel=2e-3)
    assert float(best["tau1_abs_max_Nm"]) <= A + B + 1e-9
    evaluations = rows(tmp_path / "opt.csv")
    assert len(evaluations) == 60
    for row in evaluations:  # every evaluation's figure is the closed form at its design
        theta = float(row["theta_deg[1][1]"])
        assert float(row["tau1_abs_max_Nm"]) == pytest.approx(torques(theta, 0)[0], rel=1e-9)
    assert (tmp_path / "opt.png").stat().st_size > 0


def test_two_variables_with_integer_and_choice_reach_the_maximum(tmp_path, cli):
    preset = write(
        tmp_path,
        ARM
        + """
[[optimise]]
job = "torques"
variables."theta_deg[1][1]" = { from = -40, to = 40, integer = true }
variables."theta_deg[1][2]" = { choices = [-60, -30, 0, 45] }
maximise = "tau1_abs_max_Nm"
budget = 80
population = 16
output = "opt.csv"
""",
    )
    result = cli("optimise", preset, "--out-dir", tmp_path, "--workers", "1")
    assert result.exit_code == 0, result.output
    (best,) = rows(tmp_path / "opt-optimum.csv")
    assert best["theta_deg[1][2]"] == "0" and abs(int(best["theta_deg[1][1]"])) <= 2
    assert float(best["tau1_abs_max_Nm"]) >= 0.999 * (A + B)
    for row in rows(tmp_path / "opt.csv"):
        assert float(row["theta_deg[1][1]"]).is_integer()
        assert row["theta_deg[1][2]"] in ("-60", "-30", "0", "45")


def test_paper_b_orientation_optimum_is_near_30_degrees_and_matches_a_grid(tmp_path, cli):
    """The area inside paper B's workspace (coarse precision 0.9375 cm) peaks near ±30°
    (its sweep: docs/sweeps.md); the optimiser's best is within 1 % of a dense grid's."""
    preset = write(
        tmp_path,
        PAPER_B
        + """
[[sweep]]
job = "workspace"
values.orientation_deg = { from = -45, to = 45, count = 91 }
values.precision_cm = [0.9375]
output = "grid.csv"

[[optimise]]
job = "workspace"
variables.orientation_deg = { from = -45, to = 45 }
maximise = "area_inside_cm2"
coarse = { precision_cm = 0.9375 }
budget = 96
population = 16
output = "opt.csv"
""",
    )
    result = cli("run", preset, "--out-dir", tmp_path, "--workers", "1")
    assert result.exit_code == 0, result.output
    grid = max(float(r["area_inside_cm2"]) for r in rows(tmp_path / "grid.csv"))
    (best,) = rows(tmp_path / "opt-optimum.csv")
    assert 24 <= abs(float(best["orientation_deg"])) <= 36
    assert float(best["coarse_area_inside_cm2"]) >= 0.99 * grid
    # certified at the job's own precision: a bracket around the exact area
    assert float(best["precision_cm"]) == 0.46875
    assert float(best["area_inside_cm2"]) <= float(best["area_kept_cm2"])


def test_constraints_are_held_by_every_feasible_design_and_bind_at_the_optimum(tmp_path, cli):
    preset = write(
        tmp_path,
        ARM
        + """
[[optimise]]
job = "torques"
variables."theta_deg[1][1]" = { from = 0, to = 90 }
maximise = "tau1_abs_max_Nm"
constraints = ["tau1_abs_max_Nm <= 6", "tau2_abs_max_Nm > 0.5"]
budget = 80
population = 16
output = "opt.csv"
""",
    )
    result = cli("optimise", preset, "--out-dir", tmp_path, "--workers", "1")
    assert result.exit_code == 0, result.output
    for row in rows(tmp_path / "opt.csv"):
        tau1, tau2 = float(row["tau1_abs_max_Nm"]), float(row["tau2_abs_max_Nm"])
        assert (row["feasible"] == "true") == (tau1 <= 6 and tau2 > 0.5)
    (best,) = rows(tmp_path / "opt-optimum.csv")
    # τ1 = (A + B) cos θ1 <= 6: the optimum is at the constraint, θ1 = acos(6 / (A + B))
    assert float(best["tau1_abs_max_Nm"]) <= 6
    assert float(best["tau1_abs_max_Nm"]) == pytest.approx(6, rel=0.01)
    assert float(best["theta_deg[1][1]"]) == pytest.approx(
        math.degrees(math.acos(6 / (A + B))), abs=1.0
    )


def test_two_objectives_give_a_pareto_set_no_grid_point_dominates(tmp_path, cli):
    """Maximise |τ1|, minimise |τ2| over θ1, θ2 ∈ [0, 90]°: the front is θ1 = 0,
    τ1 = A + τ2 (τ1 ≤ A cos θ1 + τ2). Every reported point lies near it and no point of a
    61 × 61 closed-form grid dominates one by more than 2 % of the ranges."""
    preset = write(
        tmp_path,
        ARM
        + """
[[optimise]]
job = "torques"
variables."theta_deg[1][1]" = { from = 0, to = 90 }
variables."theta_deg[1][2]" = { from = 0, to = 90 }
maximise = "tau1_abs_max_Nm"
minimise = "tau2_abs_max_Nm"
budget = 600
population = 40
output = "opt.csv"
plot = "front.svg"
""",
    )
    result = cli("optimise", preset, "--out-dir", tmp_path, "--workers", "1")
    assert result.exit_code == 0, result.output
    front = rows(tmp_path / "opt-optimum.csv")
    assert len(front) >= 5
    grid = [torques(a * 1.5, b * 1.5) for a in range(61) for b in range(61)]
    tol1, tol2 = 0.02 * (A + B), 0.02 * B
    taus = [(float(r["tau1_abs_max_Nm"]), float(r["tau2_abs_max_Nm"])) for r in front]
    for tau1, tau2 in taus:
        assert tau1 == pytest.approx(A + tau2, abs=0.05 * (A + B))
        assert not any(g1 > tau1 + tol1 and g2 < tau2 - tol2 for g1, g2 in grid)
    assert max(t2 for _, t2 in taus) - min(t2 for _, t2 in taus) > 0.5 * B  # spread
    assert (tmp_path / "front.svg").read_text().startswith("<?xml")


PARALLEL = (
    ARM
    + """
[[optimise]]
job = "torques"
variables."theta_deg[1][1]" = { from = -90, to = 90 }
variables."theta_deg[1][2]" = { from = -90, to = 90 }
maximise = "tau1_abs_max_Nm"
budget = {budget}
population = 20
seed = 7
output = "opt.csv"
"""
)


@pytest.mark.slow
def test_one_worker_and_a_two_process_cluster_with_a_worker_killed_give_the_same_csvs(
    tmp_path, cli
):
    """The CLI on 1 worker, then the same run on a 2-process local cluster (the CLI's
    ``--workers 2`` path: :func:`run_optimisation` with its client) one of whose worker
    processes is killed (SIGKILL) while the second generation runs: its nanny starts it
    again, Dask runs its evaluations again, the CSVs are the same."""
    import threading

    from distributed import Client

    from planar_tui.optimise.run import run_optimisation
    from planar_tui.optimise.spec import parse_optimisations
    from planar_tui.presets import load_preset
    from planar_tui.sweep.execute import local_cluster

    preset = write(tmp_path, PARALLEL.replace("{budget}", "60"))
    result = cli("optimise", preset, "--out-dir", tmp_path / "1", "--workers", "1")
    assert result.exit_code == 0, result.output
    (optimisation,) = parse_optimisations(load_preset(preset))
    started = time.monotonic()
    killed = []
    with local_cluster(2) as cluster, Client(cluster) as client:
        pids = sorted(client.run(os.getpid).values())

        def kill_during_the_next_generation(run) -> None:
            if run.generations == 1:
                threading.Timer(0.02, lambda: killed.append(os.kill(pids[0], 9))).start()

        run = run_optimisation(
            optimisation,
            client=client,
            out_dir=tmp_path / "2",
            on_generation=kill_during_the_next_generation,
        )
        assert killed and pids[0] not in client.run(os.getpid).values()
    assert time.monotonic() - started < 300
    assert len(run.evaluations) == 60
    for name in ("opt.csv", "opt-optimum.csv"):
        one, two = ((tmp_path / w / name).read_text() for w in ("1", "2"))
        assert one == two


@pytest.mark.slow
def test_ctrl_c_then_resume_gives_the_uninterrupted_csv(tmp_path, cli):
    preset = write(tmp_path, PARALLEL.replace("{budget}", "400"))
    out = tmp_path / "out"
    checkpoint = out / "opt.csv.checkpoint.jsonl"
    process = subprocess.Popen(
        [
            sys.executable,
            "-c",
            CONSOLE_SCRIPT,
            "optimise",
            str(preset),
            "--workers",
            "1",
            "--out-dir",
            str(out),
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
        env=dict(os.environ, PYTHONPATH=str(REPO)),
    )
    deadline = time.monotonic() + 120
    while not (checkpoint.exists() and len(checkpoint.read_text().splitlines()) >= 30):
        assert process.poll() is None, process.communicate()
        assert time.monotonic() < deadline, "no evaluation finished"
        time.sleep(0.01)
    os.killpg(process.pid, signal.SIGINT)
    _, err = process.communicate(timeout=600)
    assert process.returncode == ExitCode.INTERRUPTED, err
    assert err.strip().splitlines()[-1].startswith("interrupted: finished evaluations are")
    assert "Traceback" not in err
    assert not (out / "opt.csv").exists()
    kept = len(checkpoint.read_text().splitlines()) - 1
    assert 29 <= kept < 400

    result = cli("optimise", preset, "--out-dir", out, "--resume", "--workers", "1")
    assert result.exit_code == 0, result.output
    assert f"{kept} from the checkpoint" in result.stdout
    assert not checkpoint.exists()
    whole = cli("optimise", preset, "--out-dir", tmp_path / "whole", "--workers", "1")
    assert whole.exit_code == 0, whole.output
    for name in ("opt.csv", "opt-optimum.csv"):
        assert (out / name).read_text() == (tmp_path / "whole" / name).read_text()


BASE = ARM + '\n[[optimise]]\njob = "torques"\noutput = "o.csv"\n'
GOOD = 'variables."theta_deg[1][1]" = { from = 0, to = 90 }\nmaximise = "tau1_abs_max_Nm"\n'


@pytest.mark.parametrize(
    ("table", "line"),
    [
        ("", "optimise[1].variables: missing key (expected a table of key paths)"),
        (GOOD + "colour = 1\n", "optimise[1].colour: unknown key (expected one of job, "),
        (
            GOOD.replace("theta_deg[1][1]", "theta_dg[1][1]"),
            'optimise[1].variables."theta_dg[1][1]": unknown key path',
        ),
        (GOOD.replace("[1][1]", "[3][1]"), 'optimise[1].variables."theta_deg[3][1]": index 3'),
        (
            GOOD.replace("to = 90", "to = 0"),
            'optimise[1].variables."theta_deg[1][1]".to: is 0, not above from = 0 (expected to > from)',
        ),
        (
            GOOD.replace("{ from = 0, to = 90 }", "[0, 90]"),
            'optimise[1].variables."theta_deg[1][1]": is an array',
        ),
        (
            GOOD.replace("{ from = 0, to = 90 }", "{ choices = [] }"),
            'optimise[1].variables."theta_deg[1][1]".choices: is empty',
        ),
        (
            GOOD.replace("{ from = 0, to = 90 }", "{ from = 0.5, to = 9, integer = true }"),
            'optimise[1].variables."theta_deg[1][1]".from: is a number (expected an integer)',
        ),
        (
            'variables."theta_deg[1][1]" = { from = 0, to = 90 }\n',
            "optimise[1].maximise: missing key (and no minimise)",
        ),
        (GOOD + 'minimise = "tau1_abs_max_Nm"\n', "optimise[1].minimise: repeats the objective"),
        (
            GOOD + 'constraints = ["tau1_abs_max_Nm => 3"]\n',
            "optimise[1].constraints[1]: is 'tau1_abs_max_Nm => 3' (expected \"COLUMN OP NUMBER\"",
        ),
        (
            GOOD + 'constraints = ["tau1 >= nan"]\n',
            "optimise[1].constraints[1]: is 'tau1 >= nan': 'nan' is not a finite number",
        ),
        (GOOD + "constraints = [3]\n", "optimise[1].constraints[1]: is an integer"),
        (GOOD + "budget = 0\n", "optimise[1].budget: is 0 (expected an integer >= 1)"),
        (
            GOOD + 'algorithm = "pso"\n',
            "optimise[1].algorithm: is 'pso' (expected one of auto, ga, de, nsga2)",
        ),
        (
            GOOD + 'algorithm = "de"\nminimise = "tau2_abs_max_Nm"\n',
            'optimise[1].algorithm: is "de" with 2 objectives',
        ),
        (GOOD + "coarse = { speed = 1 }\n", "optimise[1].coarse.speed: unknown key path"),
        (
            GOOD + 'coarse = { "theta_deg[1][1]" = 1 }\n',
            'optimise[1].coarse."theta_deg[1][1]": names the same value as theta_deg[1][1]',
        ),
        (
            GOOD.replace("to = 90 }", 'to = 90, fixed_sum = { "theta_deg[1][1]" = 90 } }'),
            'optimise[1].variables."theta_deg[1][1]".fixed_sum."theta_deg[1][1]": names the same',
        ),
        (
            GOOD.replace("to = 90 }", 'to = 90, fixed_sum = { "theta_deg[1][2]" = 90 } }')
            + 'variables."robot.lengths_m[1]" = { from = 0.1, to = 0.4, fixed_sum = '
            '{ "theta_deg[1][2]" = 80 } }\n',
            'optimise[1].variables."robot.lengths_m[1]".fixed_sum."theta_deg[1][2]": is 80.0, '
            "another total than 90.0",
        ),
        (
            GOOD.replace("to = 90 }", "to = 90, fixed_sum = {} }"),
            'optimise[1].variables."theta_deg[1][1]".fixed_sum: is empty',
        ),
        (
            GOOD + 'coarse = { "robot.lengths_m[1]" = -1 }\n',
            "optimise[1]: point 1 (theta_deg[1][1] = 0.0, robot.lengths_m[1] = -1): robot.lengths_m",
        ),
        (
            GOOD + 'pareto_output = "o.csv"\n',
            "optimise[1].pareto_output: is 'o.csv', the same as output (expected another file)",
        ),
        (GOOD + 'plot = "o.txt"\n', "optimise[1].plot: is 'o.txt': has the suffix '.txt'"),
        (
            'job = "workspace"\n' + GOOD,
            "optimise[1].job: is 'workspace', no such job (expected "
            "one of the preset's jobs: torques)",
        ),
    ],
)
def test_a_bad_table_is_one_line_and_exit_2(tmp_path, cli, table, line):
    text = BASE.replace('job = "torques"\n', 'job = "torques"\n' + table)
    if 'job = "workspace"' in table:
        text = BASE.replace('job = "torques"\n', "") + table
    preset = write(tmp_path, text)
    result = cli("optimise", preset, "--out-dir", tmp_path / "out", "--workers", "1")
    assert result.exit_code == 2, result.output
    assert result.stdout == ""
    assert result.stderr.startswith(f"error: {preset}: {line}"), result.stderr
    assert result.stderr.count("\n") == 1
    assert not (tmp_path / "out").exists()


def test_a_column_the_job_does_not_report_is_refused(tmp_path, cli):
    preset = write(
        tmp_path,
        BASE + 'variables."theta_deg[1][1]" = { from = 0, to = 90 }\nmaximise = "tau9_Nm"\n',
    )
    result = cli("optimise", preset, "--out-dir", tmp_path, "--workers", "1")
    assert result.exit_code == 2, result.output
    assert (
        "optimise[1]: names the column 'tau9_Nm', not one of the job's (expected one of "
        "tau1_abs_max_Nm, tau2_abs_max_Nm)" in result.stderr
    )
    assert sorted(p.name for p in tmp_path.iterdir()) == ["p.toml"]  # no checkpoint left


def test_a_preset_without_optimise_tables_is_refused(tmp_path, cli):
    preset = write(tmp_path, ARM)
    result = cli("optimise", preset, "--out-dir", tmp_path)
    assert result.exit_code == 2
    assert (
        result.stderr == f"error: {preset}: optimise: no [[optimise]] table in this "
        "preset (expected an [[optimise]] table)\n"
    )


def test_the_sensitivity_jobs_torque_variance_is_the_closed_form(tmp_path):
    """Study (c)'s objective: at rest, ``τ2 = g m2 (l2/2) cos(θ1 + θ2)`` with ``m2``, ``l2``
    independent and uniform (half-widths δm, δl), so ``Var τ2 = (g cos(θ1 + θ2) / 2)² ·
    [(m2² + δm²/3)(l2² + δl²/3) − m2² l2²]``."""
    from planar_tui.batch import prepare_jobs, run_job
    from planar_tui.presets import load_preset
    from planar_tui.registry import JOB_KINDS

    preset = write(
        tmp_path,
        ARM.split("[torques]")[0]
        + """
[sensitivity]
posture = [30, 20]
speed_rad_s = 0
tolerance_length_mm = 50
tolerance_mass_g = 100
methods = ["sobol"]
samples = 4096
output = "s.csv"
""",
    )
    (job,) = prepare_jobs(load_preset(preset).jobs)
    figures = JOB_KINDS["sensitivity"].point_figures(job, run_job(job))
    dl, dm = 0.05, 0.1
    product = (M2**2 + dm**2 / 3) * (L2**2 + dl**2 / 3) - (M2 * L2) ** 2
    expected = (G * math.cos(math.radians(50)) / 2) ** 2 * product
    assert figures["tau2_variance_Nm2"] == pytest.approx(expected, rel=0.05)
    assert figures["tau_variance_max_Nm2"] == max(
        figures["tau1_variance_Nm2"], figures["tau2_variance_Nm2"]
    )

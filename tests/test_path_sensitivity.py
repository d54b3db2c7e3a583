"""The path sensitivity of a parallel robot's actuator efforts
(planar_tui/pathsensitivity): closed forms (an input that does not enter the efforts, a
purely additive effect), the three estimators against each other, the PCE's mean and
variance against Monte Carlo, the job's files, bad input and a failing path."""

from __future__ import annotations

import csv

import numpy as np
import pytest

from planar_tui.pathsensitivity.engine import design_efforts, path_outputs, path_states, scaled
from planar_tui.pathsensitivity.inputs import robot_inputs
from planar_tui.workspace.rrr.mechanism import MECHANISM
from planar_tui.workspace.rrr.path import Path3RRRSpec
from planar_tui.workspace.rrr.robot import Robot3RRR

ROBOT = """[robot3rrr]
proximal_mass_kg = 0.6
distal_mass_kg = 0.4
platform_mass_kg = 1.5
proximal_inertia_kgm2 = 0.0045
distal_inertia_kgm2 = 0.003
platform_inertia_kgm2 = 0.025
gravity_m_s2 = 9.81
"""
JOB = """[[path3rrr_sensitivity]]
from_pose = [36, 5, -2]
to_pose = [44, 9, 2]
duration_s = 0.5
steps = 20
elbow = [1, -1, -1]
joint_limits_deg = [[20, 70], [110, 160], [245, 295]]
tolerance_length_mm = 0.1
tolerance_mass_g = 20
tolerance_inertia_kgm2 = 2e-4
methods = ["sobol", "efast", "pce"]
samples = 64
output = "s.csv"
plot = "s.png"
"""
ROBOT_MODEL = Robot3RRR(
    proximal_mass_kg=0.6,
    distal_mass_kg=0.4,
    platform_mass_kg=1.5,
    proximal_inertia_kgm2=0.0045,
    distal_inertia_kgm2=0.003,
    platform_inertia_kgm2=0.025,
    gravity_m_s2=9.81,
)
NAMES = (
    "base_side_cm",
    "platform_side_cm",
    "proximal_cm",
    "distal_cm",
    "proximal_mass_kg",
    "distal_mass_kg",
    "platform_mass_kg",
    "proximal_inertia_kgm2",
    "distal_inertia_kgm2",
    "platform_inertia_kgm2",
)


def run(cli, tmp_path, text):
    preset = tmp_path / "p.toml"
    preset.write_text(text, encoding="utf-8")
    return preset, cli("run", preset, "--out-dir", tmp_path / "out")


def read(path):
    with open(path, newline="", encoding="utf-8") as handle:
        return list(csv.DictReader(handle))


def test_the_job_writes_its_tables_and_figure_and_a_fixed_orientation_leaves_out_the_inertia(
    cli, tmp_path
):
    """At a constant orientation the platform does not turn: its inertia enters no effort,
    so its Sobol' indices are exactly 0 and its PCE and eFAST ones vanish, at every step."""
    text = ROBOT + JOB.replace("[44, 9, 2]", "[44, 9, -2]")
    _, result = run(cli, tmp_path, text)
    assert result.exit_code == 0, result.output
    out = tmp_path / "out"
    main = read(out / "s.csv")
    # 6 outputs (peak and RMS of 3 actuators) x 10 inputs x 3 methods
    assert len(main) == 6 * 10 * 3
    assert {row["parameter"] for row in main} == set(NAMES)
    per_step = read(out / "s-path.csv")
    assert len(per_step) == 21 * 3 * 10 * 3
    assert {row["output"] for row in per_step} == {"tau1_Nm", "tau2_Nm", "tau3_Nm"}
    aggregated = read(out / "s-path-aggregated.csv")
    assert len(aggregated) == 4 * 10 * 3
    assert (out / "s.png").read_bytes().startswith(b"\x89PNG")
    for rows in (main, per_step):
        for row in rows:
            if row["parameter"] != "platform_inertia_kgm2" or row["S1"] == "":
                continue
            bound = {"sobol": 0.0, "pce": 1e-6, "efast": 0.02}[row["method"]]
            assert abs(float(row["S1"])) <= bound and abs(float(row["ST"])) <= bound, row
    # the platform's inertia does enter once the platform turns (the bundled path)
    (tmp_path / "t").mkdir()
    _, turning = run(cli, tmp_path / "t", ROBOT + JOB)
    assert turning.exit_code == 0, turning.output
    rows = read(tmp_path / "t" / "out" / "s-path-aggregated.csv")
    inertia = [r for r in rows if r["parameter"] == "platform_inertia_kgm2"]
    assert min(float(r["ST"]) for r in inertia if r["method"] != "efast") > 1e-6


def static_design(unit):
    """Efforts of a platform held still at one pose (gravity statics), the masses the only
    inputs (±20 g): tau = sum_b m_b G_b(pose), linear in the masses."""
    spec = Path3RRRSpec(
        from_pose=(40, 7, 0), to_pose=(40, 7, 0), duration_s=1.0, steps=4, elbow=(1, -1, -1)
    )
    inputs = robot_inputs(ROBOT_MODEL, (), 0.01, 0.02, None)
    states = path_states(spec)
    efforts = design_efforts(ROBOT_MODEL, spec, inputs, scaled(inputs, unit), states)
    return inputs, spec, states, path_outputs(efforts, states.times_s)


def test_a_purely_additive_effect_has_first_order_equal_total_the_closed_form_shares():
    """Gravity statics: each effort is linear in the masses, tau_i = sum_b c_ib m_b, so
    S1 = ST = c_ib² / sum c² (equal ranges), first-order indices summing to 1. The
    coefficients c_ib come from one massive body at a time (the mechanism alone)."""
    from planar_tui.sensitivity.engine import analyse, unit_design
    from planar_tui.sensitivity.pce import pce_indices, pce_unit_design

    inputs, spec, states, _ = static_design(np.zeros((1, 3)))
    assert [i.name for i in inputs] == ["proximal_mass_kg", "distal_mass_kg", "platform_mass_kg"]
    coefficients = []
    for body in inputs:
        alone = Robot3RRR(gravity_m_s2=9.81, **{body.field: 1.0})
        solution = MECHANISM.inverse_dynamics(
            alone, spec, states.pose, states.rate, states.acceleration
        )
        coefficients.append(solution.effort[0])
    c2 = np.array(coefficients).T ** 2  # (actuators, masses)
    expected = c2 / c2.sum(axis=1, keepdims=True)
    # peak |tau| and RMS tau of a constant effort are |tau|: the same shares
    expected = np.concatenate([expected, expected])
    for method, unit, tolerance in (
        ("pce", pce_unit_design(3, 64, 7), 1e-8),
        ("sobol", unit_design("sobol", 3, 1024, 7), 0.03),
        ("efast", unit_design("efast", 3, 1024, 7), 0.03),
    ):
        outputs = static_design(np.asarray(unit))[3][:, :6]
        if method == "pce":
            indices = pce_indices(np.asarray(unit), outputs, 7, num_resamples=1)[0]
        else:
            indices = analyse(method, outputs, 3, 7)
        np.testing.assert_allclose(indices[0], expected, atol=tolerance, err_msg=method)
        np.testing.assert_allclose(indices[2], expected, atol=tolerance, err_msg=method)
        assert np.abs(indices[0].sum(axis=1) - 1.0).max() <= 3 * tolerance


def test_pce_mean_and_variance_match_monte_carlo_of_the_same_model():
    """The PCE's mean c_0 and variance sum c_a² of the peak and RMS torques, fitted on 160
    robots, against 4096 independent uniform robots (standard errors: sigma / sqrt(N) for
    the mean, about sqrt(2 / N) relative for the variance)."""
    from planar_tui.sensitivity.engine import montecarlo_design
    from planar_tui.sensitivity.pce import fit_pce, pce_unit_design

    spec = Path3RRRSpec(
        from_pose=(36, 5, -2), to_pose=(44, 9, 2), duration_s=0.5, steps=20, elbow=(1, -1, -1)
    )
    inputs = robot_inputs(ROBOT_MODEL, ("proximal_cm", "distal_cm"), 0.05, 0.05, None)
    states = path_states(spec)

    def outputs(unit):
        efforts = design_efforts(ROBOT_MODEL, spec, inputs, scaled(inputs, unit), states)
        return path_outputs(efforts, states.times_s)[:, :6]

    unit = np.asarray(pce_unit_design(len(inputs), 160, 3))
    fit = fit_pce(unit, outputs(unit))
    sample = outputs(montecarlo_design(len(inputs), 4096, 11))
    mean, variance = sample.mean(axis=0), sample.var(axis=0, ddof=1)
    assert np.all(np.abs(fit.mean - mean) < 4 * np.sqrt(variance / 4096))
    np.testing.assert_allclose(fit.variance, variance, rtol=4 * np.sqrt(2 / 4096))


def test_sobol_efast_and_pce_agree_on_the_bundled_case(tmp_path):
    """The bundled preset's job on a coarser path: the total indices of every peak and RMS
    torque agree between the methods within Sobol's 95 % half-width (plus 0.03) and 0.05 for
    eFAST (its N = 640 per input above 4 M² (D - 1) + 1, distinct frequencies), the PCE's
    leave-one-out error below 1e-3."""
    import dataclasses

    from planar_tui.batch import prepare_jobs, run_job
    from planar_tui.presets import load_preset
    from tests.conftest import PRESETS

    (job,) = load_preset(PRESETS / "path-3rrr-sensitivity.toml").jobs
    job = dataclasses.replace(job, spec=dataclasses.replace(job.spec, steps=50))
    (ready,) = prepare_jobs([job])
    result = run_job(ready)
    by = {a.method: a for a in result.analyses}
    sobol, efast, pce = by["sobol"], by["efast"], by["pce"]
    assert pce.loo_error.max() < 1e-3
    assert np.all(np.abs(sobol.indices[2] - pce.indices[2]) <= sobol.indices[3] + 0.03)
    assert np.abs(efast.indices[2] - pce.indices[2]).max() <= 0.05
    # the masses drive the torques' peaks: the platform's mass leads every peak
    top = pce.indices[2, :3].argmax(axis=1)
    assert all(pce.names[j] == "platform_mass_kg" for j in top), top


BAD = {
    "feed forward": (JOB + "feed_forward = true\n", "feed_forward"),
    "a length tolerance of the link": (
        JOB.replace("tolerance_length_mm = 0.1", "tolerance_length_mm = 300"),
        "tolerance_length_mm",
    ),
    "a mass tolerance of the lightest body": (
        JOB.replace("tolerance_mass_g = 20", "tolerance_mass_g = 400"),
        "tolerance_mass_g",
    ),
    "samples not a power of two": (JOB.replace("samples = 64", "samples = 100"), "samples"),
    "an unknown method": (JOB.replace('"efast", ', '"fast", '), "methods"),
    "a massless robot": (JOB, "tolerance_mass_g"),
}


@pytest.mark.parametrize("case", BAD)
def test_bad_input_is_one_line_exit_2_nothing_written(cli, tmp_path, case):
    job, key = BAD[case]
    robot = "[robot3rrr]\n" if case == "a massless robot" else ROBOT
    preset, result = run(cli, tmp_path, robot + job)
    assert result.exit_code == 2, result.output
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith(f"error: {preset}: path3rrr_sensitivity[1].{key}: "), lines[0]
    assert not (tmp_path / "out").exists()


def test_a_path_the_nominal_robot_cannot_follow_fails_naming_the_first_time(cli, tmp_path):
    text = ROBOT + JOB.replace("[36, 5, -2]", "[34, 5, 0]").replace("[44, 9, 2]", "[46, 9, 0]")
    preset, result = run(cli, tmp_path, text.replace("[1, -1, -1]", "[1, -1, 1]"))
    assert result.exit_code == 1, result.output
    lines = [line for line in result.stderr.splitlines() if line.startswith("error:")]
    assert len(lines) == 1, result.stderr
    assert f"{preset}: path3rrr_sensitivity[1]: the nominal robot's path fails at t = " in lines[0]
    assert "leg 3 leaves its joint limits" in lines[0]
    assert not (tmp_path / "out" / "s.csv").exists()


def test_the_five_bar_job_spreads_each_legs_lengths_and_its_end_mass(cli, tmp_path):
    """The five-bar's inputs are its base separation, each leg's own two lengths and its
    positive masses (a massless distal link is no input): the tables have a row per
    output, input and method, and per step."""
    text = """[robot5r]
working_mode = "+-"
proximal_mass_kg = 0.5
end_mass_kg = 1.0
gravity_m_s2 = 9.81

[[path5r_sensitivity]]
from_pose = [0, 60]
to_pose = [5, 65]
steps = 20
tolerance_length_mm = 0.1
tolerance_mass_g = 20
methods = ["sobol", "pce"]
samples = 64
output = "f.csv"
"""
    _, result = run(cli, tmp_path, text)
    assert result.exit_code == 0, result.output
    rows = read(tmp_path / "out" / "f.csv")
    names = [
        "base_separation_cm",
        "proximal_cm[1]",
        "proximal_cm[2]",
        "distal_cm[1]",
        "distal_cm[2]",
        "proximal_mass_kg",
        "end_mass_kg",
    ]
    assert list(dict.fromkeys(r["parameter"] for r in rows)) == names
    # 2 actuators: peak and RMS of each, 7 inputs, 2 methods
    assert len(rows) == 4 * 7 * 2
    assert len(read(tmp_path / "out" / "f-path.csv")) == 21 * 2 * 7 * 2


def test_the_pce_bootstrap_equals_refitting_every_resample_by_least_squares():
    """The wild bootstrap's half-widths (one product per term, as a 1 000-step path needs)
    against their definition: every resample y + e ⊙ v_b refitted on each output's own
    terms by least squares, S1 and ST from the refits, z times their standard deviation."""
    from statistics import NormalDist

    from planar_tui.sensitivity.pce import bootstrap_halfwidths, fit_pce, pce_unit_design
    from planar_tui.sensitivity.pce_indices import indices_from_coefficients

    unit = np.asarray(pce_unit_design(3, 64, 5))
    x = 2.0 * unit - 1.0
    noise = np.random.default_rng(2).normal(size=(64, 2)) * 0.05
    y = np.column_stack([x[:, 0] + 0.3 * x[:, 1] ** 2, x[:, 2] * x[:, 0] + x[:, 1]]) + noise
    fit = fit_pce(unit, y)
    first, total = bootstrap_halfwidths(fit, y, 9, 50)
    signs = np.random.default_rng(9).integers(0, 2, size=(64, 50)) * 2.0 - 1.0
    residuals = y - fit.basis @ fit.coefficients
    refits = np.zeros((50, *fit.coefficients.shape))
    for b in range(50):
        for t in range(y.shape[1]):
            terms = fit.basis[:, : fit.term_counts[t]]
            target = fit.basis @ fit.coefficients[:, t] + residuals[:, t] * signs[:, b]
            refits[b, : fit.term_counts[t], t] = np.linalg.lstsq(terms, target, rcond=None)[0]
    s1, st = indices_from_coefficients(fit.indices, refits)
    z = NormalDist().inv_cdf(0.975)
    np.testing.assert_allclose(first, z * s1.std(axis=0, ddof=1), rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(total, z * st.std(axis=0, ddof=1), rtol=1e-9, atol=1e-12)
    assert first.max() > 1e-4  # a noisy fit: the half-widths are not trivially 0


@pytest.mark.parametrize("kind", ["path3rrr_sensitivity", "path5r_sensitivity"])
def test_a_horizontal_machine_at_rest_has_undefined_indices_and_the_warm_up_example_runs(
    cli, tmp_path, kind
):
    """The kinds' warm-up examples (no gravity): at both ends of a rest-to-rest path every
    robot's torques are exactly 0, outputs without variance, whose indices are undefined:
    empty cells (not 0, not NaN); so are those at mid-path, where the platform's
    acceleration vanishes on the straight path and the massless legs carry no load; at the
    other steps the torques vary and the indices do not all vanish; the aggregated indices
    stay numbers (those outputs weigh 0)."""
    from planar_tui.warmup import example

    preset = tmp_path / "w.toml"
    preset.write_text(example(kind), encoding="utf-8")
    result = cli("run", preset, "--out-dir", tmp_path / "out")
    assert result.exit_code == 0, result.output
    (per_step,) = (tmp_path / "out").glob("*-path.csv")
    rows = read(per_step)
    ends = [r for r in rows if float(r["t_s"]) in (0.0, 1.0)]  # duration_s = 1 s
    cells = ("S1", "S1_conf", "ST", "ST_conf", "percent")
    assert ends and all(r[c] == "" for r in ends for c in cells)
    inner = [r for r in rows if float(r["t_s"]) not in (0.0, 0.5, 1.0)]
    assert all(r["S1"] != "" and r["ST"] != "" for r in inner)
    assert max(float(r["ST"]) for r in inner) > 0.1
    (aggregated,) = (tmp_path / "out").glob("*-path-aggregated.csv")
    assert all(np.isfinite(float(r["ST"])) for r in read(aggregated))


def test_an_output_without_indices_is_a_dash_in_the_table_and_no_loo_cell():
    """The terminal table shows an undefined output's indices as dashes, a defined one's
    as numbers; the CSV leaves its indices and its PCE LOO error empty."""
    from rich.console import Console

    from planar_tui.sensitivity.results import Analysis, csv_table, sensitivity_percent
    from planar_tui.sensitivity.tables import VIEWS, fit_tables

    indices = np.zeros((4, 2, 2))
    indices[:, 0] = [[0.7, 0.3], [0.01, 0.01], [0.75, 0.35], [0.01, 0.01]]
    analysis = Analysis(
        "pce",
        "path",
        0.0,
        ("a_cm", "b_kg"),
        indices,
        sensitivity_percent(indices),
        ("peak", "rest"),
        loo_error=np.array([1e-4, 0.0]),
        defined=np.array([True, False]),
    )
    console = Console(width=120, record=True)
    console.print(fit_tables([analysis], VIEWS[0], 120).renderable)
    lines = {line.split()[0]: line for line in console.export_text().splitlines() if line.split()}
    assert "—" in lines["rest"] and "—" not in lines["peak"]
    rows = csv_table("r", [analysis]).rows
    assert [r[6] for r in rows] == [0.7, 0.3, "", ""]  # S1
    assert [r[-1] for r in rows] == [1e-4, 1e-4, "", ""]  # loo_error

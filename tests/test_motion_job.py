"""The ``[motion_uncertainty]`` job against known answers.

A 1-link robot in zero gravity under a constant torque from rest turns by
θ(T) = τT²/(2(I + m l²/4)) (RK4 is exact for a constant acceleration): its Monte-Carlo
mean and standard deviation and its Sobol' indices over (l, m), and over (l, m, I) with
``tolerance_inertia_kgm2``, are checked against 2-D and 3-D Gauss-Legendre quadrature of
that formula, within four standard errors of the estimator
(Sobol': twice SALib's 95 % bootstrap half-width, 1.96 standard errors); with eFAST alone
the band (from N extra Monte-Carlo robots) against the 3-D quadrature and a straight arm's
tip x = l1 + l2 against √(2/3)·tolerance, within three. A pendulum whose
inertia is m l²/12 cannot depend on m (structure zero); a robot that cannot move has
outputs without variance (zeros and a note, no NaN, no warning: the suite turns warnings
into errors); S = 1 equals the simulate job's CSV.
"""

from __future__ import annotations

import csv
import io

import numpy as np
import pytest

from planar_tui.batch import run_job
from planar_tui.motion import engine
from planar_tui.motion.runner import prepare_motion
from planar_tui.presets import parse_preset
from planar_tui.progress import Progress
from planar_tui.registry import JOB_KINDS

# 1-link, zero gravity, τ = 1 N m from rest for T = 0.5 s; l = 0.5 ± 0.2 m, m = 2 ± 1 kg;
# I = 0.01 kg m² fixed, or I = 0.1 ± 0.06 kg m² as a third input (a quarter of the variance;
# l still dominates)
L0, DL, M0, DM, INERTIA, TAU, T = 0.5, 0.2, 2.0, 1.0, 0.01, 1.0, 0.5
#: (nominal inertia, its tolerance or None) per case: inputs (l, m) or (l, m, I).
CASES = {"l-m": (INERTIA, None), "l-m-I": (0.1, 0.06)}


def job_of(robot: dict, motion: dict):
    (job,) = parse_preset("motion.toml", {"robot": robot, "motion_uncertainty": motion}).jobs
    return job


def one_link_job(methods, samples, inertia=INERTIA, tolerance_inertia=None):
    settings = {
        "duration_s": T,
        "step_s": 0.05,
        "torques_Nm": [TAU],
        "methods": methods,
        "samples": samples,
        "tolerance_length_mm": DL * 1e3,
        "tolerance_mass_g": DM * 1e3,
    }
    if tolerance_inertia is not None:
        settings["tolerance_inertia_kgm2"] = tolerance_inertia
    return job_of(
        {"lengths_m": [L0], "masses_kg": [M0], "inertias_kgm2": [inertia], "gravity_m_s2": 0.0},
        settings,
    )


def theta_closed_form(length_m, mass_kg, inertia_kgm2):
    return TAU * T**2 / (2.0 * (inertia_kgm2 + mass_kg * length_m**2 / 4.0))


def exact_moments(inertia=INERTIA, tolerance_inertia=None, points: int = 48):
    """Mean, variance, fourth central moment, first-order and total partial variances
    (per input) of θ(T) under the uniform inputs, by Gauss-Legendre quadrature on the
    (l, m) or (l, m, I) box."""
    x, w = np.polynomial.legendre.leggauss(points)
    w = w / 2.0  # the uniform density on [-1, 1]
    axes = [L0 + DL * x, M0 + DM * x]
    if tolerance_inertia is not None:
        axes.append(inertia + tolerance_inertia * x)
    d = len(axes)
    grid = np.meshgrid(*axes, indexing="ij")
    f = theta_closed_form(*grid) if d == 3 else theta_closed_form(*grid, inertia)
    weights = np.ones(())
    for _ in range(d):
        weights = np.multiply.outer(weights, w)  # the joint weights, shape (points,) * d

    def expect(values):
        return float((weights * values).sum())

    mean = expect(f)
    variance = expect((f - mean) ** 2)
    fourth = expect((f - mean) ** 4)
    first, total = [], []
    for a in range(d):
        others = tuple(i for i in range(d) if i != a)
        given_a = (weights * f).sum(axis=others) / w  # E[f | x_a]
        first.append(float(w @ (given_a - mean) ** 2))  # Var_a E[f | x_a]
        given_others = np.expand_dims(np.moveaxis(f, a, -1) @ w, a)  # E[f | x_~a]
        total.append(expect((f - given_others) ** 2))  # E_~a Var_a(f | x_~a)
    return mean, variance, fourth, tuple(first), tuple(total)


@pytest.mark.parametrize("case", CASES)
def test_montecarlo_mean_and_std_match_quadrature(case):
    inertia, tolerance_inertia = CASES[case]
    job = one_link_job(["montecarlo"], 4096, inertia, tolerance_inertia)
    result = run_job(job)
    mean, variance, fourth, _, _ = exact_moments(inertia, tolerance_inertia)
    n = result.robots
    got_mean, got_std = result.band[-1, 0, 0], result.band[-1, 1, 0]
    assert result.t_s[-1] == pytest.approx(T)
    assert abs(got_mean - mean) <= 4 * np.sqrt(variance / n)
    se_std = np.sqrt((fourth - variance**2) / (4 * variance * n))  # delta method
    assert abs(got_std - np.sqrt(variance)) <= 4 * se_std
    assert "indices" not in result.extra_tables  # Monte Carlo gives the band only


@pytest.mark.parametrize("case", CASES)
def test_sobol_indices_match_quadrature(case):
    inertia, tolerance_inertia = CASES[case]
    job = one_link_job(["sobol"], 2048, inertia, tolerance_inertia)
    result = run_job(job)
    _, variance, _, first, total = exact_moments(inertia, tolerance_inertia)
    (analysis,) = result.analyses
    assert analysis.names == ("l1", "m1", "I1")[: len(first)]
    theta = 0  # the outputs: theta1, tip x, tip y
    for j in range(len(first)):
        s1, s1_conf, st, st_conf = analysis.indices[:, theta, j]
        assert abs(s1 - first[j] / variance) <= 2 * s1_conf
        assert abs(st - total[j] / variance) <= 2 * st_conf
    assert min(first) / variance > 0.1  # every input matters: the check is not vacuous
    assert result.extra_tables["indices"].header[:4] == ("output", "t_s", "parameter", "method")
    figures = JOB_KINDS["motion_uncertainty"].point_figures(job, result)
    assert figures["theta1_rad_dominant"] == ("l1", "m1", "I1")[int(np.argmax(total))]
    assert figures["theta1_rad_mean"] == result.band[-1, 0, 0]


def test_pendulum_with_rod_inertia_does_not_depend_on_its_mass():
    """I = m l²/12 follows the sampled mass: θ̈ = -3g cos θ / (2l), free of m."""
    job = job_of(
        {"lengths_m": [0.4], "masses_kg": [1.0]},
        {
            "duration_s": 0.3,
            "step_s": 1e-3,
            "theta0_deg": [20.0],
            "methods": ["sobol", "efast"],
            "samples": 128,
            "tolerance_length_mm": 50,
            "tolerance_mass_g": 300,
        },
    )
    result = run_job(job)
    sobol, efast = result.analyses
    assert sobol.names == efast.names == ("l1", "m1")
    # Sobol': the robots of A and A_B^(m) move alike to round-off, every index of m is 0
    assert np.abs(sobol.indices[:, :, 1]).max() <= 1e-9
    # eFAST has a floor for an input that does not matter (Fourier interference, the
    # 0.4-1.2 % of paper A's Table 4 for inputs a torque cannot depend on)
    assert np.abs(efast.indices[0, :, 1]).max() <= 1e-3
    assert np.abs(efast.indices[2, :, 1]).max() <= 1e-2
    for analysis in result.analyses:
        assert analysis.indices[2, :, 0].min() > 0.9  # l does matter
    assert result.notes == ()


def test_outputs_without_variance_have_no_indices_and_a_note_not_nan():
    """Zero gravity, no torque, at rest: the joints cannot move (θ ≡ 0, tip y ≡ 0): no
    variance to apportion, so no index (empty cells, not 0)."""
    job = job_of(
        {"lengths_m": [0.3, 0.2], "masses_kg": [1.0, 0.5], "gravity_m_s2": 0.0},
        {
            "duration_s": 0.01,
            "step_s": 1e-3,
            "methods": ["montecarlo", "sobol", "efast"],
            "samples": 128,
            "at_s": [0.005, 0.01],
        },
    )
    result = run_job(job)
    table = result.extra_tables["indices"]
    text = io.StringIO()
    table.write(text)
    rows = list(csv.DictReader(io.StringIO(text.getvalue())))
    assert rows and not any("nan" in value.lower() for row in rows for value in row.values())
    for row in rows:
        if row["output"] != "tip_x_m":
            cells = (row[c] for c in ("S1", "S1_conf", "ST", "ST_conf", "percent"))
            assert set(cells) == {""}, row
    assert any(float(row["ST"]) > 0 for row in rows if row["output"] == "tip_x_m")
    assert len(result.notes) == 2 * 2 * 3  # 2 times × 2 methods × (θ1, θ2, tip y)
    assert "θ1 at t = 0.005 s does not vary over the sobol robots" in result.notes[0]
    assert result.table.first_non_finite_column() is None


def test_one_robot_equals_the_simulate_jobs_csv():
    """The engine on S = 1 robot with the nominal parameters records the simulate job's
    angles (the band of one robot is that robot): to 1e-13 relative, the lane kernel's
    ``sincos`` being within 1 ulp of the C library's."""
    robot = {"lengths_m": [0.25, 0.2, 0.15], "masses_kg": [0.484, 0.387, 0.29]}
    settings = {
        "duration_s": 0.05,
        "step_s": 1e-4,
        "theta0_deg": [10.0, -20.0, 5.0],
        "torques_Nm": [2.0, 0.3, 0.1],
        "every": 50,
    }
    (sim,) = parse_preset("s.toml", {"robot": robot, "simulate": settings}).jobs
    simulated = run_job(sim).table
    rows = np.array([[float(v) for v in r] for r in list(simulated.records())[1:]])
    motion = job_of(robot, {**settings, "methods": ["montecarlo"], "samples": 2})
    assert prepare_motion(motion).device == "cpu"
    lengths, masses, inertias = motion.robot.arrays()
    params = np.stack([lengths, masses, inertias])[None].copy()
    theta0 = np.radians(np.array(settings["theta0_deg"]))[None].copy()
    robots = engine.CpuRobots(
        params, theta0, np.zeros((1, 3)), 9.81, np.array(settings["torques_Nm"])
    )
    recorded = {}
    engine.integrate(
        robots,
        1e-4,
        motion.spec.record_steps(),
        lambda k, angles: recorded.setdefault(k, angles.copy()),
        Progress(),
    )
    assert motion.spec.record_steps() == (0, 50, 100, 150, 200, 250, 300, 350, 400, 450, 500)
    got = np.array([recorded[k][0] for k in motion.spec.record_steps()])
    assert np.abs(got - rows[:, 1:4]).max() <= 1e-13 * np.abs(rows[:, 1:4]).max()


def test_the_motion_engine_sizes_its_calls_with_the_simulate_jobs_rule(monkeypatch):
    """``integrate`` takes each call's steps from ``next_chunk_steps`` (the one home of the
    rule), clipped at the next stop, and visits every stop."""
    from planar_tui.dynamics import simulate

    asked = []

    def rule(steps, seconds, left, most=None):
        asked.append((steps, left, most))
        return 3

    monkeypatch.setattr(simulate, "next_chunk_steps", rule)

    class Robots:
        def __init__(self):
            self.blocks = [(0, 2), (2, 4)]
            self.calls = []

        def advance(self, block, step_s, n_steps):
            self.calls.append((block, n_steps))

        def angles(self):
            return np.zeros((4, 1))

    robots = Robots()
    stops = []
    engine.integrate(robots, 0.1, (0, 4, 10), lambda k, angles: stops.append(k))
    assert stops == [0, 4, 10]
    # 1 step, then the rule's 3 (the second clipped at stop 4 after 1 step: 3 left)
    assert [n for block, n in robots.calls if block == (0, 2)] == [1, 3, 3, 3]
    assert [n for block, n in robots.calls if block == (2, 4)] == [1, 3, 3, 3]
    # after each call: the steps it took, the steps to the last stop, no cap
    assert asked == [(1, 9, None), (3, 6, None), (3, 3, None), (3, 0, None)]


def test_the_band_table_is_as_wide_as_rich_draws_it():
    """The width ``band_grid`` gives (the app sizes the tables beside the plot by it) is
    Rich's own measure, and at that width no number is cut to "…"."""
    from rich.console import Console
    from rich.measure import Measurement

    from planar_tui.motion.results import band_grid

    result = run_job(one_link_job(["montecarlo"], 64))
    table, width = band_grid(result)
    console = Console(width=200, record=True, color_system=None)
    assert Measurement.get(console, console.options, table).maximum == width
    narrow = Console(width=width, record=True, color_system=None)
    narrow.print(table)
    text = narrow.export_text()
    assert "…" not in text and f"{result.band[-1, 4, 0]:.5g}" in text


# eFAST alone at N = 128 with three inputs: every input's search curve gives the other two
# the same frequency 1, so eFAST's rows correlate the inputs (r = 1/3 between every pair)
# and their standard deviation of θ(T) is 35 % high (about 4 standard errors at N = 128).
EFAST_ALONE_SAMPLES = 128


def test_efast_alone_band_matches_quadrature():
    """The band of an eFAST-only job comes from N extra Monte-Carlo robots: its mean and
    standard deviation of θ(T) match 3-D quadrature within three standard errors of N
    independent robots (eFAST's own rows are off by four)."""
    inertia, tolerance_inertia = CASES["l-m-I"]
    job = one_link_job(["efast"], EFAST_ALONE_SAMPLES, inertia, tolerance_inertia)
    result = run_job(job)
    mean, variance, fourth, _, _ = exact_moments(inertia, tolerance_inertia)
    n = EFAST_ALONE_SAMPLES
    got_mean, got_std = result.band[-1, 0, 0], result.band[-1, 1, 0]
    assert abs(got_mean - mean) <= 3 * np.sqrt(variance / n)
    se_std = np.sqrt((fourth - variance**2) / (4 * variance * n))  # delta method
    assert abs(got_std - np.sqrt(variance)) <= 3 * se_std
    assert result.robots == n * 3 + n  # eFAST's N D, and N for the band
    assert result.notes[0].startswith(f"band from {n} extra Monte-Carlo robots")
    assert "extra Monte-Carlo robots" in result.summary
    (analysis,) = result.analyses
    assert analysis.method == "efast"  # the extra robots give no indices


def test_efast_alone_band_of_a_sum_of_two_lengths():
    """A straight 2-link arm that cannot move (zero gravity, no torque, at rest) has its tip
    at x = l1 + l2: standard deviation √(2/3)·tolerance for independent uniform lengths
    (eFAST's rows give 1.22 times that at D = 4, N = 128), within three standard errors."""
    tolerance_m = 1e-3
    job = job_of(
        {"lengths_m": [0.25, 0.25], "masses_kg": [0.5, 0.5], "gravity_m_s2": 0.0},
        {
            "duration_s": 0.01,
            "step_s": 1e-3,
            "methods": ["efast"],
            "outputs": ["tip"],
            "samples": EFAST_ALONE_SAMPLES,
            "tolerance_length_mm": tolerance_m * 1e3,
        },
    )
    result = run_job(job)
    n = EFAST_ALONE_SAMPLES
    variance = 2 * tolerance_m**2 / 3
    fourth = 2.4 * variance**2  # the triangular distribution's kurtosis is 2.4
    got_mean, got_std = result.band[-1, 0, 0], result.band[-1, 1, 0]
    assert abs(got_mean - 0.5) <= 3 * np.sqrt(variance / n)
    se_std = np.sqrt((fourth - variance**2) / (4 * variance * n))
    assert abs(got_std - np.sqrt(variance)) <= 3 * se_std


def test_the_band_rows_are_uncorrelated_uniform_robots():
    """Whatever the methods, the band's rows have uncorrelated inputs (every pair's |r|
    within four standard errors, 4/√rows, of 0) and uniform means: the Monte-Carlo rows,
    the Sobol' design's A and B rows (scrambled Sobol' points), and with eFAST alone the
    extra Monte-Carlo rows (eFAST's own rows at D = 4, N = 128 have r = 0.5 between every
    pair)."""
    for methods in (["efast"], ["sobol"], ["efast", "sobol"], ["montecarlo", "efast"]):
        design = engine.build_design(methods, 4, EFAST_ALONE_SAMPLES, 42, None)
        unit = design.unit[design.band_rows()]
        correlation = np.corrcoef(unit.T)[~np.eye(4, dtype=bool)]
        assert np.abs(correlation).max() < 4 / np.sqrt(len(unit)), methods
        assert np.abs(unit.mean(axis=0) - 0.5).max() < 4 * np.sqrt(1 / 12 / len(unit)), methods


def test_the_resource_check_counts_the_band_robots_of_efast_alone():
    """eFAST alone at N = 2·10⁶ with 4 inputs: its 8·10⁶ robots × 10⁴ steps (0.93 days)
    fit the 1-day limit, the 2·10⁶ Monte-Carlo robots of the band make it 1.17 days."""
    from planar_tui.errors import PresetError

    robot = {"lengths_m": [0.25, 0.25], "masses_kg": [0.5, 0.5]}
    with pytest.raises(PresetError) as refused:
        job_of(
            robot, {"duration_s": 10.0, "step_s": 1e-3, "methods": ["efast"], "samples": 2_000_000}
        )
    assert refused.value.key == "motion_uncertainty.samples"
    assert refused.value.problem.startswith(
        "10000000 robots of 2 links × 10000 steps: needs about 1.17 days"
    )

"""The SALib hand-off: the exported runs are the job's, SALib's own estimators on them give
the job's indices back, and docs/interop.md's three lines run on them."""

from __future__ import annotations

import dataclasses
import json
import re
import warnings

import numpy as np
import pytest
from SALib.analyze import fast, sobol

from planar_tui.batch import prepare_jobs, run_job
from planar_tui.errors import PresetError
from planar_tui.interop.salib_problem import sensitivity_runs, write_problem
from planar_tui.presets import load_preset
from tests.conftest import REPO

TINY = REPO / "tests" / "data" / "app" / "tiny.toml"
INTEROP = (REPO / "docs" / "interop.md").read_text(encoding="utf-8")


@pytest.fixture(scope="module")
def sensitivity_run(tmp_path_factory):
    """The tiny preset's 2R sensitivity job (Sobol' and eFAST, N = 256), run, and its
    runs exported to ``runs/``."""
    (job,) = load_preset(TINY).jobs_of("sensitivity")
    spec = dataclasses.replace(job.spec, methods=("sobol", "efast"), samples=256)
    (job,) = prepare_jobs([dataclasses.replace(job, spec=spec)])
    result = run_job(job)
    folder = tmp_path_factory.mktemp("export")
    write_problem(folder / "runs", sensitivity_runs(job, result), {"job": job.label})
    return job, result, folder


def analysis(result, method):
    (found,) = (a for a in result.analyses if a.method == method)
    return found


def test_the_files_hold_the_problem_the_robots_and_their_torques(sensitivity_run):
    job, result, folder = sensitivity_run
    runs = folder / "runs" / "sobol"
    problem = json.loads((runs / "problem.json").read_text())
    assert problem["names"] == ["l1", "l2", "m1", "m2"]
    assert problem["outputs"] == ["tau1_Nm", "tau2_Nm"]
    nominal = [*job.robot.lengths_m, *job.robot.masses_kg]
    half = [1e-3, 1e-3, 1e-3, 1e-3]  # ±1 mm, ±1 g
    np.testing.assert_allclose(
        problem["bounds"], [[v - h, v + h] for v, h in zip(nominal, half, strict=True)]
    )
    x, y = np.load(runs / "X.npy"), np.load(runs / "Y.npy")
    assert x.shape == (256 * 6, 4) and y.shape == (256 * 6, 2)
    lower, upper = np.array(problem["bounds"]).T
    assert ((x >= lower) & (x <= upper)).all()
    # each row's torques are the inverse dynamics of that robot at the job's state
    from planar_tui.kernels.dynamics import inverse_dynamics

    theta = np.array(result.posture.theta_rad)
    for row in (0, 17, len(x) - 1):
        lengths, masses = x[row, :2], x[row, 2:]
        inertias = np.array(job.robot.inertias_kgm2)
        tau = inverse_dynamics(lengths, masses, inertias, 9.81, theta, np.ones(2), np.zeros(2))
        np.testing.assert_allclose(y[row], tau, rtol=1e-13)
    about = json.loads((runs / "run.json").read_text())
    assert (about["method"], about["samples_N"], about["seed"], about["rows"]) == (
        "sobol",
        256,
        7,
        1536,
    )
    assert "calc_second_order=False" in about["salib_analysis"]


def quiet_fast(problem, y, seed):
    """``SALib.analyze.fast.analyze`` (M = 4) without its warning about its bootstrap
    confidence intervals (only S1 and ST are compared)."""
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", "FAST confidence intervals", UserWarning)
        return fast.analyze(problem, y, M=4, seed=seed)


def test_salib_estimators_on_the_exported_runs_give_the_jobs_indices(sensitivity_run):
    """SALib's own Sobol' and FAST analyses of the files reproduce the job's S1 and ST."""
    job, result, folder = sensitivity_run
    for method, analyse in (
        ("sobol", lambda p, y: sobol.analyze(p, y, calc_second_order=False, seed=job.spec.seed)),
        ("efast", lambda p, y: quiet_fast(p, y, seed=job.spec.seed)),
    ):
        runs = folder / "runs" / method
        problem = json.loads((runs / "problem.json").read_text())
        y = np.load(runs / "Y.npy")
        ours = analysis(result, method).indices
        for k in range(y.shape[1]):
            theirs = analyse(problem, y[:, k])
            np.testing.assert_allclose(theirs["S1"], ours[0, k], rtol=1e-9, atol=1e-12)
            np.testing.assert_allclose(theirs["ST"], ours[2, k], rtol=1e-9, atol=1e-12)


def docs_example() -> str:
    start = INTEROP.index("\n## Overview\n")
    section = INTEROP[start : INTEROP.index("\n## ", start + 1)]
    block = re.search(r"```python\n(.*?)```", section, re.S)
    assert block is not None
    code = block.group(1)
    assert len(code.strip().splitlines()) == 3
    return code


def test_the_docs_example_runs_on_the_exported_runs(sensitivity_run, monkeypatch):
    """RBD-FAST on the Sobol' runs agrees loosely with the job's Sobol' indices: the same
    dominant input for each torque, every first-order index within 0.1."""
    _, result, folder = sensitivity_run
    monkeypatch.chdir(folder)
    scope: dict = {}
    exec(docs_example(), scope)
    analysed = scope["sp"].analysis
    ours = analysis(result, "sobol").indices
    for k, output in enumerate(("tau1_Nm", "tau2_Nm")):
        s1 = np.asarray(analysed[output]["S1"])
        assert s1.argmax() == ours[0, k].argmax()
        assert np.abs(s1 - ours[0, k]).max() <= 0.1


def test_an_existing_file_is_refused_before_anything_is_written(sensitivity_run, tmp_path):
    job, result, _ = sensitivity_run
    runs = sensitivity_runs(job, result)
    (tmp_path / "runs" / "efast").mkdir(parents=True)
    (tmp_path / "runs" / "efast" / "Y.npy").write_text("mine")
    with pytest.raises(PresetError) as caught:
        write_problem(tmp_path / "runs", runs, {})
    assert "exists: nothing is overwritten" in str(caught.value)
    assert "\n" not in str(caught.value)
    assert not (tmp_path / "runs" / "sobol").exists()
    assert (tmp_path / "runs" / "efast" / "Y.npy").read_text() == "mine"


def test_a_motion_jobs_runs_are_its_robots_and_their_outputs(tmp_path):
    """The Monte-Carlo file's outputs at the last time average to the job's band mean (the
    band is taken over those robots); SALib's Sobol' on the Sobol' file gives the job's
    indices."""
    from planar_tui.interop.salib_problem import motion_runs
    from planar_tui.motion.engine import montecarlo_design
    from planar_tui.presets import parse_preset

    document = {
        "robot": {"lengths_m": [0.4, 0.3], "masses_kg": [1.0, 0.8]},
        "motion_uncertainty": {
            "duration_s": 0.2,
            "step_s": 0.02,
            "torques_Nm": [2.0, 0.5],
            "samples": 64,
            "methods": ["montecarlo", "sobol"],
            "at_s": [0.1, 0.2],
            "seed": 3,
            "tolerance_length_mm": 5.0,
            "tolerance_mass_g": 50.0,
            "outputs": "tip",
        },
    }
    (job,) = parse_preset("motion.toml", document).jobs
    result = run_job(job)
    write_problem(tmp_path / "runs", motion_runs(job, result), {"job": job.label})
    runs = tmp_path / "runs"
    problem = json.loads((runs / "montecarlo" / "problem.json").read_text())
    assert problem["outputs"] == [
        "tip_x_m_at_0.1_s",
        "tip_y_m_at_0.1_s",
        "tip_x_m_at_0.2_s",
        "tip_y_m_at_0.2_s",
    ]
    x, y = np.load(runs / "montecarlo" / "X.npy"), np.load(runs / "montecarlo" / "Y.npy")
    lower, upper = np.array(problem["bounds"]).T
    np.testing.assert_array_equal(x, montecarlo_design(4, 64, 3) * (upper - lower) + lower)
    np.testing.assert_allclose(y[:, 2:].mean(axis=0), result.band[-1, 0], rtol=1e-13)
    ys = np.load(runs / "sobol" / "Y.npy")
    assert ys.shape == (64 * 6, 4)
    (last,) = (a for a in result.analyses if a.speed_rad_s == pytest.approx(0.2))
    for k in range(2):
        theirs = sobol.analyze(problem, ys[:, 2 + k], calc_second_order=False, seed=3)
        np.testing.assert_allclose(theirs["ST"], last.indices[2, k], rtol=1e-9, atol=1e-12)

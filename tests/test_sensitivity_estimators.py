"""Our jitted/vectorised estimators against SALib (the reference) on the same samples."""

import numpy as np
import pytest

from planar_tui.dynamics.robot import SerialRobot
from planar_tui.sensitivity.engine import build_problem, evaluate, scaled_design, unit_design
from planar_tui.sensitivity.estimators import efast_indices, sobol_indices
from tests.salib_reference import salib_efast_indices, salib_sobol_indices

ROBOT = SerialRobot((0.303, 0.303, 0.175), (1.126, 1.126, 0.650), (0.129, 0.129, 0.024))
POSTURE = np.radians([20.0, 120.0, 150.0])


def _torques(method, samples, seed=7):
    problem = build_problem(ROBOT, 1e-3, 1e-2)
    design = unit_design(method, problem.num_vars, samples, seed)
    return problem, evaluate(problem, design, ROBOT, POSTURE, np.full(3, 1.1), np.full(3, 0.5))


def test_scaled_design_is_salib_sampling_the_real_problem():
    from SALib.sample import fast_sampler, sobol

    problem, _ = _torques("sobol", 64)
    ours = scaled_design(problem, "sobol", 64, 3)
    theirs = sobol.sample(problem.salib(), 64, calc_second_order=False, seed=3)
    assert np.array_equal(ours, theirs)
    ours = scaled_design(problem, "efast", 100, 3)
    assert np.array_equal(ours, fast_sampler.sample(problem.salib(), 100, M=4, seed=3))


@pytest.mark.slow
@pytest.mark.parametrize("inertia_tolerance", [None, 1e-3])
def test_design_torques_equal_the_batch_kernel_on_the_scaled_design(inertia_tolerance):
    """Scaling inside the kernel is bit-identical to scaling first (SALib's arithmetic)."""
    from planar_tui.kernels.dynamics_batch import inverse_dynamics_batch

    problem = build_problem(ROBOT, 1e-3, 1e-2, inertia_tolerance)
    scaled = scaled_design(problem, "sobol", 64, 3)
    columns = [np.ascontiguousarray(scaled[:, k : k + 3]) for k in (0, 3, 6)]
    if inertia_tolerance is None:
        columns[2] = np.tile(ROBOT.arrays()[2], (len(scaled), 1))
    state = (POSTURE, np.full(3, 1.1), np.full(3, 0.5))
    expected = inverse_dynamics_batch(*columns, ROBOT.gravity_m_s2, *state)
    unit = unit_design("sobol", problem.num_vars, 64, 3)
    assert np.array_equal(evaluate(problem, unit, ROBOT, *state), expected)


@pytest.mark.filterwarnings("ignore:The balance properties of Sobol' points")  # N = 300, 127
@pytest.mark.parametrize("seed", [1, 42])
@pytest.mark.parametrize(
    ("method", "samples", "ours", "salib"),
    [
        ("sobol", 512, sobol_indices, salib_sobol_indices),
        ("sobol", 300, sobol_indices, salib_sobol_indices),
        ("sobol", 127, sobol_indices, salib_sobol_indices),
        ("efast", 300, efast_indices, salib_efast_indices),
        ("efast", 301, efast_indices, salib_efast_indices),
    ],
)
def test_estimators_equal_salib(seed, method, samples, ours, salib):
    """Point estimates to 1e-12; with SALib's bootstrap draws the half-widths too. At
    awkward sizes too: at N = 512 a Sobol' design's A and B have nearly equal means, so
    a variance of A ∪ B about the mean of A alone differs by 1e-14 there, by 5e-6 at
    N = 300; eFAST at odd N (its frequency ω and spectrum length change)."""
    problem, torques = _torques(method, samples)
    np.testing.assert_allclose(
        ours(torques, problem.num_vars, seed),
        salib(problem.salib(), torques, seed),
        rtol=0,
        atol=1e-12,
    )


def test_sobol_bootstrap_is_statistically_consistent_across_seeds():
    """Half-widths from independent bootstrap draws agree to sampling error (R = 100:
    the relative sd of a sample sd is about 1/sqrt(2 (R-1)) = 7 %)."""
    problem, torques = _torques("sobol", 1024)
    widths = np.array([sobol_indices(torques, problem.num_vars, s)[[1, 3]] for s in (1, 2, 3)])
    big = widths[0] > 1e-3
    ratio = widths[1:, big] / widths[0, big]
    assert np.all((ratio > 0.6) & (ratio < 1.6))
    assert np.median(np.abs(ratio - 1)) < 0.15


def test_sobol_half_width_covers_the_error_against_a_large_run():
    """95 % half-widths at N = 1024 should cover |S(1024) − S(65536)| for most indices."""
    problem, small = _torques("sobol", 1024)
    _, large = _torques("sobol", 65536, seed=11)
    a = sobol_indices(small, problem.num_vars, 5)
    b = sobol_indices(large, problem.num_vars, 5)
    covered = np.abs(a[[0, 2]] - b[[0, 2]]) <= a[[1, 3]] + b[[1, 3]] + 1e-12
    assert covered.mean() >= 0.9


#: Compiles both Sobol' point estimators into an empty cache; prints how many signatures
#: their shared helpers were compiled for, then the estimates' bytes' hash.
HELPER_SIGNATURES = """
from planar_tui.runtime import prepare_kernels
prepare_kernels()
import hashlib
import numpy as np
from planar_tui.kernels import sensitivity_estimators as e
outputs = np.random.default_rng(3).normal(size=(5 * 64, 2))
point, _ = e.sobol_point_and_terms(outputs, 3)
serial = e.sobol_point(outputs, 3)
assert np.array_equal(point, serial)
print(len(e._ratio.signatures), len(e._standardise_into.signatures))
"""


@pytest.mark.slow
def test_the_sobol_helpers_compile_once_for_both_estimators(tmp_path):
    """A literal True/False argument and a prange (uint64) index against a range (int64)
    one each made numba compile a helper twice."""
    import os
    import subprocess
    import sys

    from tests.conftest import REPO

    env = {**os.environ, "PYTHONPATH": str(REPO), "NUMBA_CACHE_DIR": str(tmp_path)}
    result = subprocess.run(
        [sys.executable, "-c", HELPER_SIGNATURES],
        env=env,
        timeout=900,
        capture_output=True,
        text=True,
    )
    assert result.returncode == 0, result.stderr
    assert result.stdout.split() == ["1", "1"]

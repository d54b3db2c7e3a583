"""Isotropic posture solver: closed-form designs, refusal, explicit postures."""

import math

import numpy as np
import pytest

from planar_tui.sensitivity.postures import (
    NoIsotropicPosture,
    condition_number,
    explicit_posture,
    isotropic_posture,
    jacobian,
    minimum_condition,
)


def test_jacobian_2r_matches_hand_formula():
    l1, l2, t1, t2 = 0.3, 0.2, 0.4, 1.1
    hand = np.array(
        [
            [-l1 * math.sin(t1) - l2 * math.sin(t1 + t2), -l2 * math.sin(t1 + t2)],
            [l1 * math.cos(t1) + l2 * math.cos(t1 + t2), l2 * math.cos(t1 + t2)],
        ]
    )
    np.testing.assert_allclose(jacobian([l1, l2], [t1, t2]), hand, atol=1e-15)


def test_2r_isotropic_design_l2_is_l1_over_sqrt2_at_135_degrees():
    l1 = 0.303
    posture = isotropic_posture([l1, l1 / math.sqrt(2)])
    assert posture.condition_number == pytest.approx(1.0, abs=1e-9)
    assert math.degrees(posture.theta_rad[1]) == pytest.approx(135.0, abs=1e-5)
    # and directly: kappa = 1 at theta2 = -135 too (mirror image)
    j = jacobian([l1, l1 / math.sqrt(2)], [0.3, math.radians(-135)])
    assert condition_number(j) == pytest.approx(1.0, abs=1e-12)


def test_paper_2r_is_isotropic_within_rounding():
    posture = isotropic_posture([0.303, 0.214])  # 0.214 = 0.303/√2 rounded
    assert 1.0 < posture.condition_number < 1.002


def test_3r_isotropic_design_is_equilateral_triangle():
    """l1 = l2 = √3 l3, θ = (0, 120°, 150°), L = l3/√2 gives J Jᵀ = 3 I exactly."""
    l3 = 0.175
    lengths = [math.sqrt(3) * l3, math.sqrt(3) * l3, l3]
    j = jacobian(lengths, np.radians([0, 120, 150]), l3 / math.sqrt(2))
    np.testing.assert_allclose(j @ j.T, 3 * np.eye(3), atol=1e-12)
    posture = isotropic_posture(lengths)
    assert posture.condition_number == pytest.approx(1.0, abs=1e-6)
    np.testing.assert_allclose(np.degrees(posture.theta_rad), [0, 120, 150], atol=1e-4)
    assert posture.characteristic_length_m == pytest.approx(l3 / math.sqrt(2), rel=1e-6)


@pytest.mark.parametrize("lengths", [[0.303, 0.151], [0.303, 0.151, 0.2], [0.5, 0.1, 0.1]])
def test_no_isotropic_posture_is_refused_with_the_condition_number(lengths):
    with pytest.raises(NoIsotropicPosture, match="minimum condition number"):
        isotropic_posture(lengths)


def test_explicit_posture_label_and_angles():
    posture = explicit_posture([0, 45, -90], [0.3, 0.3, 0.2])
    assert posture.label == "theta_deg=0/45/-90"
    np.testing.assert_allclose(posture.theta_rad, np.radians([0, 45, -90]))
    assert posture.condition_number > 1


def _kappa(lengths, theta, length=None):
    return condition_number(jacobian(lengths, theta, length))


@pytest.mark.parametrize("lengths", [[0.303, 0.214], [0.3, 0.5], [0.5, 0.1], [0.2, 0.2]])
def test_2r_closed_form_matches_scipy_bounded_search(lengths):
    """Independent method: scipy's bounded scalar minimiser of κ(θ2) on (0, π)."""
    from scipy.optimize import minimize_scalar

    kappa, theta, length = minimum_condition(tuple(lengths))
    fit = minimize_scalar(
        lambda t: _kappa(lengths, [0.0, t]),
        bounds=(1e-3, math.pi - 1e-3),
        method="bounded",
        options={"xatol": 1e-12},
    )
    assert length is None
    assert kappa == pytest.approx(fit.fun, rel=1e-9)
    assert theta[1] == pytest.approx(fit.x, abs=1e-4)  # κ is flat at its minimum
    assert kappa <= fit.fun + 1e-12  # the closed form is the exact minimum


@pytest.mark.slow
@pytest.mark.parametrize(
    "lengths", [[0.303, 0.303, 0.175], [0.303, 0.151, 0.2], [0.5, 0.1, 0.1], [0.4, 0.3, 0.3]]
)
def test_3r_minimum_condition_matches_scipy_multistart(lengths):
    """Independent method: scipy's Nelder-Mead and Powell on κ(θ2, θ3, log L) from a grid of
    starts; ours (own Levenberg-Marquardt + Nelder-Mead) must reach the same minimum."""
    from scipy.optimize import minimize

    def kappa_of(v):
        return _kappa(lengths, [0.0, v[0], v[1]], math.exp(v[2]))

    best = math.inf
    for t2 in (60, 150, -100):
        for t3 in (90, -120):
            for method in ("Nelder-Mead", "Powell"):
                start = [math.radians(t2), math.radians(t3), math.log(0.2)]
                tolerances = {"xatol": 1e-10, "fatol": 1e-14}
                if method == "Powell":
                    tolerances = {"xtol": 1e-10, "ftol": 1e-14}
                fit = minimize(kappa_of, start, method=method, options=tolerances)
                best = min(best, fit.fun)
    kappa, theta, length = minimum_condition(tuple(lengths))
    assert kappa == pytest.approx(_kappa(lengths, theta, length), rel=1e-12)  # as reported
    assert kappa == pytest.approx(best, rel=1e-6)


def test_parse_time_solve_imports_no_scipy():
    """The isotropic check runs before every job (batch.prepare_jobs): it must stay light
    (no scipy)."""
    import subprocess
    import sys

    from tests.conftest import REPO

    probe = (
        "import sys\nfrom planar_tui.sensitivity.postures import isotropic_posture\n"
        "isotropic_posture([0.303, 0.303, 0.175]); isotropic_posture([0.303, 0.214])\n"
        "print('scipy' in sys.modules)\n"
    )
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, cwd=REPO)
    assert out.stdout.strip() == "False", out.stderr

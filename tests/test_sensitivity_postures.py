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

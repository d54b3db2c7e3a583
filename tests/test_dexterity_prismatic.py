"""Dexterous regions of the 3-RPR and 3-PRR against finite differences of their actuated
joints: the 3-RPR's leg lengths :math:`\\rho_i = |p + R q_i - A_i|`, the 3-PRR's slider
positions (the circle of the distal link about :math:`C_i` met with the slider's line, on
the mode's side), both by plain float geometry; the checks of :mod:`tests.test_dexterity`
(samples of dexterous boxes, dexterous grid points kept, the bracket) and their failure when
the κ enclosure is shrunk by 1 %."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tests.test_dexterity import (
    check_bracket,
    check_dexterous_points_kept,
    check_inside_boxes,
    run,
    shrunk,
)

RPR = """
[robot3rpr]
base_joints_cm = [[0, 0], [120, 0], [60, 103.92]]
platform_points_cm = [[0, 23.09], [-20, -11.55], [20, -11.55]]
[[workspace3rpr]]
leg_limits_cm = [[20, 100], [20, 100], [20, 100]]
precision_cm = {precision}
geometric_reference = false
kappa_max = 1.2
characteristic_length_cm = 25
output = "rpr.csv"
"""
PRR = """
[robot3prr]
[[workspace3prr]]
precision_cm = {precision}
geometric_reference = false
kappa_max = 6
output = "prr.csv"
"""


def rpr_actuators(job):
    """``(x, y, phi) -> (valid, rho (3, ...))``."""
    robot, limits = job.robot, job.spec.leg_limits_cm

    def actuators(x, y, phi):
        valid, out = np.ones(np.shape(x), dtype=bool), []
        for (ax, ay), (qx, qy), (lo, hi) in zip(
            robot.base_joints_cm, robot.platform_points_cm, limits, strict=True
        ):
            rho = np.hypot(
                x + np.cos(phi) * qx - np.sin(phi) * qy - ax,
                y + np.sin(phi) * qx + np.cos(phi) * qy - ay,
            )
            valid &= (lo <= rho) & (rho <= hi)
            out.append(rho)
        return valid, np.array(out)

    return actuators


def prr_actuators(job, modes):
    """``(x, y, phi) -> (valid, s (3, ...))``: the slider where the distal link's circle
    about C_i meets the line B_i + s u_i, the root of sign ``modes[i]``."""
    robot = job.robot

    def actuators(x, y, phi):
        valid, out = np.ones(np.shape(x), dtype=bool), []
        for (bx, by), angle, (lo, hi), length, (qx, qy), sign in zip(
            robot.slider_points_cm,
            robot.slider_angles_deg,
            robot.strokes_cm,
            robot.distal_cm,
            robot.platform_points_cm,
            modes,
            strict=True,
        ):
            ux, uy = math.cos(math.radians(angle)), math.sin(math.radians(angle))
            cx = x + np.cos(phi) * qx - np.sin(phi) * qy - bx
            cy = y + np.sin(phi) * qx + np.cos(phi) * qy - by
            along = cx * ux + cy * uy  # |B + s u - C|^2 = l^2: s^2 - 2 s along + |c|^2 - l^2
            disc = along**2 - (cx**2 + cy**2 - length**2)
            s = along + sign * np.sqrt(np.maximum(disc, 0.0))
            valid &= (disc > 0) & (lo <= s) & (s <= hi)
            out.append(s)
        return valid, np.array(out)

    return actuators


def kappa_reference(actuators, x, y, length_cm, step_cm=1e-6):
    """Validity and κ of :math:`J^{-1} = \\partial q / \\partial(x, y, L\\varphi)`."""
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    valid, _ = actuators(x, y, 0.0)
    columns = []
    for dx, dy, dphi in ((step_cm, 0, 0), (0, step_cm, 0), (0, 0, step_cm / length_cm)):
        ahead, behind = actuators(x + dx, y + dy, dphi)[1], actuators(x - dx, y - dy, -dphi)[1]
        columns.append((ahead - behind) / (2 * step_cm))
    inverse = np.moveaxis(np.array(columns), (0, 1), (-1, -2))
    sigma = np.linalg.svd(inverse, compute_uv=False)
    with np.errstate(divide="ignore", invalid="ignore"):
        kappa = sigma[..., 0] / sigma[..., -1]
    return valid, np.where(np.isfinite(kappa), kappa, np.inf)


def patched(monkeypatch, actuators):
    """Point :mod:`tests.test_dexterity`'s checks at this robot's reference."""
    import tests.test_dexterity as base

    monkeypatch.setattr(
        base,
        "kappa_reference",
        lambda legs, x, y, length, step_cm=1e-6: kappa_reference(actuators, x, y, length, step_cm),
    )


def prr_modes(job):
    from planar_tui.workspace.prr.dexterity import working_modes

    return working_modes(job.job, job.prepared)


@pytest.mark.parametrize("robot", ["rpr", "prr"])
def test_the_region_against_the_reference(tmp_path, monkeypatch, robot):
    text = (RPR if robot == "rpr" else PRR).format(precision=0.5)
    job, result = run(tmp_path, text)
    actuators = rpr_actuators(job) if robot == "rpr" else prr_actuators(job, prr_modes(job))
    patched(monkeypatch, actuators)
    outcome = result.dexterity
    assert outcome.area_inside_cm2 > 0.0
    check_inside_boxes(outcome, None, 25.0)
    check_dexterous_points_kept(outcome, None, 25.0, 0.25)
    check_bracket(outcome, None, 25.0, 0.1)


@pytest.mark.parametrize("robot", ["rpr", "prr"])
def test_the_check_fails_with_a_shrunk_enclosure(tmp_path, monkeypatch, robot):
    shrunk(monkeypatch, 1.0, 0.99)
    text = (RPR if robot == "rpr" else PRR).format(precision=0.1)
    job, result = run(tmp_path, text)
    actuators = rpr_actuators(job) if robot == "rpr" else prr_actuators(job, prr_modes(job))
    patched(monkeypatch, actuators)
    with pytest.raises(AssertionError, match="are not dexterous"):
        check_inside_boxes(result.dexterity, None, 25.0)

"""Torques along a quintic rest-to-rest path (:mod:`planar_tui.sensitivity.path`).

The path against its defining conditions (ends, rest, derivatives by finite differences);
the torques of sampled robots against the one-robot many-states inverse dynamics
(``kernels.dynamics_batch.inverse_dynamics_batch_states``, another kernel than the design's) at
the path's states; peak and RMS against direct NumPy sums; the PCE indices of the peak and
RMS torques against Saltelli's estimate on the same robots' model.
"""

from __future__ import annotations

import numpy as np
import pytest
from planar_tui.kernels.dynamics_batch import inverse_dynamics_batch_states

from planar_tui.dynamics.robot import SerialRobot
from planar_tui.sensitivity import pce
from planar_tui.sensitivity.engine import analyse, build_problem, unit_design
from planar_tui.sensitivity.path import path_torques, peak_and_rms, quintic_path

ROBOT = SerialRobot((0.3, 0.25, 0.2), (1.2, 0.9, 0.5), (0.02, 0.01, 0.005))
START = np.radians([0.0, 30.0, -20.0])
END = np.radians([60.0, -45.0, 90.0])


def test_quintic_path_is_rest_to_rest_and_consistent():
    path = quintic_path(START, END, 1.5, 3000)
    assert path.t_s[0] == 0.0 and path.t_s[-1] == 1.5
    assert np.array_equal(path.theta_rad[0], START)
    assert path.theta_rad[-1] == pytest.approx(END, abs=1e-15)
    for rates in (path.omega_rad_s, path.alpha_rad_s2):
        assert np.abs(rates[[0, -1]]).max() <= 1e-12
    dt = path.t_s[1]
    speed = np.gradient(path.theta_rad, dt, axis=0)
    assert np.abs(speed - path.omega_rad_s)[1:-1].max() <= 1e-5
    accel = np.gradient(path.omega_rad_s, dt, axis=0)
    assert np.abs(accel - path.alpha_rad_s2)[1:-1].max() <= 1e-4
    mid = path.theta_rad[1500]  # symmetric profile: half way at half time
    assert mid == pytest.approx((START + END) / 2, abs=1e-12)


def test_path_torques_equal_the_inverse_dynamics_at_the_path_states():
    problem = build_problem(ROBOT, 5e-3, 50e-3)
    unit = pce.pce_unit_design(problem.num_vars, 8, 42)
    path = quintic_path(START, END, 0.8, 40)
    torques = path_torques(problem, np.ascontiguousarray(unit), ROBOT, path)
    values = unit * (problem.upper - problem.lower) + problem.lower
    inertias = np.array(ROBOT.inertias_kgm2)
    for s, row in enumerate(values):
        expected = inverse_dynamics_batch_states(
            row[:3].copy(),
            row[3:].copy(),
            inertias,
            9.81,
            path.theta_rad,
            path.omega_rad_s,
            path.alpha_rad_s2,
        )
        assert np.abs(torques[s] - expected).max() <= 1e-12 * np.abs(expected).max()
    peak, rms = peak_and_rms(torques, path.t_s)
    assert peak == pytest.approx(np.abs(torques).max(axis=1))
    squares = torques**2
    trapezoid = ((squares[:, 1:] + squares[:, :-1]) / 2 * np.diff(path.t_s)[None, :, None]).sum(1)
    assert rms == pytest.approx(np.sqrt(trapezoid / 0.8), rel=1e-12)


def test_pce_indices_of_peak_and_rms_agree_with_saltelli():
    """Wide tolerances (±30 mm, ±0.3 kg): PCE at its default runs against Saltelli at
    N = 4096 (2·10⁴ runs), within 0.01 and 3 Sobol' half-widths."""
    problem = build_problem(ROBOT, 30e-3, 0.3)
    d = problem.num_vars
    path = quintic_path(START, END, 0.8, 20)

    def outputs(unit):
        peak, rms = peak_and_rms(path_torques(problem, unit, ROBOT, path), path.t_s)
        return np.concatenate([peak, rms], axis=1)

    design = pce.pce_unit_design(d, pce.default_pce_samples(d), 42)
    chaos, fits = pce.pce_indices(design, outputs(np.ascontiguousarray(design)), 42)
    saltelli = analyse("sobol", outputs(unit_design("sobol", d, 4096, 42)), d, 42)
    for index, half in ((0, 1), (2, 3)):
        error = np.abs(chaos[index] - saltelli[index])
        assert error.max() <= 0.01
        assert np.all(error <= 3 * saltelli[half] + 1e-3)
    assert max(fit.loo_error.max() for fit in fits) < 1e-3

"""The batched RK4 of the motion uncertainty job: S = 1 equals ``rk4_integrate`` to the
last bit, parameters are SALib's scaling (``SALib.util.scale_samples``; D = 2n and, with
the inertias as inputs, D = 3n), free fall keeps every robot's energy, and the CUDA kernel
(numba's CUDA simulator, in a subprocess) equals the CPU kernel for D = 2n and D = 3n."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import numpy as np
import pytest
from planar_tui.kernels.dynamics import energies
from planar_tui.kernels.motion_rk4 import design_parameters, rk4_batch
from planar_tui.kernels.rk4 import rk4_integrate

TABLE1 = (
    np.array([0.25, 0.25, 0.20, 0.20, 0.15, 0.15]),
    np.array([0.484, 0.484, 0.387, 0.387, 0.290, 0.290]),
    np.array([2.54e-3, 2.54e-3, 1.31e-3, 1.31e-3, 5.61e-4, 5.61e-4]),
)
TORQUES = np.array([2.0, 0.3, 0.1, 0.03, 0.03, 0.001])


def test_one_robot_equals_rk4_integrate_to_the_last_bit():
    lengths, masses, inertias = TABLE1
    theta0 = np.radians([10.0, -20, 30, 0, 5, 15])
    omega0 = np.radians([5.0, 0, -3, 1, 0, 2])
    n_steps, step_s = 300, 1e-4
    theta, omega = theta0.copy(), omega0.copy()
    rows = n_steps + 1
    records = [
        np.empty(rows),
        np.empty((rows, 6)),
        np.empty((rows, 6)),
        np.empty(rows),
        np.empty(rows),
    ]
    rk4_integrate(
        lengths, masses, inertias, 9.81, TORQUES, theta, omega, step_s, n_steps, 1, 0, *records
    )
    params = np.stack([lengths, masses, inertias])[None].copy()
    batch_theta, batch_omega = theta0[None].copy(), omega0[None].copy()
    for chunk in (1, 99, 200):  # chunked in time: the same bits
        rk4_batch(params, 9.81, TORQUES, batch_theta, batch_omega, step_s, chunk)
    assert np.array_equal(batch_theta[0], theta)
    assert np.array_equal(batch_omega[0], omega)


def test_parameters_are_salib_scaling_and_rod_inertias_follow_the_sample():
    rng = np.random.default_rng(3)
    unit = rng.random((40, 4))
    lower = np.array([0.29, 0.19, 0.9, 0.7])
    upper = np.array([0.31, 0.21, 1.1, 0.9])
    nominal_inertia = np.array([0.05, 0.002])
    params = design_parameters(unit, lower, upper, nominal_inertia, np.array([True, False]))
    scaled = unit * (upper - lower) + lower  # SALib.util.scale_samples
    assert np.array_equal(params[:, 0], scaled[:, :2])
    assert np.array_equal(params[:, 1], scaled[:, 2:])
    assert np.array_equal(params[:, 2, 0], scaled[:, 2] * scaled[:, 0] * scaled[:, 0] / 12.0)
    assert np.all(params[:, 2, 1] == 0.002)


def salib_scaled(unit, lower, upper):
    from SALib.util import scale_samples

    bounds = [[lo, hi] for lo, hi in zip(lower, upper, strict=True)]
    return scale_samples(unit.copy(), {"num_vars": len(lower), "bounds": bounds})


def test_parameters_are_salib_scaling_with_inertias_as_inputs():
    """D = 3n: the inertias are the design's last n columns, scaled like the others; a
    rod's m l²/12 and the nominal inertias are not used."""
    rng = np.random.default_rng(4)
    unit = rng.random((40, 6))
    lower = np.array([0.29, 0.19, 0.9, 0.7, 0.004, 0.001])
    upper = np.array([0.31, 0.21, 1.1, 0.9, 0.012, 0.003])
    nominal_inertia = np.array([0.008, 0.002])
    params = design_parameters(unit, lower, upper, nominal_inertia, np.array([True, False]))
    scaled = salib_scaled(unit, lower, upper)
    assert np.array_equal(params[:, 0], scaled[:, 0:2])
    assert np.array_equal(params[:, 1], scaled[:, 2:4])
    assert np.array_equal(params[:, 2], scaled[:, 4:6])
    assert len(np.unique(params[:, 2, 0])) == 40  # sampled, not one nominal value


def test_free_fall_keeps_every_robots_energy():
    rng = np.random.default_rng(7)
    lengths, masses, inertias = TABLE1
    samples = 12
    params = np.stack([lengths, masses, inertias])[None] * rng.uniform(0.9, 1.1, (samples, 3, 6))
    theta = np.tile(np.radians([30.0, -10, 20, 5, -15, 10]), (samples, 1))
    omega = np.zeros((samples, 6))
    before = [energies(*params[s], 9.81, theta[s], omega[s]) for s in range(samples)]
    rk4_batch(params, 9.81, np.zeros(6), theta, omega, 1e-4, 2000)  # 0.2 s of free fall
    assert np.abs(theta).max() > 0.1  # it moved
    for s in range(samples):
        after = energies(*params[s], 9.81, theta[s], omega[s])
        assert abs(sum(after) - sum(before[s])) <= 1e-9


SIMULATED = """
import json, sys, numpy as np
from planar_tui.kernels import motion_cuda, motion_rk4
rng = np.random.default_rng(5)
num_vars = int(sys.argv[1])  # 4: lengths, masses; 6: and inertias
unit = rng.random((6, num_vars))
lower = np.array([0.29, 0.19, 0.9, 0.7, 0.006, 0.002][:num_vars])
upper = lower + np.array([0.02, 0.02, 0.02, 0.02, 0.008, 0.004][:num_vars])
inertias = np.array([0.01, 0.004]); rod = np.array([True, False])
theta = np.tile(np.radians([20.0, -30.0]), (6, 1)); omega = np.zeros((6, 2))
torque = np.array([1.5, 0.2])
batch = motion_cuda.CudaBatch(unit, lower, upper, inertias, rod, theta, omega, 9.81, torque)
batch.advance(1e-3, 7); batch.advance(1e-3, 8)
params = motion_rk4.design_parameters(unit, lower, upper, inertias, rod)
motion_rk4.rk4_batch(params, 9.81, torque, theta, omega, 1e-3, 15)
print(json.dumps({"params": bool(np.array_equal(params, batch.parameters())),
                  "error": float(np.abs(batch.angles() - theta).max()),
                  "moved": float(np.abs(theta - np.radians([20.0, -30.0])).max()),
                  "inertias": params[:, 2].tolist(),
                  "usable": motion_cuda.usable()}))
"""


@pytest.mark.slow
@pytest.mark.parametrize("num_vars", [4, 6], ids=["lengths-masses", "with-inertias"])
def test_cuda_kernel_on_the_simulator_equals_the_cpu_kernel(num_vars):
    """numba's CUDA simulator must be on before numba.cuda is imported: a fresh process."""
    env = {**os.environ, "NUMBA_ENABLE_CUDASIM": "1"}
    done = subprocess.run(
        [sys.executable, "-c", SIMULATED, str(num_vars)],
        env=env,
        capture_output=True,
        text=True,
        check=True,
    )
    report = json.loads(done.stdout.strip().splitlines()[-1])
    assert report["usable"] is None
    assert report["params"]  # made on the "GPU" from the unit design: the same bits
    assert report["moved"] > 1e-3
    assert report["error"] <= 1e-13
    inertias = np.array(report["inertias"])
    if num_vars == 6:  # the design's columns 4 and 5, scaled (independent of the kernels)
        rng = np.random.default_rng(5)
        unit = rng.random((6, 6))
        lower = np.array([0.006, 0.002])
        upper = lower + np.array([0.008, 0.004])
        assert np.array_equal(inertias, unit[:, 4:] * (upper - lower) + lower)
    else:  # link 1 a rod (m l²/12 of its sample), link 2 its nominal inertia
        assert np.all(inertias[:, 1] == 0.004) and len(np.unique(inertias[:, 0])) == 6

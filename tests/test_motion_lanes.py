"""The lane-batched RK4 (kernels/motion_lanes.py) and its vector sin/cos (kernels/lane_trig.py).

Oracles: the scalar kernels (``rk4_batch``, one robot at a time, NOC or articulated-body
forward dynamics with the C library's sin/cos), MuJoCo's RK4, energy conservation, and for
``sincos`` the C library's ``sin``/``cos`` (and mpmath at a few hard angles).
"""

from __future__ import annotations

import mpmath
import numpy as np
import pytest
from planar_tui.kernels.aba_planar import ABA_MIN_LINKS
from planar_tui.kernels.dynamics import energies
from planar_tui.kernels.lane_trig import SINCOS_MAX_ABS, sincos
from planar_tui.kernels.motion_lanes import FUSED_LINKS, LANES, rk4_lanes, rk4_lanes_general
from planar_tui.kernels.motion_lanes_codegen import fused_source
from planar_tui.kernels.motion_rk4 import design_parameters, rk4_batch

from benchmarks.mujoco_model import chain_model
from tests.test_motion_kernels import TABLE1, TORQUES


def table1_params(robots: int, seed: int = 1) -> np.ndarray:
    """Table 1 robots: every length ± 1 mm, every mass ± 10 g (paper-a-table1-motion)."""
    lengths, masses, inertias = TABLE1
    unit = np.random.default_rng(seed).random((robots, 12))
    centre = np.concatenate([lengths, masses])
    half = np.concatenate([np.full(6, 1e-3), np.full(6, 1e-2)])
    return design_parameters(unit, centre - half, centre + half, inertias, np.zeros(6, bool))


def ulp_steps(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """How many doubles apart a and b are (ordered integer view of the bits)."""
    ia, ib = a.view(np.int64), b.view(np.int64)
    ia = np.where(ia < 0, np.int64(-(2**63)) - ia, ia)
    ib = np.where(ib < 0, np.int64(-(2**63)) - ib, ib)
    return np.abs(ia - ib)


def test_sincos_is_within_one_ulp_of_the_c_library():
    rng = np.random.default_rng(21)
    angles = np.concatenate(
        [
            rng.uniform(-10.0, 10.0, 300_000),
            rng.uniform(-1e5, 1e5, 300_000),
            rng.uniform(-SINCOS_MAX_ABS, SINCOS_MAX_ABS, 300_000),
            np.arange(-3000, 3000) * (np.pi / 2),  # next to multiples of pi/2 (cancellation)
            np.nextafter(np.arange(-3000, 3000) * (np.pi / 2), np.inf),
            [0.0, -0.0, 1e-300, 5e-324, 1e-8, np.pi / 4, -np.pi / 4],
        ]
    )
    pairs = np.array([sincos(x) for x in angles[::97]])  # the compiled kernel, from Python
    assert ulp_steps(pairs[:, 0], np.sin(angles[::97])).max() <= 1
    from numba import njit

    @njit
    def many(x, s, c):
        for i in range(x.shape[0]):
            s[i], c[i] = sincos(x[i])

    s, c = np.empty_like(angles), np.empty_like(angles)
    many(angles, s, c)
    assert ulp_steps(s, np.sin(angles)).max() <= 1
    assert ulp_steps(c, np.cos(angles)).max() <= 1
    assert (ulp_steps(s, np.sin(angles)) > 0).mean() < 0.05  # mostly the same double


def test_sincos_with_fused_multiply_adds_is_within_one_ulp_of_the_c_library():
    """The fused lane kernel (``kernels/motion_lanes_n6.py``) is compiled with FMA
    contraction, which also applies to the ``sincos`` inlined into it."""
    from numba import njit

    @njit(fastmath={"contract"})
    def many(x, s, c):
        for i in range(x.shape[0]):
            s[i], c[i] = sincos(x[i])

    rng = np.random.default_rng(6)
    angles = np.concatenate(
        [
            rng.uniform(-10.0, 10.0, 200_000),
            rng.uniform(-SINCOS_MAX_ABS, SINCOS_MAX_ABS, 200_000),
            np.nextafter(np.arange(-3000, 3000) * (np.pi / 2), np.inf),
        ]
    )
    s, c = np.empty_like(angles), np.empty_like(angles)
    many(angles, s, c)
    assert ulp_steps(s, np.sin(angles)).max() <= 1
    assert ulp_steps(c, np.cos(angles)).max() <= 1
    asm = next(iter(many.inspect_asm().values()))
    assert "vfmadd" in asm or "vfnmadd" in asm or "vfmsub" in asm  # contraction took place


def test_the_checked_in_fused_kernel_is_the_generators_output():
    from pathlib import Path

    import planar_tui.kernels.motion_lanes_n6 as generated

    assert Path(generated.__file__).read_text() == fused_source(FUSED_LINKS, LANES)
    assert generated.LANES == LANES


def test_sincos_against_mpmath_at_hard_angles():
    """Angles whose reduction cancels most bits (next to multiples of pi/2, and a known hard
    case for a two-part pi/2): the error against the exact value is below 1 ulp."""
    mpmath.mp.prec = 200
    for x in (np.pi / 2, np.pi, 3 * np.pi / 2, 1e5 * np.pi, 54349.67809094611, 1647000.0):
        s, c = sincos(x)
        exact_s, exact_c = mpmath.sin(mpmath.mpf(x)), mpmath.cos(mpmath.mpf(x))
        assert abs(mpmath.mpf(s) - exact_s) <= np.spacing(abs(float(exact_s)))
        assert abs(mpmath.mpf(c) - exact_c) <= np.spacing(abs(float(exact_c)))


def test_lanes_equal_the_scalar_kernel_after_one_second_on_table1_robots():
    """Paper A Table 1 torques, 1 s at 1e-4 s, LANES + 6 robots (a full block and a partial
    one): every angle and rate within 1e-12 relative of the scalar kernel's."""
    params = table1_params(LANES + 6)
    shape = (len(params), 6)
    theta, omega = np.zeros(shape), np.zeros(shape)
    rk4_lanes(params, 9.81, TORQUES, theta, omega, 1e-4, 10_000)
    ref_theta, ref_omega = np.zeros(shape), np.zeros(shape)
    rk4_batch(params, 9.81, TORQUES, ref_theta, ref_omega, 1e-4, 10_000)
    assert np.abs(theta).max() > 0.3  # the arms moved
    assert np.abs(theta - ref_theta).max() <= 1e-12 * np.abs(ref_theta).max()
    assert np.abs(omega - ref_omega).max() <= 1e-12 * np.abs(ref_omega).max()
    # the fused 6-link step (FMA) against the general lane kernel (no FMA)
    general_theta, general_omega = np.zeros(shape), np.zeros(shape)
    rk4_lanes_general(params, 9.81, TORQUES, general_theta, general_omega, 1e-4, 10_000)
    assert 0.0 < np.abs(theta - general_theta).max() <= 1e-12 * np.abs(ref_theta).max()
    assert np.abs(omega - general_omega).max() <= 1e-12 * np.abs(ref_omega).max()


def test_chunked_in_time_gives_the_same_bits_and_one_robot_matches_mujoco():
    params = table1_params(3)
    theta, omega = np.zeros((3, 6)), np.zeros((3, 6))
    rk4_lanes(params, 9.81, TORQUES, theta, omega, 1e-4, 2000)
    chunked_theta, chunked_omega = np.zeros((3, 6)), np.zeros((3, 6))
    for steps in (1, 999, 1000):
        rk4_lanes(params, 9.81, TORQUES, chunked_theta, chunked_omega, 1e-4, steps)
    assert np.array_equal(theta, chunked_theta)
    assert np.array_equal(omega, chunked_omega)
    import mujoco

    model, data = chain_model(*params[1], 9.81, timestep_s=1e-4)
    data.qfrc_applied[:] = TORQUES
    for _ in range(2000):
        mujoco.mj_step(model, data)
    assert np.abs(theta[1] - data.qpos).max() <= 1e-9


def test_long_chains_take_the_articulated_body_path_and_equal_the_scalar_kernel():
    n = 12
    assert n >= ABA_MIN_LINKS
    rng = np.random.default_rng(4)
    robots = 5
    lengths = rng.uniform(0.1, 0.3, (robots, n))
    masses = rng.uniform(0.2, 1.0, (robots, n))
    params = np.stack([lengths, masses, masses * lengths**2 / 12], axis=1)
    theta0 = rng.uniform(-0.5, 0.5, (robots, n))
    torque = rng.normal(0.0, 0.5, n)
    theta, omega = theta0.copy(), np.zeros((robots, n))
    rk4_lanes_general(params, 9.81, torque, theta, omega, 1e-4, 1000)
    ref_theta, ref_omega = theta0.copy(), np.zeros((robots, n))
    rk4_batch(params, 9.81, torque, ref_theta, ref_omega, 1e-4, 1000)
    assert np.abs(theta - ref_theta).max() <= 1e-12 * np.abs(ref_theta).max()
    assert np.abs(omega - ref_omega).max() <= 1e-12 * np.abs(ref_omega).max()


def test_free_fall_keeps_every_robots_energy_on_the_lane_path():
    params = table1_params(LANES + 1, seed=7)
    theta, omega = np.zeros((len(params), 6)), np.zeros((len(params), 6))
    rk4_lanes(params, 9.81, np.zeros(6), theta, omega, 1e-4, 2000)  # 0.2 s
    for s in range(len(params)):
        kinetic, potential = energies(*params[s], 9.81, theta[s], omega[s])
        assert kinetic > 0.1
        assert abs(kinetic + potential) <= 1e-9 * kinetic  # started at rest, V = 0


@pytest.mark.parametrize("angle", [2.0e6, -5.0e7])
def test_an_angle_beyond_sincos_range_takes_the_c_library(angle):
    """A robot whose first joint starts past ``SINCOS_MAX_ABS`` (the others in range):
    its lane takes np.sin/np.cos and still equals the scalar kernel."""
    params = table1_params(4)
    theta0 = np.zeros((4, 6))
    theta0[2, 0] = angle
    theta, omega = theta0.copy(), np.zeros((4, 6))
    rk4_lanes(params, 9.81, TORQUES, theta, omega, 1e-4, 100)
    ref_theta, ref_omega = theta0.copy(), np.zeros((4, 6))
    rk4_batch(params, 9.81, TORQUES, ref_theta, ref_omega, 1e-4, 100)
    assert np.abs(omega - ref_omega).max() <= 1e-12 * np.abs(ref_omega).max()
    assert np.abs(theta[:, 1:] - ref_theta[:, 1:]).max() <= 1e-12


#: Compiles the general lane step alone into an empty cache; prints the forward dynamics'
#: compiled signatures (numba compiles a callee once per argument-type signature).
STEP_SIGNATURES = """
from planar_tui.runtime import prepare_kernels
prepare_kernels()
import numpy as np
from planar_tui.kernels import motion_lanes as m
n, lanes = 6, m.LANES
p = np.full((3, n, lanes), 0.5)
q, w = np.zeros((n, lanes)), np.zeros((n, lanes))
m.rk4_step_lanes(p, 9.81, np.zeros(n), q, w, 1e-3, np.zeros(n * m._WORK_STRIDE),
                 np.zeros((n, n, lanes)), np.empty((4, n, lanes)), np.empty((4, n, lanes)),
                 np.empty((n, lanes)), np.empty(m._ACC_ROWS * lanes), np.empty(3 * lanes))
print(len(m._forward_dynamics_lanes.signatures), len(m._noc_lanes.signatures),
      len(m._aba_lanes.signatures))
"""


@pytest.mark.slow
def test_the_general_lane_step_compiles_its_forward_dynamics_once(tmp_path):
    """A literal stage 0 at a call of its own made numba compile the forward dynamics and
    both algorithms below it a second time (for ``Literal[int](0)``): nearly 40 % of the step's
    cold compilation."""
    import os
    import subprocess
    import sys

    from tests.conftest import REPO

    env = {**os.environ, "PYTHONPATH": str(REPO), "NUMBA_CACHE_DIR": str(tmp_path)}
    result = subprocess.run(
        [sys.executable, "-c", STEP_SIGNATURES],
        env=env,
        timeout=1800,
        capture_output=True,
        text=True,
        check=True,
    )
    assert result.stdout.split() == ["1", "1", "1"]


def test_the_job_runs_whole_blocks_in_threads_with_one_calls_bits(monkeypatch):
    """The motion job shares the blocks among threads (``run_lanes``: a range of whole
    blocks each, the last block short): the same bits as one call over every robot."""
    import threading

    import numba

    from planar_tui.motion import engine

    # 8 blocks in 3 threads: 2, 3 and 3 blocks, the last one short (1000 = 7·128 + 104)
    assert engine.lane_ranges(1000, 3, LANES) == [(0, 256), (256, 640), (640, 1000)]
    assert engine.lane_ranges(5, 2, LANES) == [(0, 5)]
    params = table1_params(2 * LANES + 5, seed=3)
    shape = (len(params), 6)
    whole = np.zeros(shape), np.zeros(shape)
    rk4_lanes(params, 9.81, TORQUES, *whole, 1e-4, 50)
    calls = []

    def spy(p, gravity_m_s2, torque_Nm, theta, omega, step_s, n_steps):
        calls.append((len(p), threading.get_ident()))
        rk4_lanes(p, gravity_m_s2, torque_Nm, theta, omega, step_s, n_steps)

    monkeypatch.setattr(numba, "get_num_threads", lambda: 2)
    parts = np.zeros(shape), np.zeros(shape)
    engine.run_lanes(spy, params, 9.81, TORQUES, *parts, 1e-4, 50)
    assert sorted(robots for robots, _ in calls) == [LANES, LANES + 5]
    assert threading.get_ident() not in {thread for _, thread in calls}
    assert np.abs(whole[0]).max() > 0.0
    assert np.array_equal(parts[0], whole[0]) and np.array_equal(parts[1], whole[1])

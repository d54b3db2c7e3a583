"""Inverse dynamics of the 3-RPR and 3-PRR by the NOC (``kernels/dynamics3rpr.py``,
``kernels/dynamics3prr.py``), checked against what does not share their equations: the
Lagrange-multiplier formulation in full coordinates of :mod:`tests.closed_chain` (efforts
to 1e-8 of their largest, actuator rates and accelerations likewise) and the energy
balance along a quintic path (the actuators' work by Simpson's rule against the change of
kinetic plus potential energy of every body, itself from the full-coordinate rates).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from planar_tui.kernels.dynamics3prr import prr_path_dynamics
from planar_tui.kernels.dynamics3rpr import rpr_path_dynamics
from planar_tui.kernels.dynamics3rrr import solve_legs

from tests import closed_chain
from tests.closed_chain import Chain

G = 9.81
#: The 3-RPR and 3-PRR of the robot tables' defaults in m: paper B's base triangle (side
#: 1.2) and platform (base and height 0.4); the 3-PRR's rails along the base's sides.
BASES = np.array([[0.0, 0.0], [1.2, 0.0], [0.6, 0.6 * math.sqrt(3.0)]])
POINTS = np.array([[0.0, 0.0], [0.4, 0.0], [0.2, 0.4]])
RAIL_ANGLES = np.radians([0.0, 120.0, 240.0])
LINK_M = 0.4
SLIDER_MODES = (1.0, 1.0, 1.0)


def rpr_legs() -> np.ndarray:
    return np.array([[*a, *q, 0.0, np.inf] for a, q in zip(BASES, POINTS, strict=True)])


def prr_legs() -> np.ndarray:
    return np.array(
        [
            [*b, math.cos(t), math.sin(t), *q, LINK_M, sigma, -np.inf, np.inf]
            for b, t, q, sigma in zip(BASES, RAIL_ANGLES, POINTS, SLIDER_MODES, strict=True)
        ]
    )


def rpr_chain(pose, body) -> tuple[Chain, object]:
    return closed_chain.rpr_chain(BASES, POINTS, pose, body)


def prr_chain(pose, body) -> tuple[Chain, object]:
    return closed_chain.prr_chain(
        BASES, RAIL_ANGLES, POINTS, (LINK_M,) * 3, SLIDER_MODES, pose, body
    )


CASES = {
    "3-RPR": (rpr_path_dynamics, rpr_legs, rpr_chain, 8),
    "3-PRR": (prr_path_dynamics, prr_legs, prr_chain, 5),
}


def random_body(rng, entries: int) -> np.ndarray:
    """Random masses and inertias (the 3-RPR's centres of mass at 0.05-0.3 m), gravity."""
    body = rng.uniform(0.5, 3.0, entries)
    if entries == 8:
        body[[2, 5]] = rng.uniform(0.05, 0.3, 2)
    return np.append(body, G)


@pytest.mark.parametrize("robot", CASES)
@pytest.mark.parametrize("seed", range(3))
def test_noc_equals_lagrange_multipliers(robot, seed):
    dynamics, legs, build, entries = CASES[robot]
    rng = np.random.default_rng(seed)
    body = random_body(rng, entries)
    pose = np.array([0.4, 0.2, 0.0]) + rng.uniform(-0.05, 0.05, 3)
    rate, acceleration = rng.uniform(-1, 1, 3), rng.uniform(-3, 3, 3)
    _, velocity, accel, effort, status, closure = solve_legs(
        dynamics, legs(), body, pose[None], rate[None], acceleration[None], 1e-9
    )
    assert status[0] == 0 and closure[0] < 1e-15
    chain, actuators = build(pose, body)
    qd, qdd, reference, residual = chain.solve(0, rate, acceleration, actuators, G)
    assert residual < 1e-14
    b = actuators(np.array(chain.q))
    scale = np.max(np.abs(reference))
    np.testing.assert_allclose(effort[0], reference, rtol=0, atol=1e-8 * scale)
    np.testing.assert_allclose(velocity[0], b @ qd, rtol=0, atol=1e-12)
    np.testing.assert_allclose(accel[0], actuator_accelerations(robot, chain, body, qd, qdd))


def actuator_accelerations(robot, chain, body, qd, qdd) -> np.ndarray:
    """s'' = u . S'' along a rail; rho'' = e . P'' + (|P'|^2 - (e . P')^2) / rho for the
    piston's end P (body 2 + 2 i), P'' = J q'' - omega^2 R s."""
    q = np.array(chain.q)
    if robot == "3-PRR":
        return np.array(
            [
                qdd[6 * i + 3 : 6 * i + 5] @ (math.cos(t), math.sin(t))
                for i, t in enumerate(RAIL_ANGLES)
            ]
        )
    out = []
    for i, a in enumerate(BASES):
        piston = 2 + 2 * i
        point, jac, rs = chain.point(q, piston, (body[5], 0.0))
        pd, pdd = jac @ qd, jac @ qdd - qd[3 * piston + 2] ** 2 * rs
        rho = np.linalg.norm(point - a)
        e = (point - a) / rho
        out.append(e @ pdd + (pd @ pd - (e @ pd) ** 2) / rho)
    return np.array(out)


@pytest.mark.parametrize("robot", CASES)
def test_energy_balance_along_a_quintic(robot):
    """Work of the actuators over [0, T/2] = change of kinetic plus potential energy."""
    dynamics, legs, build, entries = CASES[robot]
    body = random_body(np.random.default_rng(7), entries)
    start, stop, duration = np.array([0.38, 0.18, -0.1]), np.array([0.45, 0.24, 0.15]), 0.5
    times = np.linspace(0.0, 0.5 * duration, 801)
    tau = times[:, None] / duration
    delta = stop - start
    pose = start + delta * tau**3 * (10 - 15 * tau + 6 * tau**2)
    rate = delta * 30 * tau**2 * (1 - tau) ** 2 / duration
    acceleration = delta * 60 * tau * (1 - tau) * (1 - 2 * tau) / duration**2
    _, velocity, _, effort, status, _ = solve_legs(
        dynamics, legs(), body, pose, rate, acceleration, 1e-9
    )
    assert not status.any()
    power = np.sum(effort * velocity, axis=1)
    h = times[1] - times[0]
    work = h / 3 * (power[0] + power[-1] + 4 * power[1:-1:2].sum() + 2 * power[2:-1:2].sum())
    energies = []
    for k in (0, -1):
        chain, actuators = build(pose[k], body)
        qd, _, _, _ = chain.solve(0, rate[k], acceleration[k], actuators, G)
        energies.append(chain.energy(qd, G))
    change = energies[1] - energies[0]
    assert abs(work - change) < 1e-8 * max(abs(change), np.max(np.abs(power)) * times[-1])
    assert abs(change) > 0.1  # the check is not vacuous


def test_a_static_platform_under_gravity_massless_legs():
    """A hand solution: massless legs, the platform's weight m g on three legs at rest;
    the legs' forces balance it, A^T f = (0, m g, 0)."""
    body = np.array([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 2.0, 0.1, G])
    pose = np.array([[0.35, 0.15, 0.0]])  # (0.4, 0.2, 0): the leg lines concurrent, singular
    zero = np.zeros((1, 3))
    _, _, _, effort, status, _ = solve_legs(
        rpr_path_dynamics, rpr_legs(), body, pose, zero, zero, 1e-9
    )
    assert status[0] == 0
    rows = []
    for a, q in zip(BASES, POINTS, strict=True):
        v = pose[0, :2] + q - a
        e = v / np.linalg.norm(v)
        rows.append([e[0], e[1], q[0] * e[1] - q[1] * e[0]])
    np.testing.assert_allclose(np.array(rows).T @ effort[0], [0.0, 2.0 * G, 0.0], atol=1e-12)


def test_failures_name_the_leg():
    legs = rpr_legs()
    legs[1, 5] = 0.3  # leg 2 at most 0.3 m
    zero = np.zeros((1, 3))
    body = np.zeros(9)
    out = solve_legs(rpr_path_dynamics, legs, body, np.array([[0.35, 0.15, 0.0]]), zero, zero, 1e-9)
    assert out[4][0] == 22 and np.isnan(out[3][0]).all()
    far = np.array([[5.0, 5.0, 0.0]])
    out = solve_legs(prr_path_dynamics, prr_legs(), np.zeros(6), far, zero, zero, 1e-9)
    assert out[4][0] == 11

"""The 3-RRR's and the five-bar's NOC inverse dynamics against references that share no
code with it: Lagrange multipliers in full coordinates (:mod:`tests.lagrange_planar`), the
energy balance along a path, hand solutions, and the serial arm's NOC leg by leg."""

from __future__ import annotations

import math

import numpy as np
import pytest
from planar_tui.kernels.dynamics import inverse_dynamics as serial_inverse_dynamics

from planar_tui.workspace.fivebar.mechanism import MECHANISM as FIVEBAR
from planar_tui.workspace.fivebar.path import Path5RSpec
from planar_tui.workspace.fivebar.robot import Robot5R
from planar_tui.workspace.path.job import pose_si
from planar_tui.workspace.path.quintic import quintic, sample_times
from planar_tui.workspace.rrr.mechanism import MECHANISM as RRR
from planar_tui.workspace.rrr.path import Path3RRRSpec
from planar_tui.workspace.rrr.robot import Robot3RRR
from tests.lagrange_planar import Leg, rr_coordinates, rr_system

MASSES = {
    "proximal_mass_kg": 0.7,
    "distal_mass_kg": 0.45,
    "proximal_inertia_kgm2": 0.006,
    "distal_inertia_kgm2": 0.0035,
    "gravity_m_s2": 9.81,
}
RRR_ROBOT = Robot3RRR(**MASSES, platform_mass_kg=1.3, platform_inertia_kgm2=0.021)
RRR_SPEC = Path3RRRSpec(from_pose=(40, 21, 0), to_pose=(45, 25, 8), elbow=(1, 1, 1))
FIVEBAR_ROBOT = Robot5R(**MASSES, end_mass_kg=0.4, working_mode="+-")
FIVEBAR_SPEC = Path5RSpec(from_pose=(0, 60), to_pose=(10, 66), elbow=(1, -1))


def rrr_legs(robot, elbow):
    return [
        Leg(
            (ax / 100, ay / 100),
            (qx / 100, qy / 100),
            robot.proximal_cm / 100,
            robot.distal_cm / 100,
            s,
        )
        for (ax, ay), (qx, qy), s in zip(
            robot.base_joints_cm(), robot.platform_points_cm(), elbow, strict=True
        )
    ]


def fivebar_legs(robot, elbow):
    return [
        Leg((ax / 100, ay / 100), (0.0, 0.0), l1 / 100, l2 / 100, s)
        for (ax, ay), l1, l2, s in zip(
            robot.base_joints_cm(), robot.proximal_cm, robot.distal_cm, elbow, strict=True
        )
    ]


def reference(robot, spec, legs, platform, dimension, times):
    """Per time: the Lagrange torques, full coordinates, rates and accelerations."""
    system = rr_system(
        legs,
        (robot.proximal_mass_kg, robot.distal_mass_kg),
        (robot.proximal_inertia_kgm2, robot.distal_inertia_kgm2),
        platform,
        robot.gravity_m_s2,
        dimension,
    )
    pose, rate, acceleration = quintic(
        pose_si(spec.from_pose), pose_si(spec.to_pose), spec.duration_s, times
    )
    out = []
    for x, xd, xdd in zip(pose, rate, acceleration, strict=True):
        q = rr_coordinates(legs, (*x, 0.0)[:3])
        assert system.residual(q) < 1e-12
        qd = system.velocities(q, xd)
        tau, qdd = system.torques(q, qd, xdd)
        out.append((tau, q, qd, qdd))
    return system, (pose, rate, acceleration), out


CASES = {
    "3-RRR": (RRR, RRR_ROBOT, RRR_SPEC, rrr_legs, (1.3, 0.021), 3),
    "five-bar": (FIVEBAR, FIVEBAR_ROBOT, FIVEBAR_SPEC, fivebar_legs, (0.4, 1.0), 2),
}


@pytest.mark.parametrize("case", CASES)
def test_torques_rates_and_accelerations_match_lagrange_multipliers(case):
    mechanism, robot, spec, legs_of, platform, dimension = CASES[case]
    times = sample_times(spec.duration_s, 10)
    legs = legs_of(robot, spec.elbow)
    _, states, expected = reference(robot, spec, legs, platform, dimension, times)
    solution = mechanism.inverse_dynamics(robot, spec, *states)
    assert not solution.status.any()
    tau = np.array([e[0] for e in expected])
    assert np.abs(tau).max() > 1.0  # a motion with real torques
    np.testing.assert_allclose(solution.effort, tau, rtol=0, atol=1e-8 * np.abs(tau).max())
    proximal = [3 * (2 * i) + 2 for i in range(len(legs))]
    rates = np.array([e[2][proximal] for e in expected])
    accelerations = np.array([e[3][proximal] for e in expected])
    np.testing.assert_allclose(solution.rate, rates, atol=1e-10 * np.abs(rates).max())
    np.testing.assert_allclose(
        solution.acceleration, accelerations, atol=1e-10 * np.abs(accelerations).max()
    )
    angles = np.array([e[1][proximal] for e in expected])
    np.testing.assert_allclose(np.cos(solution.coordinate), np.cos(angles), atol=1e-12)
    np.testing.assert_allclose(np.sin(solution.coordinate), np.sin(angles), atol=1e-12)
    assert solution.closure_m.max() < 1e-14


def simpson(values, h):
    """Composite Simpson's rule over an even number of intervals."""
    return h / 3.0 * (values[0] + values[-1] + 4 * values[1:-1:2].sum() + 2 * values[2:-1:2].sum())


@pytest.mark.parametrize("case", CASES)
def test_actuator_work_is_the_change_of_kinetic_plus_potential_energy(case):
    mechanism, robot, spec, legs_of, platform, dimension = CASES[case]
    steps = 400
    times = sample_times(spec.duration_s, steps)
    legs = legs_of(robot, spec.elbow)
    system, states, expected = reference(robot, spec, legs, platform, dimension, times)
    solution = mechanism.inverse_dynamics(robot, spec, *states)
    power = (solution.effort * solution.rate).sum(axis=1)
    energy = np.array([system.energy(e[1], e[2]) for e in expected])
    h = spec.duration_s / steps
    scale = np.abs(energy - energy[0]).max()
    assert scale > 0.01
    for k in (steps // 2, steps):  # mid-path (kinetic energy) and end (potential only)
        work = simpson(power[: k + 1], h)
        assert abs(work - (energy[k] - energy[0])) < 1e-7 * scale, (k, work, energy[k] - energy[0])


def test_massless_platform_weighty_proximal_links_hold_their_own_weight():
    """At rest, only the proximal links weighing m: each motor holds its own link,
    tau_i = m g (l1 / 2) cos(theta_i), the angle from the two circles (test code)."""
    robot = Robot3RRR(proximal_mass_kg=0.9, gravity_m_s2=9.81)
    spec = Path3RRRSpec(from_pose=(41, 22, 3), to_pose=(41, 22, 3), elbow=(1, -1, 1))
    states = quintic(pose_si(spec.from_pose), pose_si(spec.to_pose), 1.0, np.zeros(1))
    solution = RRR.inverse_dynamics(robot, spec, *states)
    q = rr_coordinates(rrr_legs(robot, spec.elbow), pose_si(spec.from_pose))
    theta = q[[2, 8, 14]]
    expected = 0.9 * 9.81 * 0.15 * np.cos(theta)
    np.testing.assert_allclose(solution.effort[0], expected, rtol=1e-12, atol=1e-14)


def test_massless_platform_spinning_proximal_links_need_i_theta_ddot():
    """Only the proximal links' inertia I, no gravity: tau_i = I theta_i'', the angular
    accelerations from the Lagrange reference's kinematics."""
    robot = Robot3RRR(proximal_inertia_kgm2=0.02)
    legs = rrr_legs(robot, RRR_SPEC.elbow)
    times = sample_times(1.0, 6)
    _, states, expected = reference(robot, RRR_SPEC, legs, (0.0, 0.0), 3, times)
    solution = RRR.inverse_dynamics(robot, RRR_SPEC, *states)
    theta_ddot = np.array([e[3][[2, 8, 14]] for e in expected])
    np.testing.assert_allclose(solution.effort, 0.02 * theta_ddot, atol=1e-12)


@pytest.mark.parametrize("case", CASES)
def test_each_leg_is_the_serial_arms_noc(case):
    """Massless platform: the actuators' power is the sum over the legs of the serial
    arm's NOC torques times its joint rates, each leg an RR arm in relative angles
    (theta, psi - theta), its motion from the Lagrange reference."""
    mechanism, robot, spec, legs_of, _, dimension = CASES[case]
    import dataclasses

    robot = dataclasses.replace(
        robot,
        **(
            {"platform_mass_kg": 0.0, "platform_inertia_kgm2": 0.0}
            if dimension == 3
            else {"end_mass_kg": 0.0}
        ),
    )
    legs = legs_of(robot, spec.elbow)
    times = sample_times(spec.duration_s, 8)
    _, states, expected = reference(robot, spec, legs, (0.0, 1.0), dimension, times)
    solution = mechanism.inverse_dynamics(robot, spec, *states)
    lengths = np.array([legs[0].l1, legs[0].l2])
    masses = np.array([robot.proximal_mass_kg, robot.distal_mass_kg])
    inertias = np.array([robot.proximal_inertia_kgm2, robot.distal_inertia_kgm2])
    for k, (_, q, qd, qdd) in enumerate(expected):
        serial_power = 0.0
        for i in range(len(legs)):
            a, b = 6 * i + 2, 6 * i + 5
            theta = np.array([q[a], q[b] - q[a]])
            rate = np.array([qd[a], qd[b] - qd[a]])
            acceleration = np.array([qdd[a], qdd[b] - qdd[a]])
            tau = serial_inverse_dynamics(
                lengths, masses, inertias, robot.gravity_m_s2, theta, rate, acceleration
            )
            serial_power += float(tau @ rate)
        power = float(solution.effort[k] @ solution.rate[k])
        assert power == pytest.approx(serial_power, rel=1e-9, abs=1e-12)
    assert math.isfinite(power)

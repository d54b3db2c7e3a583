"""The exported models in the real engines: MuJoCo loads the MJCF, Pinocchio the URDF, and
both give planar-tui's inverse dynamics (the NOC kernel) at random states.

Independent references: MuJoCo's ``mj_inverse`` (its recursive Newton-Euler in 6-D spatial
coordinates) and Pinocchio's ``rnea`` on the files exactly as ``export`` writes them; the
URDF's gravity is not in the file (URDF has none), so it is set as its comment says.
"""

from __future__ import annotations

import mujoco
import numpy as np
import pinocchio
import pytest
from planar_tui.kernels.dynamics import inverse_dynamics

from planar_tui.dynamics.robot import SerialRobot
from planar_tui.interop.mjcf import robot_mjcf
from planar_tui.interop.urdf import robot_urdf
from tests.test_dynamics_kernels import random_robot, random_state

#: Relative agreement asked of the engines: max |Δτ| / max |τ| over the states.
RELATIVE = 1e-10
LINKS = range(1, 51)


def random_serial_robot(rng, n: int) -> SerialRobot:
    lengths, masses, inertias = random_robot(rng, n)
    return SerialRobot(
        lengths_m=tuple(lengths),
        masses_kg=tuple(masses),
        inertias_kgm2=tuple(inertias),
        gravity_m_s2=float(rng.uniform(0.0, 20.0)),
    )


def planar_tui_torques(robot: SerialRobot, theta, omega, alpha) -> np.ndarray:
    return inverse_dynamics(*robot.arrays(), robot.gravity_m_s2, theta, omega, alpha)


def worst_relative(pairs) -> float:
    return max(np.abs(a - b).max() / np.abs(b).max() for a, b in pairs)


def test_exported_mjcf_in_mujoco_gives_planar_tui_inverse_dynamics():
    rng = np.random.default_rng(2024)
    pairs = []
    for n in LINKS:
        robot = random_serial_robot(rng, n)
        model = mujoco.MjModel.from_xml_string(robot_mjcf(robot))
        data = mujoco.MjData(model)
        assert model.nq == model.nv == model.nu == n
        np.testing.assert_array_equal(model.opt.gravity, [0.0, -robot.gravity_m_s2, 0.0])
        for _ in range(3):
            theta, omega, alpha = random_state(rng, n)
            data.qpos[:], data.qvel[:], data.qacc[:] = theta, omega, alpha
            mujoco.mj_inverse(model, data)
            pairs.append((data.qfrc_inverse.copy(), planar_tui_torques(robot, theta, omega, alpha)))
    assert worst_relative(pairs) <= RELATIVE


def test_exported_urdf_in_pinocchio_gives_planar_tui_inverse_dynamics():
    rng = np.random.default_rng(2025)
    pairs = []
    for n in LINKS:
        robot = random_serial_robot(rng, n)
        model = pinocchio.buildModelFromXML(robot_urdf(robot))
        # continuous joints: (cos q, sin q) per joint, one velocity each
        assert (model.nq, model.nv) == (2 * n, n)
        model.gravity.linear = np.array([0.0, -robot.gravity_m_s2, 0.0])  # as the file says
        data = model.createData()
        for _ in range(3):
            theta, omega, alpha = random_state(rng, n)
            q = np.column_stack([np.cos(theta), np.sin(theta)]).ravel()
            tau = pinocchio.rnea(model, data, q, omega, alpha)
            pairs.append((np.array(tau), planar_tui_torques(robot, theta, omega, alpha)))
    assert worst_relative(pairs) <= RELATIVE


@pytest.mark.parametrize("n", [1, 4])
def test_exported_urdf_in_mujoco_matches_its_mjcf(n):
    """MuJoCo's own URDF reader sees the same arm as the MJCF (with the gravity set)."""
    rng = np.random.default_rng(n)
    robot = random_serial_robot(rng, n)
    from_urdf = mujoco.MjModel.from_xml_string(robot_urdf(robot))
    from_urdf.opt.gravity[:] = (0.0, -robot.gravity_m_s2, 0.0)
    data = mujoco.MjData(from_urdf)
    theta, omega, alpha = random_state(rng, n)
    data.qpos[:], data.qvel[:], data.qacc[:] = theta, omega, alpha
    mujoco.mj_inverse(from_urdf, data)
    expected = planar_tui_torques(robot, theta, omega, alpha)
    assert np.abs(data.qfrc_inverse - expected).max() <= RELATIVE * np.abs(expected).max()


def test_the_axial_moment_satisfies_mujoco_for_tiny_and_huge_inertias():
    """MuJoCo's triangle inequality and smallest moment hold from 1e-15 to 1e15 kg m²."""
    for inertia in (1e-15, 3e-12, 1.0, 1e15):
        robot = SerialRobot(
            lengths_m=(1.0, 2.0), masses_kg=(1.0, 1.0), inertias_kgm2=(inertia, inertia)
        )
        model = mujoco.MjModel.from_xml_string(robot_mjcf(robot))
        np.testing.assert_array_equal(model.body_inertia[1:, 2], [inertia, inertia])

"""A path job's ``constant_efforts`` on the five-bar, the 3-RPR and the 3-PRR (the 3-RRR's
is in tests/test_path_constant_efforts.py): without gravity, from rest, the actuators' work
``sum e_i (a_i(T) - a_i(0))`` equals the kinetic energy at ``T``, both from the CSV's
poses and rates through references that share no code with the robots' kernels: the
Lagrange model of RR legs in full coordinates (:mod:`tests.lagrange_planar`) for the
five-bar, the closed chains of :mod:`tests.closed_chain` for the prismatic robots, and
each robot's actuator coordinates (joint angle, leg length, stroke) from its own
inverse kinematics here."""

from __future__ import annotations

import numpy as np
import pytest

from tests.conftest import PRESETS
from tests.test_path5r import JOB as FIVEBAR_JOB
from tests.test_path5r import ROBOT as FIVEBAR_ROBOT
from tests.test_path_constant_efforts import read, run, weightless
from tests.test_path_prismatic import PRR_PRESET


def fivebar_reference(robot, spec, ends):
    """Joint angles at both ends and the kinetic energy at the last (Lagrange, RR legs
    meeting at the end mass, a point platform)."""
    from tests.lagrange_planar import rr_coordinates, rr_system
    from tests.test_parallel_dynamics_lagrange import fivebar_legs

    legs = fivebar_legs(robot, spec.elbow)
    system = rr_system(
        legs,
        (robot.proximal_mass_kg, robot.distal_mass_kg),
        (robot.proximal_inertia_kgm2, robot.distal_inertia_kgm2),
        (robot.end_mass_kg, 0.0),
        0.0,
        dimension=2,
    )
    coordinates = [rr_coordinates(legs, (x, y, 0.0)) for (x, y), _ in ends]
    theta = np.array([[q[6 * i + 2] for i in range(2)] for q in coordinates])
    last, rate = coordinates[1], ends[1][1]
    return theta, system.energy(last, system.velocities(last, rate))


def rotated(phi, point):
    c, s = np.cos(phi), np.sin(phi)
    return np.array([c * point[0] - s * point[1], s * point[0] + c * point[1]])


def rpr_reference(robot, spec, ends):
    """Leg lengths ``|p + R q_i - A_i|`` at both ends and the kinetic energy at the last
    (the closed chain of cylinders and pistons)."""
    from tests.closed_chain import rpr_chain

    bases = np.array(robot.base_joints_cm) / 100.0
    points = np.array(robot.platform_points_cm) / 100.0
    body = (
        robot.cylinder_mass_kg,
        robot.cylinder_inertia_kgm2,
        robot.cylinder_com_cm / 100.0,
        robot.piston_mass_kg,
        robot.piston_inertia_kgm2,
        robot.piston_com_cm / 100.0,
        robot.platform_mass_kg,
        robot.platform_inertia_kgm2,
    )
    lengths = np.array(
        [
            [
                np.linalg.norm(pose[:2] + rotated(pose[2], q) - a)
                for a, q in zip(bases, points, strict=True)
            ]
            for pose, _ in ends
        ]
    )
    pose, rate = ends[1]
    chain, actuators = rpr_chain(bases, points, pose, body)
    qd = chain.solve(0, rate, np.zeros(3), actuators, 0.0)[0]
    return lengths, chain.energy(qd, 0.0)


def prr_reference(robot, spec, ends):
    """Strokes ``s_i = g.u + sigma sqrt(l^2 - (g x u)^2)`` (``g = C_i - B_i``) at both ends
    and the kinetic energy at the last (the closed chain of sliders and links)."""
    from tests.closed_chain import prr_chain

    bases = np.array(robot.slider_points_cm) / 100.0
    angles = np.radians(robot.slider_angles_deg)
    points = np.array(robot.platform_points_cm) / 100.0
    links = np.array(robot.distal_cm) / 100.0
    body = (
        robot.slider_mass_kg,
        robot.link_mass_kg,
        robot.link_inertia_kgm2,
        robot.platform_mass_kg,
        robot.platform_inertia_kgm2,
    )
    strokes = []
    for pose, _ in ends:
        row = []
        for b, t, q, link, sigma in zip(
            bases, angles, points, links, spec.slider_modes, strict=True
        ):
            u = np.array([np.cos(t), np.sin(t)])
            g = pose[:2] + rotated(pose[2], q) - b
            row.append(g @ u + sigma * np.sqrt(link**2 - (g[0] * u[1] - g[1] * u[0]) ** 2))
        strokes.append(row)
    pose, rate = ends[1]
    chain, actuators = prr_chain(bases, angles, points, links, spec.slider_modes, pose, body)
    qd = chain.solve(0, rate, np.zeros(3), actuators, 0.0)[0]
    return np.array(strokes), chain.energy(qd, 0.0)


CASES = {
    "path5r": (FIVEBAR_ROBOT + FIVEBAR_JOB, [0.02, -0.015], "f", fivebar_reference),
    "path3rpr": (
        (PRESETS / "path-3rpr.toml").read_text(encoding="utf-8"),
        [1.0, -0.8, 0.5],
        "path-3rpr",
        rpr_reference,
    ),
    "path3prr": (PRR_PRESET, [1.0, -0.8, 0.5], "prr", prr_reference),
}


@pytest.mark.parametrize("kind", CASES)
def test_the_actuators_work_becomes_kinetic_energy(cli, tmp_path, kind):
    """Zero gravity, constant efforts from rest for 0.1 s (100 RK4 steps): the work equals
    the kinetic energy at ``T`` of the independent reference, to RK4 accuracy."""
    from planar_tui.batch import prepare_jobs
    from planar_tui.presets import load_preset

    text, efforts, stem, reference = CASES[kind]
    text = weightless(text, str(efforts), steps=100)
    if "duration_s" not in text:
        text = text.replace("\nsteps =", "\nduration_s = 0.1\nsteps =")
    text = "\n".join(
        "duration_s = 0.1" if line.startswith("duration_s") else line for line in text.split("\n")
    )
    preset, result = run(cli, tmp_path, text)
    assert result.exit_code == 0, result.output
    header, values = read(tmp_path / "out" / f"{stem}-forward.csv")
    width = 2 if kind == "path5r" else 3
    assert len(header) == 1 + 2 * width and len(values) == 101
    scale = np.array([0.01, 0.01, np.pi / 180.0])[:width]
    ends = [(values[k, 1 : 1 + width] * scale, values[k, 1 + width :] * scale) for k in (0, -1)]
    assert np.all(ends[0][1] == 0.0)  # from rest
    (job,) = prepare_jobs(load_preset(preset).jobs_of(kind))
    coordinates, kinetic = reference(job.robot, job.prepared, ends)
    work = np.array(efforts) @ (coordinates[1] - coordinates[0])
    assert kinetic > 1e-6  # the platform moved
    assert abs(values[-1, 1:3] - values[0, 1:3]).max() > 0.01
    assert work == pytest.approx(kinetic, rel=1e-9)

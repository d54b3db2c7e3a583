# ruff: noqa: E402  (the repository root goes on sys.path and numba is set up first)
"""Benchmark of the 3-RRR's closed-chain inverse dynamics (``python
benchmarks/bench_path_dynamics.py``), with the bundled preset ``presets/path-3rrr.toml``.

Rows (JIT warmed first, best of several repeats, one thread: the kernel is serial):

* the NOC kernel (:func:`kernels.dynamics3rrr.rr_path_dynamics`: leg kinematics and
  torques) per pose over 10^5 poses, and over one 1 000-step path (1 001 poses), kernel
  alone and through the mechanism's ``inverse_dynamics`` (Python wrapper, allocation);
* the forward dynamics per state in platform coordinates (5 inverse dynamics + a 3x3
  solve, :func:`planar_tui.workspace.path.forward.acceleration`, called from Python);
* Pinocchio's ``constraintDynamics`` (the same 3-RRR as a tree, leg 1 carrying the
  platform, legs 2 and 3 closed by 3-D point constraints) per call from Python, given the
  NOC's torques; its accelerations are compared with the path's and the largest
  difference printed (this model does not reproduce them yet: the timing compares the
  cost of one constrained-dynamics call, not a verified equivalent).

Goals (issue 35): <= 1 us per pose on one thread, a 1 000-step path <= 1 ms, and >= 10x
faster than Pinocchio's constrained dynamics per step.
"""

import math
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from planar_tui.runtime import prepare_kernels

prepare_kernels()  # before any kernel is imported

from planar_tui.kernels.dynamics3rrr import rr_path_dynamics

from benchmarks.baselines import import_pinocchio
from benchmarks.timing import load
from planar_tui.presets import load_preset
from planar_tui.workspace.path.forward import acceleration
from planar_tui.workspace.path.job import pose_si
from planar_tui.workspace.path.model import SINGULAR_RELATIVE
from planar_tui.workspace.path.quintic import quintic, sample_times
from planar_tui.workspace.rrr.dynamics import body_array, leg_rows

PRESET = Path(__file__).resolve().parent.parent / "presets" / "path-3rrr.toml"


def best_time(function, repeats=7):
    best = np.inf
    for _ in range(repeats):
        start = time.perf_counter()
        function()
        best = min(best, time.perf_counter() - start)
    return best


def path_states(spec, steps):
    times = sample_times(spec.duration_s, steps)
    return quintic(pose_si(spec.from_pose), pose_si(spec.to_pose), spec.duration_s, times)


def kernel_call(legs, body, states):
    n = len(states[0])
    out = [np.empty((n, 3)) for _ in range(4)]
    status, closure = np.empty(n, dtype=np.int64), np.empty(n)

    def call():
        rr_path_dynamics(legs, body, *states, SINGULAR_RELATIVE, *out, status, closure)

    return call, out, status


def pinocchio_3rrr(robot, elbow):
    """``(model, data, constraint models, constraint datas)``: three RR legs, leg 1's
    distal link carrying the platform (a revolute joint at C1), legs 2 and 3 closed at
    C2, C3 by point constraints; gravity (0, -g, 0)."""
    pin = import_pinocchio()
    model = pin.Model()
    l1, l2 = robot.proximal_cm / 100, robot.distal_cm / 100
    distal = []
    for ax, ay in robot.base_joints_cm():
        base = pin.SE3(np.eye(3), np.array([ax / 100, ay / 100, 0.0]))
        joint = model.addJoint(0, pin.JointModelRZ(), base, "proximal")
        inertia = robot.proximal_inertia_kgm2
        model.appendBodyToJoint(
            joint,
            pin.Inertia(
                robot.proximal_mass_kg, np.array([l1 / 2, 0, 0]), np.diag([1e-10, inertia, inertia])
            ),
            pin.SE3.Identity(),
        )
        elbow_joint = model.addJoint(
            joint, pin.JointModelRZ(), pin.SE3(np.eye(3), np.array([l1, 0, 0])), "distal"
        )
        inertia = robot.distal_inertia_kgm2
        model.appendBodyToJoint(
            elbow_joint,
            pin.Inertia(
                robot.distal_mass_kg, np.array([l2 / 2, 0, 0]), np.diag([1e-10, inertia, inertia])
            ),
            pin.SE3.Identity(),
        )
        distal.append(elbow_joint)
    platform = model.addJoint(
        distal[0], pin.JointModelRZ(), pin.SE3(np.eye(3), np.array([l2, 0, 0])), "platform"
    )
    inertia = robot.platform_inertia_kgm2
    model.appendBodyToJoint(
        platform,
        pin.Inertia(robot.platform_mass_kg, np.zeros(3), np.diag([1e-10, inertia, inertia])),
        pin.SE3.Identity(),
    )
    model.gravity.linear = np.array([0.0, -robot.gravity_m_s2, 0.0])
    data = model.createData()
    constraints = pin.StdVec_RigidConstraintModel()
    for leg in (1, 2):
        qx, qy = robot.platform_points_cm()[leg]
        constraints.append(
            pin.RigidConstraintModel(
                pin.ContactType.CONTACT_3D,
                model,
                distal[leg],
                pin.SE3(np.eye(3), np.array([l2, 0, 0])),
                platform,
                pin.SE3(np.eye(3), np.array([qx / 100, qy / 100, 0])),
                pin.ReferenceFrame.LOCAL,
            )
        )
    datas = pin.StdVec_RigidConstraintData()
    for c in constraints:
        datas.append(c.createData())
    pin.initConstraintDynamics(model, data, constraints, datas)
    return pin, model, data, constraints, datas


def joint_state(robot, pose, rate, theta, theta_rate):
    """Pinocchio's ``(q, v)``: relative angles (theta_i, psi_i - theta_i) per leg and the
    platform's phi - psi_1, psi and its rate from the leg's geometry."""
    l1, l2 = robot.proximal_cm / 100, robot.distal_cm / 100
    x, y, phi = pose
    xd, yd, phid = rate
    c, s = math.cos(phi), math.sin(phi)
    q, v, psis = [], [], []
    for i, ((ax, ay), (qx, qy)) in enumerate(
        zip(robot.base_joints_cm(), robot.platform_points_cm(), strict=True)
    ):
        rx, ry = (c * qx - s * qy) / 100, (s * qx + c * qy) / 100
        th, thd = theta[i], theta_rate[i]
        ux = x + rx - ax / 100 - l1 * math.cos(th)
        uy = y + ry - ay / 100 - l1 * math.sin(th)
        psi = math.atan2(uy, ux)
        # C' - l1 thd e_perp(th) = l2 psid e_perp(psi)
        wx = xd - phid * ry + l1 * thd * math.sin(th)
        wy = yd + phid * rx - l1 * thd * math.cos(th)
        psid = (-wx * math.sin(psi) + wy * math.cos(psi)) / l2
        q += [th, psi - th]
        v += [thd, psid - thd]
        psis.append((psi, psid))
    q.append(phi - psis[0][0])
    v.append(phid - psis[0][1])
    return np.array(q), np.array(v)


def main():
    preset = load_preset(PRESET)
    (job,) = preset.jobs_of("path3rrr")
    robot, spec = job.robot, job.spec
    legs, body = leg_rows(robot, spec.elbow, spec.limits_rad), body_array(robot)
    rows = []

    many = path_states(spec, 99_999)
    call, _, status = kernel_call(legs, body, many)
    call()
    assert not status.any()
    per_pose = best_time(call) / len(many[0])
    rows.append(("NOC kernel, per pose (10^5 poses)", per_pose, "<= 1 us"))

    path = path_states(spec, 1000)
    call, out, status = kernel_call(legs, body, path)
    call()
    rows.append(("NOC kernel, 1 000-step path", best_time(call), "<= 1 ms"))
    mechanism = spec.mechanism
    rows.append(
        (
            "inverse_dynamics (Python wrapper), 1 000-step path",
            best_time(lambda: mechanism.inverse_dynamics(robot, spec, *path)),
            "",
        )
    )
    k = 300
    state = (path[0][k], path[1][k])
    effort = out[3][k]
    forward = (
        best_time(
            lambda: [acceleration(mechanism, robot, spec, *state, effort) for _ in range(100)]
        )
        / 100
    )
    rows.append(("forward dynamics per state (Python + 5 ID in one call)", forward, ""))

    pin, model, data, constraints, datas = pinocchio_3rrr(robot, spec.elbow)
    settings = pin.ProximalSettings(1e-14, 1e-10, 100)  # mu > 0: the z rows are empty
    errors, qs = [], []
    for k in range(0, 1001, 50):
        q, v = joint_state(robot, path[0][k], path[1][k], out[0][k], out[1][k])
        tau = np.zeros(model.nv)
        tau[[0, 2, 4]] = out[3][k]
        ddq = pin.constraintDynamics(model, data, q, v, tau, constraints, datas, settings)
        errors.append(abs(ddq[[0, 2, 4]] - out[2][k]).max() / max(1.0, abs(out[2][k]).max()))
        qs.append((q, v, tau))
    q, v, tau = qs[6]
    pin_time = (
        best_time(
            lambda: [
                pin.constraintDynamics(model, data, q, v, tau, constraints, datas, settings)
                for _ in range(1000)
            ]
        )
        / 1000
    )
    rows.append(("Pinocchio constraintDynamics per call (from Python)", pin_time, ""))

    print(f"load average {load()}")
    print(f"{'row':58s} {'time':>12s}  goal")
    for name, seconds, goal in rows:
        shown = f"{seconds * 1e6:9.3f} us"
        print(f"{name:58s} {shown:>12s}  {goal}")
    print(f"ratio Pinocchio constraintDynamics / NOC kernel per pose: {pin_time / per_pose:.0f}x")
    print(f"ratio Pinocchio constraintDynamics / NOC forward dynamics: {pin_time / forward:.2f}x")
    # not a verification: this Pinocchio model's accelerations do not match the path's
    # (the NOC matches an independent Lagrange formulation to 1e-8 in the tests); the
    # figure is printed so that the comparison's model is not mistaken for a verified one
    print(f"Pinocchio's actuated accelerations vs the path's: {max(errors):.2e} (relative)")


if __name__ == "__main__":
    main()

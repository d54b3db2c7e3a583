"""The 3-RRR's NOC torques against Pinocchio's constrained dynamics: the closed chain as a
tree (leg 1 carrying the platform) with legs 2 and 3 closed by point constraints
(``RigidConstraintModel``), driven by the bundled preset's path torques, returns the
path's actuated accelerations (the issue asks 1e-8 of the largest)."""

from __future__ import annotations

import numpy as np

from benchmarks.baselines import ACTUATED_3RRR, joint_state_3rrr, pinocchio_3rrr
from planar_tui.presets import load_preset
from planar_tui.workspace.path.job import pose_si
from planar_tui.workspace.path.quintic import quintic, sample_times
from tests.conftest import PRESETS


def test_pinocchio_constraint_dynamics_follows_the_path_under_the_noc_torques():
    (job,) = load_preset(PRESETS / "path-3rrr.toml").jobs_of("path3rrr")
    robot, spec = job.robot, job.spec
    times = sample_times(spec.duration_s, 40)
    states = quintic(pose_si(spec.from_pose), pose_si(spec.to_pose), spec.duration_s, times)
    solution = spec.mechanism.inverse_dynamics(robot, spec, *states)
    pin, model, data, constraints, datas = pinocchio_3rrr(robot)
    settings = pin.ProximalSettings(1e-14, 1e-10, 100)
    worst = 0.0
    for k in range(len(times)):
        q, v = joint_state_3rrr(
            robot, states[0][k], states[1][k], solution.coordinate[k], solution.rate[k]
        )
        tau = np.zeros(model.nv)
        tau[ACTUATED_3RRR] = solution.effort[k]
        ddq = pin.constraintDynamics(model, data, q, v, tau, constraints, datas, settings)
        worst = max(worst, float(np.abs(ddq[ACTUATED_3RRR] - solution.acceleration[k]).max()))
    scale = float(np.abs(solution.acceleration).max())
    assert scale > 1.0
    assert worst < 1e-8 * scale
    # and a wrong torque is seen: 1 % more on motor 2 changes the accelerations
    tau[ACTUATED_3RRR[1]] *= 1.01
    ddq = pin.constraintDynamics(model, data, q, v, tau, constraints, datas, settings)
    assert np.abs(ddq[ACTUATED_3RRR] - solution.acceleration[-1]).max() > 1e-4 * scale

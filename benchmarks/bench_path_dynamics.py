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
  NOC's torques; its accelerations are compared with the path's (the largest difference,
  relative to the path's largest, is printed; tests/test_path3rrr_pinocchio.py holds it).

Goals (issue 35): <= 1 us per pose on one thread, a 1 000-step path <= 1 ms, and >= 10x
faster than Pinocchio's constrained dynamics per step.
"""

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from planar_tui.runtime import prepare_kernels

prepare_kernels()  # before any kernel is imported

from planar_tui.kernels.dynamics3rrr import rr_path_dynamics

from benchmarks.baselines import ACTUATED_3RRR, joint_state_3rrr, pinocchio_3rrr
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

    pin, model, data, constraints, datas = pinocchio_3rrr(robot)
    settings = pin.ProximalSettings(1e-14, 1e-10, 100)  # mu > 0: the z rows are empty
    errors, qs = [], []
    for k in range(0, 1001, 50):
        q, v = joint_state_3rrr(robot, path[0][k], path[1][k], out[0][k], out[1][k])
        tau = np.zeros(model.nv)
        tau[ACTUATED_3RRR] = out[3][k]
        ddq = pin.constraintDynamics(model, data, q, v, tau, constraints, datas, settings)
        errors.append(abs(ddq[ACTUATED_3RRR] - out[2][k]).max() / abs(out[2]).max())
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
    print(f"Pinocchio's actuated accelerations vs the path's: {max(errors):.2e} (relative)")


if __name__ == "__main__":
    main()

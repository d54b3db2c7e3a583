r"""Forward dynamics in platform coordinates, written once for any robot with
:meth:`~planar_tui.workspace.paving.mechanism.Mechanism.inverse_dynamics`.

The independent coordinates are the platform pose :math:`X` (the state :math:`(X, \dot
X)`); the equation of motion :math:`M_X(X)\ddot X + h(X, \dot X) = A^T\tau` is used in
actuator space, :math:`A^{-T}(M_X\ddot X + h) = \tau`, where both sides come from the
inverse dynamics :math:`\tau_{ID}(X, \dot X, \ddot X) = A^{-T}(M_X\ddot X + h)`, linear in
:math:`\ddot X`: its columns :math:`A^{-T}M_X e_j = \tau_{ID}(X, 0, e_j) - \tau_{ID}(X, 0,
0)` (unit accelerations) and its bias :math:`\tau_{ID}(X, \dot X, 0)`, so

.. math:: \ddot X = \big[A^{-T}M_X\big]^{-1}\big(\tau - \tau_{ID}(X, \dot X, 0)\big),

integrated by classical RK4. The legs are solved exactly from the pose at every
evaluation, so the loop closure holds to machine precision: the largest closure residual
met is reported as the drift. :func:`constant_motion` is a path job's ``constant_efforts``
run: from rest under constant efforts, its poses and rates as a CSV table.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from planar_tui.csvio import CsvTable
from planar_tui.workspace.path.model import OK, problem_text


class PathFailure(ValueError):
    """A state where the inverse dynamics fails (out of reach, singular): ``time_s`` and
    the status's words."""

    def __init__(self, time_s: float, status: int):
        self.time_s = time_s
        self.status = status
        super().__init__(f"at t = {time_s:.6g} s: {problem_text(status)}")


@dataclass(frozen=True)
class Motion:
    """A forward-dynamics run: times (n,), poses and rates (n, d), SI, the largest
    loop-closure residual met (m) and, for a run kept up to a failure, that failure (the
    rows end at the last step before it)."""

    times_s: Any
    pose: Any
    rate: Any
    drift_m: float
    failure: PathFailure | None = None


def acceleration(mechanism: Any, robot: Any, spec: Any, pose: Any, rate: Any, effort: Any) -> Any:
    """:math:`\\ddot X` at the state ``(pose, rate)`` (d,) under the actuator ``effort``
    (module docstring); :class:`PathFailure` (at t = 0) where the pose fails, and the
    closure residual: ``(acceleration, closure_m)``."""
    import numpy as np

    d = len(pose)
    poses = np.repeat(np.asarray(pose, dtype=np.float64)[None, :], d + 2, axis=0)
    rates = np.zeros((d + 2, d))
    rates[0] = rate
    accelerations = np.zeros((d + 2, d))
    accelerations[2:] = np.eye(d)
    solution = mechanism.inverse_dynamics(robot, spec, poses, rates, accelerations)
    bad = solution.status != OK
    if bad.any():
        raise PathFailure(0.0, int(solution.status[bad][0]))
    columns = (solution.effort[2:] - solution.effort[1]).T
    rhs = np.asarray(effort, dtype=np.float64) - solution.effort[0]
    return np.linalg.solve(columns, rhs), float(solution.closure_m.max())


def simulate(
    mechanism: Any,
    robot: Any,
    spec: Any,
    pose: Any,
    rate: Any,
    effort: Callable[[float], Any],
    duration_s: float,
    steps: int,
    on_step: Callable[[int], None] | None = None,
    keep_partial: bool = False,
) -> Motion:
    """RK4 from the state ``(pose, rate)`` over ``duration_s`` in ``steps`` steps, the
    actuators exerting ``effort(t)`` (constant efforts: a function returning them;
    feed-forward: a path's efforts at ``t``); ``on_step(1)`` after each step (a progress
    bar's ``advance``, which may raise :class:`~planar_tui.errors.Cancelled`).
    :class:`PathFailure` names the time a stage fails at; with ``keep_partial`` the
    steps done until then are returned with it (:attr:`Motion.failure`)."""
    import numpy as np

    h = duration_s / steps
    times = np.arange(steps + 1) * h
    poses = np.empty((steps + 1, len(pose)))
    rates = np.empty_like(poses)
    poses[0], rates[0] = pose, rate
    drift = 0.0

    def derivative(t: float, x: Any, v: Any) -> tuple[Any, Any]:
        nonlocal drift
        try:
            a, closure = acceleration(mechanism, robot, spec, x, v, effort(t))
        except PathFailure as failure:
            raise PathFailure(t, failure.status) from None
        drift = max(drift, closure)
        return v, a

    for k in range(steps):
        t, x, v = times[k], poses[k], rates[k]
        try:
            k1x, k1v = derivative(t, x, v)
            k2x, k2v = derivative(t + 0.5 * h, x + 0.5 * h * k1x, v + 0.5 * h * k1v)
            k3x, k3v = derivative(t + 0.5 * h, x + 0.5 * h * k2x, v + 0.5 * h * k2v)
            k4x, k4v = derivative(t + h, x + h * k3x, v + h * k3v)
        except PathFailure as failure:
            if not keep_partial:
                raise
            n = k + 1
            return Motion(times[:n], poses[:n], rates[:n], drift, failure)
        poses[k + 1] = x + h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x)
        rates[k + 1] = v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v)
        if on_step is not None:
            on_step(1)
    return Motion(times, poses, rates, drift)


def forward_header(pose_dimension: int) -> tuple[str, ...]:
    """The ``OUTPUT-forward.csv`` columns: time, pose (cm[, deg]) and its rates."""
    pose = ("x_cm", "y_cm", "phi_deg")[:pose_dimension]
    return ("t_s", *pose, *(f"{name}_s" for name in pose))


def constant_motion(
    mechanism: Any,
    robot: Any,
    spec: Any,
    start: Any,
    on_step: Callable[[int], None] | None = None,
) -> tuple[Any, str]:
    """A path job's ``constant_efforts`` run: :func:`simulate` from rest at ``start`` (SI)
    under ``spec.constant_efforts`` (N m or N) for ``spec.duration_s`` in ``spec.steps``
    steps, kept up to where the platform leaves the workspace. Returns the CSV table
    (:func:`forward_header`, cm and degrees) and the summary's words (the end time and the
    closure drift)."""
    import numpy as np

    efforts = np.asarray(spec.constant_efforts, dtype=np.float64)
    motion = simulate(
        mechanism,
        robot,
        spec,
        np.asarray(start, dtype=np.float64),
        np.zeros(len(start)),
        lambda t: efforts,
        spec.duration_s,
        spec.steps,
        on_step,
        keep_partial=True,
    )
    scale = np.array([100.0, 100.0, 180.0 / np.pi][: len(start)])
    rows = np.column_stack([motion.times_s, motion.pose * scale, motion.rate * scale])
    if motion.failure is None:
        words = f"to t = {motion.times_s[-1]:.6g} s"
    else:
        words = (
            f"the platform leaves the workspace {motion.failure} (the forward CSV stops at "
            f"t = {motion.times_s[-1]:.6g} s)"
        )
    words += f", closure drift {motion.drift_m:.3g} m"
    return CsvTable(forward_header(len(start)), rows), words

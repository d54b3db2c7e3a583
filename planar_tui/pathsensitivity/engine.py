r"""The efforts of every design row along a path, and the outputs the estimators see.

A design row :math:`x \in \prod_j [x_j - \delta_j, x_j + \delta_j]` is a robot
(:func:`~planar_tui.pathsensitivity.inputs.robot_at`); its mechanism's
inverse dynamics gives its efforts :math:`\tau_i(t_k)` at the path's ``steps + 1``
samples, many robots in one kernel call over the whole path (no Python per step, the
robots in parallel; the same numbers as the mechanism's ``inverse_dynamics``). The outputs per row
are, per actuator i, the peak :math:`\max_k |\tau_i(t_k)|`, the RMS
:math:`\sqrt{\frac1T\int_0^T \tau_i^2 dt}` (trapezoidal rule,
:func:`~planar_tui.sensitivity.path.peak_and_rms`, as the serial arm's path study), then
every effort at every step (step-major). A row whose robot cannot follow the path (a leg
that cannot close, a limit, a singularity at some sample) has NaN efforts: a failed run.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from planar_tui.pathsensitivity.inputs import Input, robot_at
from planar_tui.progress import Progress
from planar_tui.sensitivity.path import peak_and_rms
from planar_tui.workspace.path.job import pose_si
from planar_tui.workspace.path.quintic import quintic, sample_times

#: Design rows per kernel call, progress report and cancel check: ~30-60 ms at 1 000 steps
#: on two threads.
ROWS_PER_CALL = 64


@dataclass(frozen=True)
class PathStates:
    """The path's sample times (K + 1,) and platform poses, rates, accelerations (SI)."""

    times_s: np.ndarray
    pose: np.ndarray
    rate: np.ndarray
    acceleration: np.ndarray


def path_states(spec: Any) -> PathStates:
    """The quintic of a path spec (``from_pose``, ``to_pose``, ``duration_s``, ``steps``)."""
    times = sample_times(spec.duration_s, spec.steps)
    pose, rate, acceleration = quintic(
        pose_si(spec.from_pose), pose_si(spec.to_pose), spec.duration_s, times
    )
    return PathStates(times, pose, rate, acceleration)


def scaled(inputs: tuple[Input, ...], unit: np.ndarray) -> np.ndarray:
    """A unit design (S, D) scaled to the inputs' ranges as SALib scales it."""
    nominal = np.array([i.nominal for i in inputs])
    half = np.array([i.half_width for i in inputs])
    lower, upper = nominal - half, nominal + half
    return unit * (upper - lower) + lower


def design_efforts(
    robot: Any,
    spec: Any,
    inputs: tuple[Input, ...],
    rows: np.ndarray,
    states: PathStates,
    progress: Progress | None = None,
    detail: str = "",
) -> np.ndarray:
    """Efforts (S, K + 1, k) of the robots of the design ``rows`` (S, D), NaN where a row's
    path fails: each row's leg rows and body entries (the mechanism's ``path_arrays``), then
    :func:`~planar_tui.kernels.dynamics_robots.robots_path_efforts` over
    :data:`ROWS_PER_CALL` robots at a time, ``progress`` advancing by the fraction done
    after each call."""
    from planar_tui.kernels.dynamics_robots import robots_path_efforts
    from planar_tui.workspace.path.model import SINGULAR_RELATIVE

    mechanism = spec.mechanism
    actuators = mechanism.path_model(robot).actuators
    efforts = np.empty((len(rows), len(states.times_s), actuators))
    pose, rate, acceleration = (
        np.ascontiguousarray(a, dtype=np.float64)
        for a in (states.pose, states.rate, states.acceleration)
    )
    for start in range(0, len(rows), ROWS_PER_CALL):
        stop = min(len(rows), start + ROWS_PER_CALL)
        arrays = [
            mechanism.path_arrays(robot_at(robot, inputs, row), spec) for row in rows[start:stop]
        ]
        family = arrays[0][0]
        legs = np.stack([legs for _, legs, _ in arrays]).astype(np.float64)
        body = np.stack([body for _, _, body in arrays]).astype(np.float64)
        block = efforts[start:stop]
        robots_path_efforts(family, legs, body, pose, rate, acceleration, SINGULAR_RELATIVE, block)
        if progress is not None:
            progress.advance((stop - start) / len(rows), detail)
    return efforts


def path_outputs(efforts: np.ndarray, times_s: np.ndarray) -> np.ndarray:
    """Outputs (S, 2k + (K + 1) k): peak |effort| and RMS effort of each actuator, then
    every effort at every step (step-major), the serial path study's layout."""
    peak, rms = peak_and_rms(efforts, times_s)
    return np.concatenate([peak, rms, efforts.reshape(len(efforts), -1)], axis=1)

"""An independent reference for the certified pose error: Monte-Carlo robots solved by a
vectorised Newton method written here (numeric Jacobians, numpy's batched solve), nothing
of the kernels.

A robot is a list of distance legs: leg ``i`` joins the point ``B_i`` of its actuated chain
to the platform point ``C_i = p + R(phi) c_i`` at the distance ``ell_i`` (the model the
docs state for each robot). Its parameters are a flat vector (:class:`Model`); the errors
are a half-width per parameter. Samples: uniform in the error box, random vertices of it,
and the vertices that the linearised pose error (by finite differences of the solved poses)
makes worst for each pose coordinate, both signs.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import scipy.optimize


@dataclass
class Model:
    """``residual(poses (N, n), params (N, k)) -> (N, n)``: the loop equations of robots
    with parameter vectors ``params`` at ``poses``; ``nominal`` the nominal parameters
    (actuators at the nominal pose's inverse kinematics), ``half_widths`` the errors."""

    residual: Callable[[np.ndarray, np.ndarray], np.ndarray]
    nominal: np.ndarray
    half_widths: np.ndarray


def solve(model: Model, pose: np.ndarray, params: np.ndarray, steps: int = 40) -> np.ndarray:
    """The poses (N, n) of robots ``params`` (N, k) by Newton's method from ``pose``
    (central-difference Jacobian); every one must converge (residual below 1e-9)."""
    x = np.tile(pose, (len(params), 1)).astype(float)
    n = x.shape[1]
    h = 1e-6
    for _ in range(steps):
        f = model.residual(x, params)
        if np.max(np.abs(f)) < 1e-10:
            break
        jac = np.empty((len(x), n, n))
        for j in range(n):
            step = np.zeros(n)
            step[j] = h
            jac[:, :, j] = (model.residual(x + step, params) - model.residual(x - step, params)) / (
                2 * h
            )
        x -= np.linalg.solve(jac, f[..., None])[..., 0]
    assert np.max(np.abs(model.residual(x, params))) < 1e-9, "Newton did not converge"
    return x


def scipy_pose(model: Model, pose: np.ndarray, params: np.ndarray) -> np.ndarray:
    """One robot's pose by ``scipy.optimize.root`` (a cross-check of :func:`solve`)."""
    found = scipy.optimize.root(lambda x: model.residual(x[None], params[None])[0], pose, tol=1e-13)
    assert found.success
    return found.x


def error_samples(model: Model, pose: np.ndarray, count: int, rng) -> np.ndarray:
    """``count`` parameter vectors: a third uniform, a third random vertices, the rest
    random vertices, plus the worst linearised vertices (both signs per pose coordinate)."""
    k = len(model.nominal)
    delta = model.half_widths
    sensitivity = np.empty((len(pose), k))
    for j in range(k):
        if delta[j] == 0:
            sensitivity[:, j] = 0
            continue
        moved = np.tile(model.nominal, (2, 1))
        moved[0, j] += 1e-3 * delta[j]
        moved[1, j] -= 1e-3 * delta[j]
        ahead, behind = solve(model, pose, moved)
        sensitivity[:, j] = (ahead - behind) / (2e-3 * delta[j])
    worst = np.sign(sensitivity) * delta
    uniform = rng.uniform(-1.0, 1.0, (count // 2, k)) * delta
    vertices = rng.choice([-1.0, 1.0], (count - count // 2, k)) * delta
    errors = np.concatenate([uniform, vertices, worst, -worst])
    return model.nominal + errors


def pose_errors(model_at: Callable, points: np.ndarray, count: int, rng) -> np.ndarray:
    """The largest ``|pose - nominal pose|`` per coordinate over ``count`` robots (and the
    worst vertices) at each nominal pose of ``points`` (m, n): ``model_at(point)`` the
    model with the nominal actuators there. Returns (m, n)."""
    worst = []
    for point in points:
        model = model_at(point)
        params = error_samples(model, point, count, rng)
        poses = solve(model, point, params)
        error = np.abs(poses - point)
        check = scipy_pose(model, point, params[-1])
        assert np.allclose(check, poses[-1], atol=1e-9)
        worst.append(error.max(axis=0))
    return np.array(worst)


def box_points(box, extra: int, rng, orientation: float | None = None) -> np.ndarray:
    """The box's corners and centre and ``extra`` uniform points in it, with the pose's
    orientation appended where given."""
    xlo, xhi, ylo, yhi = box
    corners = [
        (xlo, ylo),
        (xlo, yhi),
        (xhi, ylo),
        (xhi, yhi),
        (0.5 * (xlo + xhi), 0.5 * (ylo + yhi)),
    ]
    points = np.array(
        corners + list(zip(rng.uniform(xlo, xhi, extra), rng.uniform(ylo, yhi, extra), strict=True))
    )
    if orientation is None:
        return points
    return np.column_stack([points, np.full(len(points), orientation)])

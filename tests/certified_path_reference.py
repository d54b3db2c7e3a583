"""An independent reference for the certified-path tests: the legs' inverse kinematics in
closed form, κ by central finite differences of it, and a smooth failure margin per time
(positive: valid) whose first root is found with scipy's ``brentq``."""

from __future__ import annotations

import math

import numpy as np

from planar_tui.workspace.path.quintic import quintic


def leg_angles(bases, points, l1, l2, elbow, pose):
    """Per leg ``(theta, cos_beta)`` at ``pose`` (x, y cm, phi rad): theta = alpha + s beta
    (``cos_beta`` outside [-1, 1]: the leg cannot close; theta is then NaN)."""
    x, y, phi = (*pose, 0.0)[:3]
    c, s = math.cos(phi), math.sin(phi)
    out = []
    for (ax, ay), (qx, qy), la, lb, sign in zip(bases, points, l1, l2, elbow, strict=True):
        vx, vy = x + c * qx - s * qy - ax, y + s * qx + c * qy - ay
        rho = math.hypot(vx, vy)
        cos_beta = (rho * rho + la * la - lb * lb) / (2.0 * la * rho)
        beta = math.acos(cos_beta) if abs(cos_beta) <= 1.0 else math.nan
        out.append((math.atan2(vy, vx) + sign * beta, cos_beta))
    return out


def kappa_fd(bases, points, l1, l2, elbow, pose, length_cm, h=1e-6):
    """κ of the matrix of d theta / d(x, y, L phi) by central differences (2 x 2 without
    an orientation)."""
    d = len(pose)
    columns = []
    for j in range(d):
        step = np.zeros(d)
        step[j] = h
        plus = [t for t, _ in leg_angles(bases, points, l1, l2, elbow, np.add(pose, step))]
        minus = [t for t, _ in leg_angles(bases, points, l1, l2, elbow, np.subtract(pose, step))]
        diff = (np.unwrap(np.array([minus, plus]), axis=0)[1] - minus) / (2.0 * h)
        columns.append(diff / length_cm if j == 2 else diff)
    sigma = np.linalg.svd(np.array(columns).T, compute_uv=False)
    return sigma[0] / sigma[-1] if sigma[-1] > 0 else math.inf


def angle_margin(theta, lo, hi):
    """The signed angular distance of ``theta`` inside the arc ``[lo, hi]`` (negative
    outside), the arc taken modulo a turn."""
    t = lo + (theta - lo) % (2.0 * math.pi)
    if t <= hi:
        return min(t - lo, hi - t)
    return -min(t - hi, lo + 2.0 * math.pi - t)


def margin(robot, t, start, stop, duration_s, kappa_max, length_cm):
    """A continuous failure margin at time ``t``: the least of each leg's reach margin
    (1 - |cos beta|), each joint's margin inside its limits (rad) and kappa_max - κ; the
    path is valid at ``t`` iff it is >= 0. ``robot``: ``(bases, points, l1, l2, elbow,
    limits)``."""
    bases, points, l1, l2, elbow, limits = robot
    pose = quintic(start, stop, duration_s, np.array([t]))[0][0]
    worst = math.inf
    for (theta, cos_beta), (lo, hi) in zip(
        leg_angles(bases, points, l1, l2, elbow, pose), limits, strict=True
    ):
        reach = 1.0 - abs(cos_beta)
        if reach < 0.0:
            return reach
        worst = min(worst, reach, angle_margin(theta, lo, hi))
    if worst < 0.0:
        return worst
    return min(
        worst, (kappa_max - kappa_fd(bases, points, l1, l2, elbow, pose, length_cm)) / kappa_max
    )

"""Forward kinematics of a serial planar arm, for drawing it.

With relative joint angles :math:`\\theta_i`, link :math:`k`'s absolute angle is
:math:`\\varphi_k = \\theta_1 + \\dots + \\theta_k` and joint :math:`k`'s end is
:math:`p_k = \\sum_{j \\le k} l_j (\\cos\\varphi_j, \\sin\\varphi_j)`, :math:`p_0 = 0`.
"""

from __future__ import annotations

from typing import Any


def joint_points_m(lengths_m: Any, theta_rad: Any) -> Any:
    """Joint positions (…, n + 1, 2) in metres for relative angles ``theta_rad`` (…, n):
    the base at the origin, then every link's far end (the last is the tip)."""
    import numpy as np

    theta = np.asarray(theta_rad, dtype=float)
    phi = np.cumsum(theta, axis=-1)
    steps = np.stack([np.cos(phi), np.sin(phi)], axis=-1) * np.asarray(lengths_m)[:, None]
    points = np.cumsum(steps, axis=-2)
    zero = np.zeros((*points.shape[:-2], 1, 2))
    return np.concatenate([zero, points], axis=-2)


def draw_arm(ax: Any, points_m: Any, *, colour: Any, alpha: float = 1.0, label=None) -> None:
    """One pose of the arm: links as a line through the joints, joints as dots."""
    ax.plot(
        points_m[:, 0],
        points_m[:, 1],
        "-o",
        color=colour,
        alpha=alpha,
        lw=1.6,
        ms=3,
        label=label,
        gid="arm",
    )

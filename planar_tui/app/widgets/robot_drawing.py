"""A character-cell drawing of a planar serial robot in a given posture (plain text)."""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence


def joint_positions_m(
    lengths_m: Sequence[float], theta_deg: Sequence[float]
) -> list[tuple[float, float]]:
    """Joint positions (base first, tip last) for relative joint angles (paper A eq. 1):
    ``p_{i+1} = p_i + l_i (cos Σ_{j<=i} θ_j, sin Σ_{j<=i} θ_j)``."""
    points = [(0.0, 0.0)]
    angle = 0.0
    for length, theta in zip(lengths_m, theta_deg, strict=False):
        angle += math.radians(theta)
        x, y = points[-1]
        points.append((x + length * math.cos(angle), y + length * math.sin(angle)))
    return points


def draw_serial_robot(
    lengths_m: Sequence[float], theta_deg: Sequence[float], width: int = 36, height: int = 11
) -> str:
    """The robot drawn in ``width × height`` cells: ``#`` base, ``o`` joints, ``.`` links,
    ``+`` tip, ``-`` the ground line through the base (y = 0; gravity points down).

    Cells are about twice as tall as wide, so x is scaled by 2 relative to y.
    """
    theta = list(theta_deg) + [0.0] * (len(lengths_m) - len(theta_deg))
    points = joint_positions_m(lengths_m, theta)
    reach = sum(abs(length) for length in lengths_m) or 1.0
    scale = min((width - 1) / (4 * reach), (height - 1) / (2 * reach))
    centre_col, centre_row = (width - 1) / 2, (height - 1) / 2

    def cell(x: float, y: float) -> tuple[int, int]:
        return round(centre_col + 2 * x * scale), round(centre_row - y * scale)

    grid = [[" "] * width for _ in range(height)]
    for col in range(width):
        grid[round(centre_row)][col] = "-"
    for (x0, y0), (x1, y1) in itertools.pairwise(points):
        c0, r0 = cell(x0, y0)
        c1, r1 = cell(x1, y1)
        steps = max(abs(c1 - c0), abs(r1 - r0), 1)
        for k in range(steps + 1):
            col = round(c0 + (c1 - c0) * k / steps)
            row = round(r0 + (r1 - r0) * k / steps)
            if 0 <= row < height and 0 <= col < width:
                grid[row][col] = "."
    for index, (x, y) in enumerate(points):
        col, row = cell(x, y)
        if 0 <= row < height and 0 <= col < width:
            grid[row][col] = "#" if index == 0 else "+" if index == len(points) - 1 else "o"
    return "\n".join("".join(row).rstrip() for row in grid)

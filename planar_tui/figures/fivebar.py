"""Figure of a five-bar workspace: the kept boxes (inside / boundary), the singular leaves
and the singularity-free circle (:func:`planar_tui.figures.workspace.draw`), the exact
boundary (:func:`planar_tui.workspace.fivebar.robot.workspace_polygon`, inner polygon) and the
robot at a pose inside (legs ``A_i B_i P`` in the working mode, or the first branch
within the limits)."""

from __future__ import annotations

import math
from typing import Any

from planar_tui.figures.workspace import BOUNDARY_SEGMENTS, _polygon_rings, draw, draw_tolerance


def draw_fivebar(ax: Any, robot: Any, point: tuple[float, float]) -> bool:
    """The legs ``A_i, B_i, P`` at ``point`` (False, nothing drawn, if out of reach)."""
    from planar_tui.workspace.fivebar.robot import leg_angles

    joints = []
    for a, l1, angles, sign, (lo, hi) in zip(
        robot.base_joints_cm(),
        robot.proximal_cm,
        leg_angles(robot, point),
        robot.elbows,
        robot.limits_rad,
        strict=True,
    ):
        if angles is None:
            return False
        inside = [s for s in (1, -1) if (angles[s] - lo) % (2 * math.pi) <= hi - lo + 1e-9]
        if not inside or (sign and sign not in inside):
            return False
        theta = angles[sign or inside[0]]
        joints.append((a, (a[0] + l1 * math.cos(theta), a[1] + l1 * math.sin(theta))))
    for a, b in joints:
        ax.plot(
            [a[0], b[0], point[0]],
            [a[1], b[1], point[1]],
            "-o",
            color="#3a5fcd",
            lw=1.6,
            ms=3.5,
            gid="leg",
        )
    ax.plot(*zip(*(a for a, _ in joints), strict=True), "s", color="0.3", gid="base")
    return True


def from_result(job: Any, result: Any) -> Any:
    """The figure of a finished ``[[workspace5r]]`` job (with a tolerance, the overlaid
    workspaces of :func:`~planar_tui.figures.workspace.draw_tolerance`)."""
    import numpy as np

    from planar_tui.workspace.fivebar.robot import workspace_polygon
    from planar_tui.workspace.paving.levels import INSIDE
    from planar_tui.workspace.paving.result import map_title

    outcome = result.outcome
    if getattr(result, "companions", None):
        return draw_tolerance(job, result, workspace_polygon(job.robot, BOUNDARY_SEGMENTS, False))
    boxes = np.asarray(outcome.boxes)[:, :4] if len(outcome.boxes) else np.zeros((0, 4))
    singular = result.singularity
    if singular is not None and singular.centre_cm is None:
        singular = None  # draw() draws the circle with the singular boxes
    fig = draw(
        boxes,
        np.asarray(outcome.status) == INSIDE,
        map_title(job, outcome),
        summary=result.summary,
        singularity=singular,
    )
    ax = fig.axes[0]
    if result.singularity is not None and singular is None:
        b = result.singularity.boxes
        ax.plot(
            0.5 * (b[:, 0] + b[:, 1]),
            0.5 * (b[:, 2] + b[:, 3]),
            ",",
            color="#c0392b",
            gid="singular",
        )
    polygon = workspace_polygon(job.robot, BOUNDARY_SEGMENTS, False)
    for k, ring in enumerate(_polygon_rings(polygon)):
        ax.plot(
            ring[:, 0],
            ring[:, 1],
            color="k",
            lw=1.0,
            gid="exact",
            label="exact boundary" if k == 0 else None,
        )
    if not polygon.is_empty:
        inner = polygon.representative_point()
        draw_fivebar(ax, job.robot, (inner.x, inner.y))
    return fig

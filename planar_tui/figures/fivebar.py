"""Figure of a five-bar workspace: the kept boxes (inside / boundary), the singular leaves
and the singularity-free circle (:func:`planar_tui.figures.workspace.draw`), the exact
boundary (its mechanism's inner polygon) and the robot at a pose inside (legs
``A_i B_i P`` in the working mode, or the first branch within the limits)."""

from __future__ import annotations

import math
from typing import Any

from planar_tui.figures.workspace import BOUNDARY_SEGMENTS, _polygon_rings, draw, draw_tolerance
from planar_tui.workspace.paving.result import map_title


def draw_fivebar(ax: Any, job: Any, point: tuple[float, float]) -> bool:
    """The legs ``A_i, B_i, P`` at ``point`` in the robot's working mode (its mechanism's
    :meth:`~planar_tui.workspace.paving.mechanism.Mechanism.leg_poses`; False, nothing
    drawn, if a leg is out of reach or limits)."""
    robot = job.robot
    legs = job.spec.mechanism.leg_poses(robot, job.spec, point)
    if any(leg is None for leg in legs):
        return False
    joints = []
    for a, l1, (theta, _) in zip(robot.base_joints_cm(), robot.proximal_cm, legs, strict=True):
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


def exact_polygon(job: Any) -> Any:
    """The exact workspace's inner polygon (its mechanism's
    :meth:`~planar_tui.workspace.paving.mechanism.Mechanism.polygon`)."""
    return job.spec.mechanism.polygon(job.robot, job.spec, BOUNDARY_SEGMENTS, False)


def from_result(job: Any, result: Any) -> Any:
    """The figure of a finished ``[[workspace5r]]`` job (with a tolerance, the overlaid
    workspaces of :func:`~planar_tui.figures.workspace.draw_tolerance`)."""
    import numpy as np

    from planar_tui.workspace.paving.levels import INSIDE

    outcome = result.outcome
    if getattr(result, "companions", None):
        return draw_tolerance(job, result, exact_polygon(job))
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
    polygon = exact_polygon(job)
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
        draw_fivebar(ax, job, (inner.x, inner.y))
    return fig

"""Type II singularities and the singularity-free circle of a 3-RPR (``singularities = true``).

The search box is paved by :func:`planar_tui.kernels.singularity3rpr.singular_level` (its
docstring holds the Jacobian and the box test): the kept leaves may hold a singular pose of
the workspace :math:`W`, every singular pose of :math:`W` lies in one. About a centre
:math:`c \\in W` with :math:`\\det A(c) \\ne 0` (default: the centroid of the exact
workspace), :math:`r^* = \\sup\\{r : \\bar D(c, r) \\subseteq W,\\ \\det A \\ne 0
\\text{ on it}\\}` is the distance from :math:`c` to the *bad* set (outside :math:`W`, or
singular), certified as ``r_in <= r* <= r_out``:

* :math:`W` is an intersection of annuli, so the distance from :math:`c` to its complement
  is exactly :math:`m(c) = \\min_i \\min(|c - c_i| - \\underline\\rho_i,
  \\overline\\rho_i - |c - c_i|)` (taken with a round-off margin either way);
* the singular poses of :math:`W` lie in the kept leaves: their least distance to :math:`c`
  bounds the distance to them from below, so ``r_in = min(m, that)``;
* a leaf centre :math:`q` whose determinant is proved of the sign opposite to
  :math:`\\det A(c)` bounds :math:`r^* \\le |q - c|` (on the segment :math:`[c, q]` either
  some point leaves :math:`W` or the continuous determinant vanishes), so
  ``r_out = min(m, those)``.

The circle's columns are the 3-RRR's (:data:`planar_tui.workspace.paving.circle.HEADER`, the
``elbow`` column empty: a 3-RPR has no working modes).
"""

from __future__ import annotations

import math
import time
from typing import Any

from planar_tui.errors import PresetError
from planar_tui.workspace.paving.circle import (
    MARGIN_CM,
    SINGULAR_RELATIVE,
    FreeCircle,
    box_distances,
    given_or_centroid,
)
from planar_tui.workspace.rpr.robot import Robot3RPR, leg_parameters, workspace_polygon


def offsets_cm(robot: Robot3RPR, orientation_rad: float):
    """The (3, 2) array of :math:`r_i = R(\\varphi) q_i`."""
    import numpy as np

    c, s = math.cos(orientation_rad), math.sin(orientation_rad)
    return np.array([[c * qx - s * qy, s * qx + c * qy] for qx, qy in robot.platform_points_cm])


def workspace_margin_cm(robot: Robot3RPR, spec, point) -> float:
    """:math:`m(p)`: the distance from ``point`` to the workspace's complement (negative
    outside)."""
    centres = robot.centres_cm(spec.orientation_rad)
    return min(
        min(
            math.hypot(point[0] - cx, point[1] - cy) - lo,
            hi - math.hypot(point[0] - cx, point[1] - cy),
        )
        for (cx, cy), (lo, hi) in zip(centres, spec.leg_limits_cm, strict=True)
    )


def det_sign(robot: Robot3RPR, spec, point) -> int:
    """The proved sign of :math:`\\det A` at ``point`` (0: within round-off of zero)."""
    import numpy as np

    from planar_tui.kernels.singularity3rpr import points_det_range

    out = np.zeros((1, 2))
    p, offsets = leg_parameters(robot, spec), offsets_cm(robot, spec.orientation_rad)
    points_det_range(np.array([point[0]]), np.array([point[1]]), p, offsets, out)
    return 1 if out[0, 0] > 0.0 else -1 if out[0, 1] < 0.0 else 0


def resolve_centre(job: Any) -> tuple[float, float] | None:
    """The circle's centre of a job with ``singularities`` (``None`` without): the given
    one or the exact workspace's centroid; one off the workspace or on a singularity is a
    :class:`PresetError` (exit code 2), before anything runs."""
    robot, spec = job.robot, job.spec
    if not spec.singularities:
        return None
    key = f"{job.key}.circle_centre_cm"
    expected = "a centre inside the workspace, off its singularities"
    centre = given_or_centroid(job, workspace_polygon)
    where = f"({centre[0]:.6g}, {centre[1]:.6g}) cm"
    if workspace_margin_cm(robot, spec, centre) <= MARGIN_CM:
        raise PresetError(job.preset_path, key, f"{where} is not inside the workspace", expected)
    hi = max(hi for _, hi in spec.leg_limits_cm)
    scale = hi**3 * (1.0 + max(math.hypot(*q) for q in robot.platform_points_cm))
    if abs(float_det(robot, spec, centre)) <= SINGULAR_RELATIVE * scale:
        raise PresetError(job.preset_path, key, f"{where} is on a type II singularity", expected)
    return centre


def float_det(robot: Robot3RPR, spec, point) -> float:
    """:math:`\\det A` at ``point`` in floats (rows :math:`[v_i^T, v_i \times r_i]`)."""
    import numpy as np

    rows = [
        [point[0] - cx, point[1] - cy, (point[0] - cx) * ry - (point[1] - cy) * rx]
        for (cx, cy), (rx, ry) in zip(
            robot.centres_cm(spec.orientation_rad),
            offsets_cm(robot, spec.orientation_rad),
            strict=True,
        )
    ]
    return float(np.linalg.det(np.array(rows)))


def compute_singularities(job: Any, centre, extent, budget: Any) -> FreeCircle:
    """Pave ``extent`` down to ``singularity_precision_cm`` (default ``precision_cm``) and
    bracket the circle about ``centre`` (module docstring)."""
    import numpy as np

    from planar_tui.kernels.singularity3rpr import points_det_range, singular_level
    from planar_tui.workspace.paving.levels import pave_in_levels

    started = time.perf_counter()
    robot, spec = job.robot, job.spec
    p, offsets = leg_parameters(robot, spec), offsets_cm(robot, spec.orientation_rad)
    precision = spec.singularity_precision_cm or spec.precision_cm
    processed = budget.processed

    def decide(rows, start, stop, children, outcome):
        singular_level(p, offsets, precision, rows, start, stop, children, outcome)

    budget.progress.start(1.0, "type II singularities")
    boxes, _ = pave_in_levels(np.array([extent], dtype=np.float64), budget, decide)
    cx, cy = centre
    margin = workspace_margin_cm(robot, spec, centre)
    lo = hi = margin
    sign = det_sign(robot, spec, centre)
    if sign == 0:
        raise PresetError(
            job.preset_path,
            f"{job.key}.circle_centre_cm",
            f"({cx:.6g}, {cy:.6g}) cm cannot be proved off the singularities (within round-off)",
            "a centre inside the workspace, off its singularities",
        )
    if len(boxes):
        lo = min(lo, float(np.min(box_distances(boxes, centre))))
        qx, qy = 0.5 * (boxes[:, 0] + boxes[:, 1]), 0.5 * (boxes[:, 2] + boxes[:, 3])
        det = np.zeros((len(boxes), 2))
        points_det_range(qx, qy, p, offsets, det)
        flips = det[:, 1] < 0.0 if sign > 0 else det[:, 0] > 0.0
        if flips.any():
            hi = min(hi, float(np.min(np.hypot(qx[flips] - cx, qy[flips] - cy))))
    return FreeCircle(
        boxes=boxes,
        centre_cm=(cx, cy),
        radius_lo_cm=max(0.0, lo - MARGIN_CM),
        radius_hi_cm=hi + MARGIN_CM,
        boxes_processed=budget.processed - processed,
        seconds=time.perf_counter() - started,
    )

"""Type II singularities and the singularity-free circle of a 3-PRR (``singularities = true``).

The search box is paved in the working mode ``slider_modes`` (default: the one the strokes
allow at the centre) by :func:`planar_tui.kernels.singularity3prr.prr_singular_level` (its
docstring holds the model, the Jacobian and the box test). About a centre :math:`c` of the
mode's workspace :math:`W_\\sigma` with :math:`\\det A(c) \\ne 0` (default: the exact
workspace's centroid), :math:`r^*` is the distance from :math:`c` to the *bad* set (outside
:math:`W_\\sigma`, or singular), certified as ``r_in <= r* <= r_out`` as for the 3-RRR: every
bad point lies in a kept box or outside the search box, so ``r_in`` is the least distance to
them; a kept box proved all bad, the search box's edge, or a leaf centre proved outside
:math:`W_\\sigma` or with the determinant's sign opposite to the centre's bounds ``r_out``.
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
from planar_tui.workspace.prr.robot import Robot3PRR, workspace_polygon


def slider_rows(robot: Robot3PRR) -> Any:
    """The slider lines' rows ``bx, by, ux, uy, s_lo, s_hi, l`` (3, 7) of the kernels:
    each line's point and direction, its stroke and its distal length."""
    import numpy as np

    rows = [
        [bx, by, math.cos(math.radians(a)), math.sin(math.radians(a)), lo, hi, length]
        for (bx, by), a, (lo, hi), length in zip(
            robot.slider_points_cm,
            robot.slider_angles_deg,
            robot.strokes_cm,
            robot.distal_cm,
            strict=True,
        )
    ]
    return np.array(rows, dtype=np.float64)


def kernel_inputs(robot: Robot3PRR, spec) -> tuple[Any, Any]:
    """``(g, offsets)`` of :mod:`planar_tui.kernels.singularity3prr`: the
    :func:`slider_rows` with each line's point shifted by its leg's platform offset
    :math:`R(\\varphi) q_i`."""
    import numpy as np

    c, s = math.cos(spec.orientation_rad), math.sin(spec.orientation_rad)
    offsets = np.array([[c * qx - s * qy, s * qx + c * qy] for qx, qy in robot.platform_points_cm])
    rows = slider_rows(robot)
    rows[:, :2] -= offsets
    return rows, offsets


def float_links(robot: Robot3PRR, spec, point) -> list[list[tuple[float, float] | None]]:
    """Per leg, per mode ``[+1, -1]``: the distal link :math:`d_i` at ``point`` when the leg
    closes there in that mode within its stroke, else ``None`` (floats)."""
    g, _ = kernel_inputs(robot, spec)
    links: list[list[tuple[float, float] | None]] = []
    for bx, by, ux, uy, lo, hi, length in g:
        wx, wy = point[0] - bx, point[1] - by
        a, h = wx * ux + wy * uy, -wx * uy + wy * ux
        per_mode: list[tuple[float, float] | None] = []
        for sigma in (1.0, -1.0):
            q = length * length - h * h
            ok = q >= 0.0 and lo <= a + sigma * math.sqrt(max(q, 0.0)) <= hi
            root = math.sqrt(max(q, 0.0))
            per_mode.append(
                (-h * uy - sigma * root * ux, h * ux - sigma * root * uy) if ok else None
            )
        links.append(per_mode)
    return links


def resolve_circle(job: Any) -> tuple[tuple[float, float], tuple[int, int, int]] | None:
    """The circle's centre and working modes of a job with ``singularities`` (``None``
    without); a centre no mode reaches, one both modes of a leg reach without
    ``slider_modes``, or one on a singularity, is a :class:`PresetError` (exit code 2)."""
    import numpy as np

    robot, spec = job.robot, job.spec
    if not spec.singularities:
        return None
    key = f"{job.key}.circle_centre_cm"
    expected = "a centre inside the workspace, off its singularities"
    centre = given_or_centroid(job, workspace_polygon)
    where = f"({centre[0]:.6g}, {centre[1]:.6g}) cm"
    modes = []
    for leg, per_mode in enumerate(float_links(robot, spec, centre)):
        reach = [sigma for sigma, link in zip((1, -1), per_mode, strict=True) if link is not None]
        if spec.slider_modes is not None:
            if spec.slider_modes[leg] not in reach:
                raise PresetError(
                    job.preset_path,
                    key,
                    f"{where} is not reachable: leg "
                    f"{leg + 1} cannot close in its mode {spec.slider_modes[leg]:+d} "
                    "within its stroke",
                    expected,
                )
            modes.append(spec.slider_modes[leg])
        elif not reach:
            raise PresetError(
                job.preset_path,
                key,
                f"{where} is not reachable: leg {leg + 1} cannot close within its stroke",
                expected,
            )
        elif len(reach) == 2:
            raise PresetError(
                job.preset_path,
                f"{job.key}.slider_modes",
                f"is not set and leg {leg + 1} reaches {where} in both modes within its stroke",
                "slider_modes = [s1, s2, s3], each 1 or -1",
            )
        else:
            modes.append(reach[0])
    links = [
        per_mode[0 if m > 0 else 1]
        for per_mode, m in zip(float_links(robot, spec, centre), modes, strict=True)
    ]
    _, offsets = kernel_inputs(robot, spec)
    rows = [[dx, dy, dx * ry - dy * rx] for (dx, dy), (rx, ry) in zip(links, offsets, strict=True)]  # type: ignore[misc]
    scale = max(robot.distal_cm) ** 3 * (
        1.0 + max(math.hypot(*q) for q in robot.platform_points_cm)
    )
    if abs(float(np.linalg.det(np.array(rows)))) <= SINGULAR_RELATIVE * scale:
        raise PresetError(job.preset_path, key, f"{where} is on a type II singularity", expected)
    return centre, (modes[0], modes[1], modes[2])


def compute_singularities(job: Any, circle, extent, budget: Any) -> FreeCircle:
    """Pave ``extent`` down to ``singularity_precision_cm`` (default ``precision_cm``) in the
    circle's modes and bracket the circle (module docstring)."""
    import numpy as np

    from planar_tui.kernels.singularity3prr import boxes_status, prr_singular_level
    from planar_tui.kernels.workspace_arc import INSIDE
    from planar_tui.workspace.paving.levels import pave_in_levels

    started = time.perf_counter()
    robot, spec = job.robot, job.spec
    (cx, cy), modes = circle
    g, offsets = kernel_inputs(robot, spec)
    sigma = np.array(modes, dtype=np.float64)
    precision = spec.singularity_precision_cm or spec.precision_cm
    processed = budget.processed
    status = np.zeros((1, 4))
    boxes_status(np.array([[cx, cx, cy, cy]]), g, sigma, offsets, status)
    if status[0, 0] != 1.0 or status[0, 2] <= 0.0 <= status[0, 3]:
        raise PresetError(
            job.preset_path,
            f"{job.key}.circle_centre_cm",
            f"({cx:.6g}, {cy:.6g}) cm cannot be proved reachable and off the "
            "singularities (within round-off)",
            "a centre inside the workspace, off its singularities",
        )
    sign = 1.0 if status[0, 2] > 0.0 else -1.0

    def decide(rows, start, stop, children, outcome):
        prr_singular_level(g, sigma, offsets, precision, rows, start, stop, children, outcome)

    budget.progress.start(1.0, "type II singularities")
    boxes, labels = pave_in_levels(np.array([extent], dtype=np.float64), budget, decide)
    xlo, xhi, ylo, yhi = extent
    lo = hi = max(0.0, min(cx - xlo, xhi - cx, cy - ylo, yhi - cy))
    if len(boxes):
        distance = box_distances(boxes, (cx, cy))
        lo = min(lo, float(distance.min()))
        bad = labels == INSIDE
        if bad.any():
            hi = min(hi, float(distance[bad].min()))
        leaves = ~bad
        qx = 0.5 * (boxes[leaves, 0] + boxes[leaves, 1])
        qy = 0.5 * (boxes[leaves, 2] + boxes[leaves, 3])
        at = np.zeros((len(qx), 4))
        boxes_status(np.column_stack([qx, qx, qy, qy]), g, sigma, offsets, at)
        flips = at[:, 3] < 0.0 if sign > 0 else at[:, 2] > 0.0
        witness = (at[:, 1] == 1.0) | ((at[:, 0] == 1.0) & flips)
        if witness.any():
            hi = min(hi, float(np.min(np.hypot(qx[witness] - cx, qy[witness] - cy))))
    whole = np.zeros((len(boxes), 4))
    boxes_status(np.ascontiguousarray(boxes), g, sigma, offsets, whole)
    singular = (whole[:, 1] == 0.0) & (whole[:, 2] <= 0.0) & (whole[:, 3] >= 0.0)
    return FreeCircle(
        boxes=boxes[singular],
        centre_cm=(cx, cy),
        radius_lo_cm=max(0.0, lo - MARGIN_CM),
        radius_hi_cm=hi + MARGIN_CM,
        boxes_processed=budget.processed - processed,
        seconds=time.perf_counter() - started,
        elbow=" ".join(str(m) for m in modes),
    )

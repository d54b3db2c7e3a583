"""Parallel (type II) singularities and the maximal singularity-free circle of a 3-RRR.

With ``singularities = true`` a single-orientation ``[workspace]`` job also paves the
search box with the interval test of :mod:`planar_tui.kernels.singularity3rrr` (its
docstring holds the model and the proofs): the boxes that may hold a singular pose of the
working mode are drawn on the map (``×``), and the largest closed disc about
``circle_centre_cm`` (default: the centroid of the exact workspace) whose every point the
robot reaches in that mode without a singularity is certified as ``r_in <= r* <= r_out``.

The working mode is ``elbow = [s1, s2, s3]`` (``+1``: :math:`\\theta_i = \\alpha_i +
\\beta_i`, the elbow to the left of the base-to-platform line; ``-1``: to the right) or, by
default, the one the joint limits allow at the centre (a leg with both modes within its
limits there asks for ``elbow``). A centre the robot cannot reach in that mode, or on a
singularity, is refused before any job runs: one line, exit code 2 (``prepare``).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from planar_tui.errors import PresetError
from planar_tui.workspace.paving.circle import (
    SINGULAR_RELATIVE,
    refuse_without_singularities,
)
from planar_tui.workspace.paving.legs import branch_angles, on_arc
from planar_tui.workspace.rrr.orientation import geometry_vector

if TYPE_CHECKING:
    import numpy as np

    from planar_tui.jobkind import Job
    from planar_tui.workspace.paving.levels import BoxBudget
    from planar_tui.workspace.rrr.robot import Robot3RRR

#: Wall time aimed at per kernel chunk.
CHUNK_S = 0.05
#: Leaves are looked at on a LEAF_GRID x LEAF_GRID grid of sub-boxes (sharper locus, r_in).
LEAF_GRID = 4

#: The keys that take the working mode ``elbow`` without ``singularities``.
MODED_KEYS = ("kappa_max", "leg_width_cm", "accuracy")


def check_singularity(values: dict, reader) -> None:
    """``elbow``, ``circle_centre_cm`` and ``singularity_precision_cm`` go with
    ``singularities = true`` (``elbow`` with ``kappa_max``, ``leg_width_cm`` or ``accuracy``
    too, ``circle_centre_cm`` with ``kappa_max``: the dexterous disc's centre), which needs
    a single orientation and a form with boxes."""
    if not values["singularities"]:
        moded = any(values.get(k) is not None for k in MODED_KEYS)
        mode = () if moded else ("elbow",)  # the mode of the MODED_KEYS
        centre = () if values.get("kappa_max") is not None else ("circle_centre_cm",)
        refuse_without_singularities(values, reader, (*mode, *centre, "singularity_precision_cm"))
        return
    if isinstance(values["orientation_deg"], tuple):
        raise reader.error(
            "singularities", "is true with orientation_deg = [lo, hi]", "a single orientation_deg"
        )


def leg_angles(robot, orientation_rad, point):
    """Per leg, :func:`branch_angles` at the platform position ``point``."""
    l1, l2 = robot.proximal_cm, robot.distal_cm
    return [
        branch_angles(point[0] + dx, point[1] + dy, l1, l2)
        for dx, dy in robot.leg_offsets_cm(orientation_rad)
    ]


def det_at(robot, orientation_rad, point, elbow) -> float:
    """:math:`\\det A` at ``point`` in the mode ``elbow`` (rows :math:`[u_i^T, u_i \\times
    r_i]`), in floating point."""
    import numpy as np

    c, s = math.cos(orientation_rad), math.sin(orientation_rad)
    rows = []
    for (qx, qy), (ax, ay), angles, sign in zip(
        robot.platform_points_cm(),
        robot.base_joints_cm(),
        leg_angles(robot, orientation_rad, point),
        elbow,
        strict=True,
    ):
        rx, ry = c * qx - s * qy, s * qx + c * qy
        theta = angles[sign]
        ux = point[0] + rx - ax - robot.proximal_cm * math.cos(theta)
        uy = point[1] + ry - ay - robot.proximal_cm * math.sin(theta)
        rows.append([ux, uy, ux * ry - uy * rx])
    return float(np.linalg.det(np.array(rows)))


def _centroid(robot, spec):
    from planar_tui.workspace.rrr.geometry import workspace_polygon

    polygon = workspace_polygon(robot, spec.limits_rad, spec.orientation_rad, 256, False)
    if polygon.is_empty:
        return None
    point = polygon.centroid
    return (float(point.x), float(point.y))


@dataclass(frozen=True)
class Circle:
    """The singularity-free circle's centre (cm) and the working mode it holds for."""

    x_cm: float
    y_cm: float
    elbow: tuple[int, int, int]


def resolve_circle(job: Job[Any, Robot3RRR]) -> Circle:
    """The circle's centre and working mode of a job with ``singularities``; an
    unreachable or singular centre is a :class:`PresetError` (exit code 2)."""
    spec = job.spec
    key = f"{job.key}.circle_centre_cm"

    def refuse(problem, expected="a centre inside the workspace, off its singularities"):
        return PresetError(job.preset_path, key, problem, expected)

    centre = spec.circle_centre_cm or _centroid(job.robot, spec)
    if centre is None:
        raise refuse("has no default: the workspace is empty", "a non-empty workspace")
    where = f"({centre[0]:.6g}, {centre[1]:.6g}) cm"
    if spec.circle_centre_cm is None:
        where = f"the workspace's centroid {where}"
    angles = leg_angles(job.robot, spec.orientation_rad, centre)
    elbow = []
    for leg, (leg_angle, (lo, hi)) in enumerate(zip(angles, spec.limits_rad, strict=True)):
        modes = [] if leg_angle is None else [s for s in (1, -1) if on_arc(leg_angle[s], lo, hi)]
        if spec.elbow is not None:
            if spec.elbow[leg] not in modes:
                raise refuse(
                    f"{where} is not reachable: leg {leg + 1} cannot close in its elbow "
                    f"{spec.elbow[leg]:+d} mode within its joint limits"
                )
            elbow.append(spec.elbow[leg])
        elif not modes:
            raise refuse(f"{where} is not reachable: leg {leg + 1} cannot close within its limits")
        elif len(modes) == 2 and leg_angle[1] != leg_angle[-1]:
            raise PresetError(
                job.preset_path,
                f"{job.key}.elbow",
                f"is not set and leg {leg + 1} reaches {where} in both working modes "
                "within its joint limits",
                "elbow = [s1, s2, s3], each 1 or -1",
            )
        else:
            elbow.append(modes[0])
    robot = job.robot
    scale = (robot.proximal_cm + robot.distal_cm) ** 3 * (
        1.0 + max(math.hypot(*q) for q in robot.platform_points_cm())
    )
    if abs(det_at(robot, spec.orientation_rad, centre, elbow)) <= SINGULAR_RELATIVE * scale:
        raise refuse(f"{where} is on a type II singularity (det A = 0)")
    return Circle(float(centre[0]), float(centre[1]), (elbow[0], elbow[1], elbow[2]))


# -- the interval paving ------------------------------------------------------------------
@dataclass
class SingularityOutcome:
    """Leaves of the paving (rows ``x_lo, x_hi, y_lo, y_hi``; ``status`` 2 = may hold a
    singular pose, 1 = not proved in the mode's workspace), the circle and its bracket."""

    boxes: np.ndarray
    status: np.ndarray
    centre_cm: tuple[float, float]
    elbow: tuple[int, int, int]
    radius_lo_cm: float
    radius_hi_cm: float
    precision_cm: float
    boxes_processed: int
    seconds: float

    @property
    def singular_boxes(self) -> np.ndarray:
        """The leaves that may hold a singular pose."""
        from planar_tui.kernels.singularity3rrr import SINGULAR

        return self.boxes[self.status == SINGULAR]

    def columns(self) -> list:
        """The summary's :data:`~planar_tui.workspace.paving.circle.HEADER` cells (``elbow`` as ``"1 -1 1"``)."""
        elbow = " ".join(str(s) for s in self.elbow)
        return [*self.centre_cm, self.radius_lo_cm, self.radius_hi_cm, elbow]

    def describe(self) -> str:
        """``singularity-free: r ∈ [lo, hi] cm about (x, y), elbow [+1 -1 +1]``."""
        signs = " ".join(f"{s:+d}" for s in self.elbow)
        return (
            f"singularity-free: r ∈ [{self.radius_lo_cm:.5g}, {self.radius_hi_cm:.5g}] cm "
            f"about ({self.centre_cm[0]:.4g}, {self.centre_cm[1]:.4g}), elbow [{signs}]"
        )


def kernel_inputs(robot, spec, circle: Circle):
    """``(g, r, elbow, limits)`` of :mod:`planar_tui.kernels.singularity3rrr`."""
    import numpy as np

    from planar_tui.kernels.workspace_arc import limits_array

    c, s = math.cos(spec.orientation_rad), math.sin(spec.orientation_rad)
    r = np.array([[c * qx - s * qy, s * qx + c * qy] for qx, qy in robot.platform_points_cm()])
    elbow = np.array(circle.elbow, dtype=np.float64)
    return geometry_vector(robot), r, elbow, limits_array(spec.limits_rad)


def compute_singularities(
    job: Job[Any, Robot3RRR], circle: Circle, extent, budget: BoxBudget
) -> SingularityOutcome:
    """Pave ``extent`` (``x_lo, x_hi, y_lo, y_hi``, holding the workspace) down to
    ``singularity_precision_cm`` (default ``precision_cm``) about ``circle`` (resolved
    by :func:`resolve_circle` when the job was prepared)."""
    import numpy as np

    from planar_tui.kernels.singularity3rrr import box_status, singular_bisect_chunk
    from planar_tui.kernels.workspace3rrr import CHUNK_LIMIT, DONE, KEPT_FULL, STACK_FULL
    from planar_tui.workspace.paving.boxes import grow, xy_area

    started = time.perf_counter()
    progress = budget.progress
    robot, spec = job.robot, job.spec
    g, r, elbow, limits = kernel_inputs(robot, spec, circle)
    cx, cy = circle.x_cm, circle.y_cm
    in_w, _, d_lo, d_hi = box_status(cx, cx, cy, cy, g, r, elbow, limits)
    if not in_w or d_lo <= 0.0 <= d_hi:
        raise PresetError(
            job.preset_path,
            f"{job.key}.circle_centre_cm",
            f"({cx:.6g}, {cy:.6g}) cm cannot be proved reachable and off the singularities "
            "(it lies within round-off of an edge)",
            "a centre inside the workspace, off its singularities",
        )
    sign = 1.0 if d_lo > 0.0 else -1.0
    precision = spec.singularity_precision_cm or spec.precision_cm
    xlo, xhi, ylo, yhi = extent
    edge = max(0.0, min(cx - xlo, xhi - cx, cy - ylo, yhi - cy))
    bounds = np.array([edge, edge])
    stack = np.zeros((256, 4))
    stack[0] = extent
    root_area = xy_area(stack[:1])
    kept = np.zeros((4096, 4))
    status = np.zeros(4096, dtype=np.int64)
    n_stack, n_kept, processed_here, work = 1, 0, 0, 1024  # box tests per call
    progress.start(1.0, "type II singularities")
    while True:
        tic = time.perf_counter()
        n_stack, n_kept, processed, code = singular_bisect_chunk(
            g,
            r,
            elbow,
            limits,
            precision,
            LEAF_GRID,
            cx,
            cy,
            sign,
            stack,
            n_stack,
            kept,
            status,
            n_kept,
            work,
            bounds,
        )
        if code == CHUNK_LIMIT:  # aim at CHUNK_S of work per call
            elapsed = time.perf_counter() - tic
            work = int(min(max(work * CHUNK_S / max(elapsed, 1e-6), 256), 4 * work))
        processed_here += processed
        budget.count(processed, "singularity_precision_cm")
        fraction = 1.0 - xy_area(stack[:n_stack]) / root_area
        progress.advance(
            max(0.0, fraction - progress.completed),
            f"{processed_here:,} boxes, circle radius in [{bounds[0]:.5g}, {bounds[1]:.5g}] cm",
            radius_lower_cm=float(bounds[0]),
            radius_upper_cm=float(bounds[1]),
        )
        if code == DONE:
            break
        if code == KEPT_FULL:
            kept, status = grow(kept), grow(status)
        elif code == STACK_FULL:
            stack = grow(stack)
    return SingularityOutcome(
        boxes=kept[:n_kept].copy(),
        status=status[:n_kept].copy(),
        centre_cm=(cx, cy),
        elbow=circle.elbow,
        radius_lo_cm=float(bounds[0]),
        radius_hi_cm=float(bounds[1]),
        precision_cm=precision,
        boxes_processed=processed_here,
        seconds=time.perf_counter() - started,
    )

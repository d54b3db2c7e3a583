"""Type I and II singularities and the largest singularity-free circle of a five-bar.

With ``singularities = true`` a ``[[workspace5r]]`` job also paves its search box with the
interval tests of :mod:`planar_tui.kernels.singularity5r` (its docstring holds the model
and the proofs): the leaves that may hold a singular point of the workspace (type I, the
leg extended or folded; type II, the distal links aligned; in every working mode when the
robot's is ``any``) are drawn on the map (``×``). With ``singularity_free_circle = [x, y]``
(a working mode needed) the largest closed disc about that centre whose every point the
robot reaches in its mode without a singularity is certified as ``r_in <= r* <= r_out``.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from planar_tui.errors import JobError
from planar_tui.workspace.fivebar.robot import det_at, leg_angles

if TYPE_CHECKING:
    import numpy as np

    from planar_tui.jobkind import Job
    from planar_tui.workspace.fivebar.robot import Robot5R
    from planar_tui.workspace.paving.levels import BoxBudget

#: The summary's singularity columns.
HEADER = (
    "type1_boxes",
    "type2_boxes",
    "circle_centre_x_cm",
    "circle_centre_y_cm",
    "circle_radius_lo_cm",
    "circle_radius_hi_cm",
)
#: |det A| at the centre below this fraction of (l1 + l2)^2 counts as singular.
SINGULAR_RELATIVE = 1e-9


def centre_problem(robot: Robot5R, centre: tuple[float, float]) -> str | None:
    """Why ``centre`` cannot centre a singularity-free circle in the robot's working mode
    (float model), or ``None``."""
    where = f"({centre[0]:.6g}, {centre[1]:.6g}) cm"
    for leg, (angles, (lo, hi), sign) in enumerate(
        zip(leg_angles(robot, centre), robot.limits_rad, robot.elbows, strict=True), start=1
    ):
        if angles is None or (angles[sign] - lo) % (2.0 * math.pi) > hi - lo:
            return f"{where} is not reachable: leg {leg} cannot close in its mode within its limits"
    scale = max(l1 + l2 for l1, l2 in zip(robot.proximal_cm, robot.distal_cm, strict=True)) ** 2
    if abs(det_at(robot, centre, robot.elbows)) <= SINGULAR_RELATIVE * scale:
        return f"{where} is on a type II singularity (det A = 0)"
    return None


@dataclass
class FiveBarSingularities:
    """The leaves that may hold a singular point (rows ``x_lo, x_hi, y_lo, y_hi``, ``kinds``
    the bits 1 = type I, 2 = type II) and the circle's bracket (``None`` without one)."""

    boxes: np.ndarray
    kinds: np.ndarray
    centre_cm: tuple[float, float] | None
    radius_lo_cm: float
    radius_hi_cm: float
    precision_cm: float
    boxes_processed: int
    seconds: float

    @property
    def singular_boxes(self) -> np.ndarray:
        """Every leaf that may hold a singular point (the map's ``×``)."""
        return self.boxes

    def count(self, bit: int) -> int:
        import numpy as np

        return int(np.count_nonzero(self.kinds & bit))

    def columns(self) -> list:
        """The summary's :data:`HEADER` cells."""
        circle: list = ["", "", "", ""]
        if self.centre_cm is not None:
            circle = [*self.centre_cm, self.radius_lo_cm, self.radius_hi_cm]
        return [self.count(1), self.count(2), *circle]

    def describe(self) -> str:
        """``singular boxes: 812 type I, 240 type II; singularity-free: r ∈ [..] cm ...``."""
        text = f"singular boxes: {self.count(1)} type I, {self.count(2)} type II"
        if self.centre_cm is not None:
            text += (
                f"; singularity-free: r ∈ [{self.radius_lo_cm:.5g}, {self.radius_hi_cm:.5g}] cm "
                f"about ({self.centre_cm[0]:.4g}, {self.centre_cm[1]:.4g})"
            )
        return text


def kernel_inputs(robot: Robot5R):
    """``(g, r, modes, limits, legs)`` of :mod:`planar_tui.kernels.singularity5r`."""
    import numpy as np

    legs, limits = robot.leg_arrays()
    g = np.zeros((2, 14))
    for leg in range(2):
        g[leg, 0], g[leg, 1] = robot.proximal_cm[leg], robot.distal_cm[leg]
        g[leg, 8 + 2 * leg : 10 + 2 * leg] = robot.base_joints_cm()[leg]
    everyone = [(1, 1), (1, -1), (-1, 1), (-1, -1)]
    modes = np.array(everyone if robot.working_mode == "any" else [robot.elbows], dtype=float)
    return g, np.zeros((2, 2)), modes, limits, legs


def compute_singularities(job: Job[Any, Robot5R], extent, budget: BoxBudget):
    """Pave ``extent`` (``x_lo, x_hi, y_lo, y_hi``, holding the workspace) down to
    ``singularity_precision_cm`` (default ``precision_cm``), then the circle if asked."""
    import numpy as np

    from planar_tui.kernels.singularity5r import singular_level, tag_kinds
    from planar_tui.workspace.paving.levels import pave_in_levels

    started = time.perf_counter()
    robot, spec = job.robot, job.spec
    g, r, modes, limits, legs = kernel_inputs(robot)
    precision = spec.singularity_precision_cm or spec.precision_cm
    processed = budget.processed

    def decide(rows, start, stop, children, outcome):
        singular_level(g, r, modes, limits, legs, precision, rows, start, stop, children, outcome)

    budget.progress.start(1.0, "type I and II singularities")
    boxes, _ = pave_in_levels(np.array([extent], dtype=float), budget, decide)
    boxes = np.ascontiguousarray(boxes)
    kinds = np.zeros(len(boxes), dtype=np.int64)
    tag_kinds(boxes, g, r, modes, limits, legs, kinds)
    centre = spec.singularity_free_circle
    lo = hi = math.nan
    if centre is not None:
        lo, hi = certify_circle(job, centre, extent, precision, budget)
    seconds = time.perf_counter() - started
    return FiveBarSingularities(
        boxes, kinds, centre, lo, hi, precision, budget.processed - processed, seconds
    )


def certify_circle(job, centre, extent, precision, budget) -> tuple[float, float]:
    """``(r_in, r_out)`` about ``centre`` in the robot's mode (module docstring of
    :mod:`planar_tui.kernels.singularity5r`)."""
    import numpy as np

    from planar_tui.kernels.singularity5r import circle_level, mode_status
    from planar_tui.workspace.paving.levels import BOUNDARY, pave_in_levels

    g, r, _, limits, _ = kernel_inputs(job.robot)
    elbow = np.array(job.robot.elbows, dtype=float)
    cx, cy = centre
    in_w, _, d_lo, d_hi = mode_status(cx, cx, cy, cy, g, r, elbow, limits)
    if not in_w or d_lo <= 0.0 <= d_hi:
        raise JobError(
            job.preset_path,
            f"{job.key}.singularity_free_circle",
            f"({cx:.6g}, {cy:.6g}) cm cannot be proved reachable and off the singularities",
            "a centre inside the workspace, off its singularities",
        )
    sign = 1.0 if d_lo > 0.0 else -1.0
    xlo, xhi, ylo, yhi = extent
    reach = max(0.0, min(cx - xlo, xhi - cx, cy - ylo, yhi - cy))
    upper = [reach]

    def decide(rows, start, stop, children, outcome):
        witness = np.empty(stop - start)
        circle_level(
            g,
            r,
            elbow,
            limits,
            cx,
            cy,
            sign,
            reach,
            precision,
            rows,
            start,
            stop,
            children,
            outcome,
            witness,
        )
        upper.append(float(witness.min(initial=math.inf)))

    budget.progress.start(1.0, "singularity-free circle")
    boxes, status = pave_in_levels(np.array([extent], dtype=float), budget, decide)
    bad = boxes[status == BOUNDARY]
    dx = np.maximum(np.maximum(bad[:, 0] - cx, cx - bad[:, 1]), 0.0)
    dy = np.maximum(np.maximum(bad[:, 2] - cy, cy - bad[:, 3]), 0.0)
    nearest = float(np.hypot(dx, dy).min(initial=reach))
    return max(0.0, np.nextafter(np.nextafter(nearest, 0.0), 0.0)), min(upper)

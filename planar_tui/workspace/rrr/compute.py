"""The 3-RRR's paving stages (paper B): the joint bisection of Algorithm 1, the leg-wise
paving, the arc-distance paving and its classification, and the box estimate; the level-wise
driver and the certified bracket are the core's (:mod:`planar_tui.workspace.paving.levels`)."""

from __future__ import annotations

import math
import time
from typing import Protocol

import numpy as np

from planar_tui.progress import Progress
from planar_tui.workspace.paving.boxes import unique_rows
from planar_tui.workspace.paving.levels import (
    BOUNDARY,
    INSIDE,
    BoxBudget,
    WorkspaceOutcome,
    finished_outcome,
    pave_in_levels,
    report_boxes,
    square_about,
)
from planar_tui.workspace.paving.tolerance import tolerant_vector
from planar_tui.workspace.rrr.forms import INTERVAL_FORMS, kernel_form
from planar_tui.workspace.rrr.geometry import geometric_area, outer_area_and_length
from planar_tui.workspace.rrr.joint import joint_stage
from planar_tui.workspace.rrr.legwise import legwise_stage
from planar_tui.workspace.rrr.robot import Robot3RRR


class Reach(Protocol):
    """A robot whose reach bounds its workspace (:func:`default_search_box`)."""

    def reach_box_cm(self, orientation_rad: float) -> tuple[float, float, float, float]: ...


#: Boxes per kernel call of the joint bisection, all threads together: 10-50 ms of work
#: at the 0.1-0.25 µs a 5-D box takes with the verdict memo on one thread (Table 3's
#: forms); at 50 000 the returns to Python for progress took a tenth of the expanded
#: form's paving.
CHUNK_BOXES = 200_000


#: Leaf check of the arc-distance form: an n x n sub-grid may prove a leaf outside.
LEAF_GRID = 8


def _interval_stage(form_code, p, spec, box, budget) -> np.ndarray:
    """Paper's Algorithm 1 over 5-D boxes on every thread
    (:func:`planar_tui.workspace.rrr.joint.joint_stage`); the kept (x, y) boxes (may repeat)."""
    return joint_stage(
        form_code,
        p,
        spec.precision_cm,
        spec.angle_scale,
        np.array(spec.limits_rad),
        box,
        budget,
        CHUNK_BOXES,
    )


def _arc_stage(p, limits, precision, seeds, budget, inside_cm2=0.0, tol=None):
    """2-D paving with the exact leg-wise test from the (x, y) boxes ``seeds`` (disjoint);
    ``inside_cm2`` is the area already proved inside, for the progress bracket; ``tol``:
    the tolerance-certified test (:mod:`planar_tui.workspace.paving.tolerance`)."""
    from planar_tui.kernels.workspace_arc import arc_level
    from planar_tui.kernels.workspace_tolerance import tolerant_arc_level

    def decide(rows, start, stop, children, outcome):
        if tol is None:
            arc_level(p, limits, precision, LEAF_GRID, rows, start, stop, children, outcome)
        else:
            tolerant_arc_level(
                p, limits, tol, precision, LEAF_GRID, rows, start, stop, children, outcome
            )

    return pave_in_levels(seeds, budget, decide, inside_cm2)


def default_search_box(
    robot: Reach, orientation_rad: float, precision_cm: float
) -> tuple[tuple[float, float], tuple[float, float]]:
    """A square about the reach box whose side is ``precision_cm * 2**n`` (smallest n), so
    that the bisection's leaves are exactly ``precision_cm`` wide."""
    return square_about(robot.reach_box_cm(orientation_rad), precision_cm)


#: Processed boxes per (x, y) cell of side ε of the workspace's area, per 5-D form: an
#: estimate fitted on paper B's Tables 3-5 at ε and ε/2, k = 10 (observed 28-72, expanded
#: natural 915), rounded up.
BOXES_PER_CELL = {"natural": 75.0, "mean-value": 65.0, "slope": 55.0, "expanded": 1000.0}


#: Processed boxes of the arc-distance form per ε of the workspace's boundary length
#: (observed 6.7-7.2 on the same cases).
BOXES_PER_BOUNDARY_STEP = 8.0


#: Leg boxes (x, y, θ_i) the leg-wise paving evaluates per ε of the boundary length, per
#: form: fitted on paper B's Tables 3-5 and the 120° case (observed 67-445
#: with mean-value and slope, 1.5-3x that with natural).
LEG_BOXES_PER_BOUNDARY_STEP = {"natural": 400.0, "mean-value": 180.0, "slope": 180.0}


def estimate_boxes(robot: Robot3RRR, spec) -> int:
    """About how many boxes the bisection will process (0 for ``geometric``), before it runs.

    From the outer polygon of the exact workspace (shapely, 64 segments per turn: a few
    ms, once per geometry: :func:`~planar_tui.workspace.rrr.geometry.outer_area_and_length`):
    its area A and boundary length L. The 5-D forms refine the whole area down to ε, with
    their θ boxes: ``BOXES_PER_CELL[form] · A / ε²``; the arc-distance form proves
    inside boxes early and refines the boundary only: ``BOXES_PER_BOUNDARY_STEP · L / ε``;
    the leg-wise paving too, evaluating a few θ pieces per leg and (x, y) box:
    ``LEG_BOXES_PER_BOUNDARY_STEP[form] · L / ε``;
    a boundary refinement adds the latter at ``refine_precision_cm``. An estimate (within
    about 2x of the counts of paper B's tables), not a bound.
    """
    if spec.form == "geometric":
        return 0
    area, length = outer_area_and_length(robot, spec.limits_rad, spec.orientation_rad, 64)
    eps = spec.precision_cm
    if spec.form == "arc-distance":
        boxes = BOXES_PER_BOUNDARY_STEP * length / eps
    elif spec.strategy == "legwise":
        boxes = (
            LEG_BOXES_PER_BOUNDARY_STEP["natural" if spec.expanded else spec.form] * length / eps
        )
    else:
        per_cell = BOXES_PER_CELL["expanded" if spec.expanded else spec.form]
        boxes = per_cell * area / (eps * eps)
    if spec.refine_precision_cm is not None:
        boxes += BOXES_PER_BOUNDARY_STEP * length / spec.refine_precision_cm
    return math.ceil(boxes) + 1


def report_estimate(robot: Robot3RRR, spec, progress: Progress) -> int:
    """Put :func:`estimate_boxes` in ``progress.figures["boxes_estimate"]`` and warn
    (``progress.warning``) when it exceeds the job's ``box_budget`` (:func:`report_boxes`)."""
    return report_boxes(estimate_boxes(robot, spec), spec, progress)


def kernel_parameters(robot: Robot3RRR, spec) -> np.ndarray:
    """The kernels' parameter vector ``p`` for this robot and orientation."""
    from planar_tui.kernels.workspace3rrr import parameter_vector

    return parameter_vector(
        robot.proximal_cm,
        robot.distal_cm,
        robot.leg_offsets_cm(spec.orientation_rad),
        robot.base_side_cm,
        robot.platform_side_cm,
        spec.orientation_rad,
    )


def compute_workspace(robot: Robot3RRR, spec, budget: BoxBudget) -> WorkspaceOutcome:
    """Run the stages of the module docstring for one robot and spec."""
    from planar_tui.kernels.workspace_arc import classify_boxes, limits_array

    started = time.perf_counter()
    box = spec.search_box_cm or default_search_box(robot, spec.orientation_rad, spec.precision_cm)
    extent = (box[0][0], box[0][1], box[1][0], box[1][1])
    p = kernel_parameters(robot, spec)
    limits = limits_array(spec.limits_rad)
    geometric = None
    if spec.geometric_reference or spec.form == "geometric":
        geometric = geometric_area(robot, spec.limits_rad, spec.orientation_rad)
    if spec.form == "geometric":
        assert geometric is not None
        empty = np.zeros((0, 4))
        return WorkspaceOutcome(
            spec.form,
            spec.precision_cm,
            None,
            empty,
            np.zeros(0, np.int64),
            0,
            geometric.outer_cm2,
            geometric.inner_cm2,
            geometric,
            time.perf_counter() - started,
            extent,
        )

    report_estimate(robot, spec, budget.progress)
    tol = tolerant_vector(spec)  # None: the nominal robot
    interval_form = spec.form in INTERVAL_FORMS
    legwise = interval_form and spec.strategy == "legwise"
    xy_boxes = 0
    budget.progress.start(1.0, f"{spec.form} {'leg-wise paving' if legwise else 'bisection'}")
    if spec.form == "arc-distance":
        boxes, status = _arc_stage(
            p, limits, spec.precision_cm, np.array([extent]), budget, tol=tol
        )
    else:
        code = kernel_form(spec.form, spec.expanded)
        if legwise:
            from planar_tui.kernels.workspace_legwise import (
                NO_TOLERANCE,
                classify_boxes_parallel,
            )

            boxes, proved, xy_boxes = legwise_stage(code, p, spec, box, budget, tol)
            status = np.zeros(len(boxes), dtype=np.int64)
            classify_boxes_parallel(boxes, p, limits, status, NO_TOLERANCE if tol is None else tol)
        else:
            boxes = unique_rows(_interval_stage(code, p, spec, box, budget))
            proved = np.zeros(len(boxes), dtype=np.int64)
            status = np.zeros(len(boxes), dtype=np.int64)
            classify_boxes(boxes, p, limits, status)
        status = np.where((status == INSIDE) | (proved == INSIDE), INSIDE, BOUNDARY)

    def refine(seeds, inside_cm2):
        return _arc_stage(p, limits, spec.refine_precision_cm, seeds, budget, inside_cm2, tol)

    return finished_outcome(
        spec,
        boxes,
        status,
        refine,
        budget,
        geometric,
        started,
        extent,
        form=spec.form + (" (expanded)" if spec.expanded else ""),
        # the leg-wise and arc-distance pavings split boxes into disjoint halves: their
        # union's area is the sum (the sweep of union_area took 0.12 s of Table 3's
        # refined arc-distance job, 135 924 boxes, for the same figure)
        disjoint=legwise or spec.form == "arc-distance",
        strategy=spec.strategy if interval_form else "",
        xy_boxes=xy_boxes,
    )

"""The 3-RRR's separator (:class:`~planar_tui.workspace.paving.mechanism.Mechanism`).

Its leg test is the exact arc-distance test of :mod:`planar_tui.kernels.workspace_arc`
(each leg's reachable annulus sector, the joint limits as arcs); the interval forms of
paper B (the joint bisection and the leg-wise paving, :mod:`.compute`) are its own runner's
stages, ahead of that test. Its ``[workspace]`` job runs its own stages
(:func:`~planar_tui.workspace.rrr.job.run_workspace`), its box estimate is
:func:`~planar_tui.workspace.rrr.compute.estimate_boxes`.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from types import MappingProxyType
from typing import Any

from planar_tui.workspace.path.certify import (
    box_test,
    clearance_test,
    open_limits,
    with_leg_width,
)
from planar_tui.workspace.path.model import PathModel, PathSolution
from planar_tui.workspace.paving.accuracy import range_accuracy
from planar_tui.workspace.paving.interference import range_interference
from planar_tui.workspace.paving.linkage import Linkage, platform_joints, rotated
from planar_tui.workspace.paving.mechanism import Mechanism
from planar_tui.workspace.paving.orientation_dexterity import range_dexterity
from planar_tui.workspace.rrr.orientation import (
    compute_orientation_workspace,
    geometry_vector,
    reach_box_for,
)
from planar_tui.workspace.rrr.pose import leg_modes
from planar_tui.workspace.rrr.robot import TOLERANCE_KEYS_3RRR
from planar_tui.workspace.rrr.singularity import compute_singularities, resolve_circle

# The registry (so the CLI's help) loads this module: the capabilities' modules (dexterity,
# interference, dynamics) are imported in the methods that use them.


class Mechanism3RRR(Mechanism):
    """The 3-RRR of paper B: three RR legs, the active joints' limits as arcs."""

    name = "3-RRR"
    explores = True
    tolerance_keys = TOLERANCE_KEYS_3RRR
    # its own estimate (:func:`planar_tui.workspace.rrr.compute.estimate_boxes`)
    singular_boxes_per_step = 0.0
    tolerance_boxes = MappingProxyType({})
    has_singularities = True
    has_orientation_ranges = True
    has_dexterity = True
    has_interference = True
    accuracy_unit = "deg"

    def parameters(self, robot: Any, spec: Any) -> Any:
        from planar_tui.workspace.rrr.compute import kernel_parameters  # numpy

        return kernel_parameters(robot, spec)

    def level_kernel(self) -> Callable[..., None]:
        from planar_tui.kernels.workspace_arc import arc_level

        return arc_level

    def decider(self, robot: Any, spec: Any, precision_cm: float) -> Callable[..., None]:
        from planar_tui.kernels.workspace_arc import limits_array
        from planar_tui.workspace.rrr.compute import LEAF_GRID

        p, limits = self.parameters(robot, spec), limits_array(spec.limits_rad)
        level = self.level_kernel()

        def decide(rows: Any, start: int, stop: int, children: Any, outcome: Any) -> None:
            level(p, limits, precision_cm, LEAF_GRID, rows, start, stop, children, outcome)

        return decide

    def reach_box(self, robot: Any, spec: Any) -> tuple[float, float, float, float]:
        return reach_box_for(robot, spec.orientation_deg)

    def polygon(self, robot: Any, spec: Any, segments_per_turn: int, outward: bool) -> Any:
        from planar_tui.workspace.rrr.geometry import workspace_polygon  # numpy, shapely

        return workspace_polygon(
            robot, spec.limits_rad, spec.orientation_rad, segments_per_turn, outward
        )

    def resolve_centre(self, job: Any) -> object:
        return resolve_circle(job) if job.spec.singularities else None

    def compute_singularities(self, job: Any, prepared: Any, extent: Any, budget: Any) -> Any:
        return compute_singularities(job, prepared, extent, budget)

    def dexterity(self, job: Any, prepared: Any) -> Callable[[Any], tuple[Any, Any]]:
        from planar_tui.workspace.rrr.dexterity import evaluator

        if isinstance(job.spec.orientation_deg, tuple):
            return range_dexterity(self, job, self.characteristic_length_cm(job.robot, job.spec))
        return evaluator(job.robot, job.spec, prepared.circle)

    def interference(self, job: Any, prepared: Any) -> Callable[[Any], tuple[Any, Any]]:
        from planar_tui.workspace.rrr.interference import evaluator

        if isinstance(job.spec.orientation_deg, tuple):
            return range_interference(self, job)
        return evaluator(job.robot, job.spec, prepared.circle)

    def accuracy(self, job: Any, prepared: Any) -> Callable[[Any], tuple[Any, Any]]:
        from planar_tui.workspace.rrr.accuracy import evaluator, pose_evaluator

        robot, spec = job.robot, job.spec
        if isinstance(spec.orientation_deg, tuple):
            return range_accuracy(self, job, lambda: pose_evaluator(robot, spec, spec.elbow))
        return evaluator(robot, spec, prepared.circle)

    def compute_range(self, robot: Any, spec: Any, budget: Any) -> Any:
        return compute_orientation_workspace(robot, spec, budget)

    def characteristic_length_cm(self, robot: Any, spec: Any) -> float:
        from planar_tui.workspace.rrr.dexterity import length_cm

        return length_cm(robot, spec)

    def path_box_test(self, robot: Any, spec: Any) -> Callable[[Any], tuple[Any, Any, Any]]:
        from planar_tui.kernels.path_certify_rr import rr_pose_boxes  # numba
        from planar_tui.kernels.path_interference_rr import rr_pose_clearance  # numba

        inputs = pose_inputs(robot, spec)
        test = box_test(rr_pose_boxes, *inputs, self.characteristic_length_cm(robot, spec))
        return with_leg_width(test, spec, rr_pose_clearance, *inputs)

    def pose_clearance(self, robot: Any, spec: Any) -> Callable[[Any], tuple[Any, Any]]:
        from planar_tui.kernels.path_interference_rr import rr_pose_clearance  # numba

        width = float(spec.leg_width_cm)
        return clearance_test(rr_pose_clearance, *pose_inputs(robot, spec), width)

    def direct_kinematics(self, robot: Any, actuators: Any) -> Any:
        """The poses at active joint angles ``actuators`` = :math:`\\theta_i` (rad): the
        three-distance problem with bases the elbows
        :math:`A_i + l_1(\\cos\\theta_i, \\sin\\theta_i)` and distances :math:`l_2`."""
        from planar_tui.kernels.direct_kinematics import three_distance_poses  # numpy

        l1, l2 = robot.proximal_cm, robot.distal_cm
        elbows = [
            (ax + l1 * math.cos(theta), ay + l1 * math.sin(theta))
            for (ax, ay), theta in zip(robot.base_joints_cm(), actuators, strict=True)
        ]
        return three_distance_poses(elbows, robot.platform_points_cm(), (l2, l2, l2))

    def path_model(self, robot: Any) -> PathModel:
        return PathModel(pose_dimension=3, actuators=3)

    def inverse_dynamics(
        self, robot: Any, spec: Any, pose: Any, rate: Any, acceleration: Any
    ) -> PathSolution:
        from planar_tui.workspace.rrr.dynamics import solve_path

        return solve_path(robot, spec, pose, rate, acceleration)

    def path_arrays(self, robot: Any, spec: Any) -> tuple[int, Any, Any]:
        from planar_tui.workspace.rrr.dynamics import path_arrays  # numpy

        return path_arrays(robot, spec)

    def linkage(self, robot: Any, pose: Any, actuators: Any) -> Linkage:
        """Legs :math:`A_i \\to A_i + l_1(\\cos\\theta_i, \\sin\\theta_i) \\to C_i`, the base
        triangle as the frame."""
        base = robot.base_joints_cm()
        platform = platform_joints(pose, robot.platform_points_cm())
        legs = tuple(
            (a, rotated(a, robot.proximal_cm, theta), c)
            for a, theta, c in zip(base, actuators, platform, strict=True)
        )
        return Linkage(frame=((*base, base[0]),), legs=legs, platform=platform)

    def pave(self, robot: Any, spec: Any, budget: Any) -> Any:
        from planar_tui.workspace.rrr.compute import compute_workspace  # numpy

        return compute_workspace(robot, spec, budget)

    def leg_poses(
        self, robot: Any, spec: Any, point_cm: tuple[float, float], modes: Any = None
    ) -> list[tuple[float, int] | None]:
        """:func:`~planar_tui.workspace.rrr.pose.leg_modes` at the spec's orientation and
        joint limits (``modes``: the working mode to prefer, the singularity-free circle's)."""
        return leg_modes(robot, spec.orientation_rad, point_cm, spec.limits_rad, modes)


def pose_inputs(robot: Any, spec: Any) -> tuple[Any, Any, Any, Any]:
    """The pose-box kernels' ``(g, q, elbow, limits)``: one geometry row per leg, the
    platform points in its frame, the given ``elbow`` and the joint limits (radians; a full
    turn cuts nothing, :func:`~planar_tui.workspace.path.certify.open_limits`)."""
    import numpy as np

    rows = np.tile(geometry_vector(robot), (3, 1))  # one geometry row per leg
    q = np.array(robot.platform_points_cm(), dtype=np.float64)
    limits = open_limits(spec.limits_rad or ((-np.pi, np.pi),) * 3)
    return rows, q, np.array(spec.elbow, dtype=np.float64), limits


MECHANISM = Mechanism3RRR()

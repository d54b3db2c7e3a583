"""The five-bar's separator (:class:`~planar_tui.workspace.paving.mechanism.Mechanism`):
its reach box and polygon for the estimate, its leg test for the paving."""

from __future__ import annotations

import math
from collections.abc import Callable
from types import MappingProxyType
from typing import Any

from planar_tui.workspace.fivebar.robot import geometric_area, leg_angles, workspace_polygon
from planar_tui.workspace.fivebar.tolerance import TOLERANCE_KEYS_5R, tolerant_level_kernel
from planar_tui.workspace.path.certify import box_test, open_limits, with_leg_width
from planar_tui.workspace.path.model import PathModel, PathSolution
from planar_tui.workspace.paving.linkage import Linkage, rotated
from planar_tui.workspace.paving.mechanism import Mechanism

# The registry (so the CLI's help) loads this module: the capabilities' modules (dexterity,
# interference, dynamics) are imported in the methods that use them.


class MechanismFiveBar(Mechanism):
    """The five-bar's separator (:class:`~planar_tui.workspace.paving.mechanism.Mechanism`):
    the exact leg test of :mod:`planar_tui.kernels.workspace5r` (or its tolerance-certified
    form, :func:`~planar_tui.workspace.fivebar.tolerance.tolerant_level_kernel`); its
    singularities are its job's own (:mod:`.singularity`)."""

    name = "five-bar"
    explores = False
    tolerance_keys = TOLERANCE_KEYS_5R
    singular_boxes_per_step = 20.0
    tolerance_boxes = MappingProxyType({"all": 1.0, "some": 1.0})
    has_singularities = False  # its runner, not the generic one, certifies them
    has_orientation_ranges = False
    has_dexterity = True
    has_interference = True
    accuracy_unit = "deg"

    def parameters(self, robot: Any, spec: Any) -> Any:
        return robot.leg_arrays()

    def level_kernel(self) -> Callable[..., None]:
        from planar_tui.kernels.workspace5r import level

        return level

    def decider(self, robot: Any, spec: Any, precision_cm: float) -> Callable[..., None]:
        (legs, limits), level = self.parameters(robot, spec), self.level_kernel()
        level = tolerant_level_kernel(spec, level)

        def decide(rows: Any, start: int, stop: int, children: Any, outcome: Any) -> None:
            level(legs, limits, precision_cm, rows, start, stop, children, outcome)

        return decide

    def dexterity(self, job: Any, prepared: Any) -> Callable[[Any], tuple[Any, Any]]:
        from planar_tui.workspace.fivebar.dexterity import evaluator

        return evaluator(job.robot, job.spec)

    def interference(self, job: Any, prepared: Any) -> Callable[[Any], tuple[Any, Any]]:
        from planar_tui.workspace.fivebar.interference import evaluator

        return evaluator(job.robot, job.spec)

    def accuracy(self, job: Any, prepared: Any) -> Callable[[Any], tuple[Any, Any]]:
        from planar_tui.workspace.fivebar.accuracy import evaluator

        return evaluator(job.robot, job.spec)

    def reach_box(self, robot: Any, spec: Any) -> tuple[float, float, float, float]:
        return robot.reach_box_cm()

    def polygon(self, robot: Any, spec: Any, segments_per_turn: int, outward: bool) -> Any:
        return workspace_polygon(robot, segments_per_turn, outward)

    def geometric_area(self, robot: Any, spec: Any) -> Any:
        """:func:`~planar_tui.workspace.fivebar.robot.geometric_area` (at most 2^17
        segments per turn)."""
        return geometric_area(robot)

    def path_box_test(self, robot: Any, spec: Any) -> Callable[[Any], tuple[Any, Any, Any]]:
        import numpy as np

        from planar_tui.kernels.path_certify_rr import rr_pose_boxes  # numba
        from planar_tui.kernels.path_interference_rr import rr_pose_clearance  # numba
        from planar_tui.workspace.fivebar.singularity import kernel_inputs

        g, q, _, limits, _ = kernel_inputs(robot)  # q: the point platform's zero offsets
        elbow = np.array(spec.elbow, dtype=np.float64)
        test = box_test(rr_pose_boxes, g, q, elbow, open_limits(limits), 0.0)
        return with_leg_width(test, spec, rr_pose_clearance, g, q, elbow, open_limits(limits))

    def direct_kinematics(self, robot: Any, actuators: Any) -> Any:
        """The end points at joint angles ``actuators`` = :math:`\\theta_1, \\theta_2` (rad):
        the circles of radii :math:`l_{2,i}` about the elbows
        :math:`B_i = A_i + l_{1,i}(\\cos\\theta_i, \\sin\\theta_i)` intersected, an array
        (m, 2), ``m <= 2`` (left of :math:`B_1 \\to B_2` first)."""
        from planar_tui.kernels.direct_kinematics import circle_intersections  # numpy

        (b1, b2) = (
            (ax + l1 * math.cos(theta), ay + l1 * math.sin(theta))
            for (ax, ay), l1, theta in zip(
                robot.base_joints_cm(), robot.proximal_cm, actuators, strict=True
            )
        )
        return circle_intersections(b1, robot.distal_cm[0], b2, robot.distal_cm[1])

    def path_model(self, robot: Any) -> PathModel:
        return PathModel(pose_dimension=2, actuators=2)

    def inverse_dynamics(
        self, robot: Any, spec: Any, pose: Any, rate: Any, acceleration: Any
    ) -> PathSolution:
        from planar_tui.workspace.fivebar.dynamics import solve_path

        return solve_path(robot, spec, pose, rate, acceleration)

    def path_arrays(self, robot: Any, spec: Any) -> tuple[int, Any, Any]:
        from planar_tui.workspace.fivebar.dynamics import path_arrays  # numpy

        return path_arrays(robot, spec)

    def linkage(self, robot: Any, pose: Any, actuators: Any) -> Linkage:
        """Legs :math:`A_i \\to B_i = A_i + l_{1,i}(\\cos\\theta_i, \\sin\\theta_i) \\to P`,
        the base link :math:`A_1A_2` as the frame, no platform."""
        base = robot.base_joints_cm()
        end = (float(pose[0]), float(pose[1]))
        legs = tuple(
            (a, rotated(a, l1, theta), end)
            for a, l1, theta in zip(base, robot.proximal_cm, actuators, strict=True)
        )
        return Linkage(frame=(base,), legs=legs)

    def leg_poses(
        self, robot: Any, spec: Any, point_cm: tuple[float, float], modes: Any = None
    ) -> list[tuple[float, int] | None]:
        """Per leg (``θ = α + sβ``, :func:`~planar_tui.workspace.fivebar.robot.leg_angles`)
        the robot's working mode (``modes``, else its ``elbows``; ``0``: the first of
        ``+1, -1``) within the joint limits; ``None`` where it is not within them."""
        legs: list[tuple[float, int] | None] = []
        for angles, sign, (lo, hi) in zip(
            leg_angles(robot, point_cm), modes or robot.elbows, robot.limits_rad, strict=True
        ):
            if angles is None:
                legs.append(None)
                continue
            inside = [s for s in (1, -1) if (angles[s] - lo) % (2 * math.pi) <= hi - lo + 1e-9]
            mode = sign or (inside[0] if inside else 0)
            legs.append((angles[mode], mode) if mode in inside else None)
        return legs


MECHANISM = MechanismFiveBar()

"""The 3-RPR's separator (:class:`~planar_tui.workspace.paving.mechanism.LegMechanism`), the
:class:`~planar_tui.workspace.paving.runner.PlanarSpec` of its job names."""

from __future__ import annotations

import math
from collections.abc import Callable
from types import MappingProxyType
from typing import Any

from planar_tui.workspace.path.certify import box_test, clearance_test, with_leg_width
from planar_tui.workspace.path.model import PathModel, PathSolution
from planar_tui.workspace.paving.accuracy import range_accuracy
from planar_tui.workspace.paving.interference import range_interference
from planar_tui.workspace.paving.linkage import Linkage, platform_joints
from planar_tui.workspace.paving.mechanism import LegMechanism
from planar_tui.workspace.paving.orientation_dexterity import range_dexterity
from planar_tui.workspace.rpr import orientation, singularity
from planar_tui.workspace.rpr import robot as rpr
from planar_tui.workspace.rpr.tolerance import TOLERANCE_KEYS_3RPR

# The registry (so the CLI's help) loads this module: the capabilities' modules (dexterity,
# interference, dynamics) are imported in the methods that use them.


class Mechanism3RPR(LegMechanism):
    """The 3-RPR's separator: the annulus test of :mod:`planar_tui.kernels.workspace3rpr`, its
    singularities (:mod:`.singularity`) and orientation ranges (:mod:`.orientation`)."""

    name = "3-RPR"
    tolerance_keys = TOLERANCE_KEYS_3RPR
    singular_boxes_per_step = 10.0
    tolerance_boxes = MappingProxyType({"all": 5.0, "some": 5.0})
    has_dexterity = True
    has_tolerant_dexterity = True
    robot_module = rpr
    singularity_module = singularity
    orientation_module = orientation

    has_interference = True
    accuracy_unit = "cm"

    def level_kernel(self) -> Callable[..., None]:
        from planar_tui.kernels.workspace3rpr import rpr_level

        return rpr_level

    def resolve_centre(self, job: Any) -> object:
        return singularity.resolve_centre(job)

    def interference(self, job: Any, prepared: Any) -> Callable[[Any], tuple[Any, Any]]:
        from planar_tui.workspace.rpr.interference import evaluator

        if isinstance(job.spec.orientation_deg, tuple):
            return range_interference(self, job)
        return evaluator(job.robot, job.spec)

    def dexterity(self, job: Any, prepared: Any) -> Callable[[Any], tuple[Any, Any]]:
        from planar_tui.workspace.rpr.dexterity import evaluator

        if isinstance(job.spec.orientation_deg, tuple):
            length = self.characteristic_length_cm(job.robot, job.spec)
            return range_dexterity(self, job, length)
        return evaluator(job.robot, job.spec)

    def accuracy(self, job: Any, prepared: Any) -> Callable[[Any], tuple[Any, Any]]:
        from planar_tui.workspace.rpr.accuracy import evaluator, pose_evaluator

        if isinstance(job.spec.orientation_deg, tuple):
            return range_accuracy(self, job, lambda: pose_evaluator(job.robot, job.spec))
        return evaluator(job.robot, job.spec)

    def path_box_test(self, robot: Any, spec: Any) -> Callable[[Any], tuple[Any, Any, Any]]:
        from planar_tui.kernels.path_certify_prismatic import rpr_pose_boxes  # numba
        from planar_tui.kernels.path_interference_prismatic import rpr_pose_clearance  # numba

        inputs = pose_inputs(robot, spec)
        test = box_test(rpr_pose_boxes, *inputs, self.characteristic_length_cm(robot, spec))
        return with_leg_width(test, spec, rpr_pose_clearance, *inputs)

    def pose_clearance(self, robot: Any, spec: Any) -> Callable[[Any], tuple[Any, Any]]:
        from planar_tui.kernels.path_interference_prismatic import rpr_pose_clearance  # numba

        width = float(spec.leg_width_cm)
        return clearance_test(rpr_pose_clearance, *pose_inputs(robot, spec), width)

    def path_model(self, robot: Any) -> PathModel:
        return PathModel(pose_dimension=3, actuators=3, prismatic=True)

    def inverse_dynamics(
        self, robot: Any, spec: Any, pose: Any, rate: Any, acceleration: Any
    ) -> PathSolution:
        from planar_tui.workspace.rpr.dynamics import solve_path

        return solve_path(robot, spec, pose, rate, acceleration)

    def path_arrays(self, robot: Any, spec: Any) -> tuple[int, Any, Any]:
        from planar_tui.workspace.rpr.dynamics import path_arrays  # numpy

        return path_arrays(robot, spec)

    def direct_kinematics(self, robot: Any, actuators: Any) -> Any:
        """The poses at leg lengths ``actuators`` = :math:`\\rho_i` (cm): the three-distance
        problem with bases :math:`A_i` and distances :math:`\\rho_i`."""
        from planar_tui.kernels.direct_kinematics import three_distance_poses  # numpy

        return three_distance_poses(robot.base_joints_cm, robot.platform_points_cm, actuators)

    def linkage(self, robot: Any, pose: Any, actuators: Any) -> Linkage:
        """Legs :math:`A_i \\to C_i` (their lengths the actuators' :math:`\\rho_i`), the
        base triangle as the frame."""
        base = tuple(robot.base_joints_cm)
        platform = platform_joints(pose, robot.platform_points_cm)
        legs = tuple(zip(base, platform, strict=True))
        return Linkage(frame=((*base, base[0]),), legs=legs, platform=platform)


def pose_inputs(robot: Any, spec: Any) -> tuple[Any, Any, Any]:
    """The pose-box kernels' ``(bases, q, limits)``: the base joints, the platform points in
    its frame and the leg length limits (cm)."""
    import numpy as np

    bases = np.array(robot.base_joints_cm, dtype=np.float64)
    q = np.array(robot.platform_points_cm, dtype=np.float64)
    limits = np.array(spec.leg_limits_cm or ((0.0, math.inf),) * 3, dtype=np.float64)
    return bases, q, limits


MECHANISM = Mechanism3RPR()

"""The 3-PRR's separator (:class:`~planar_tui.workspace.paving.mechanism.LegMechanism`), the
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
from planar_tui.workspace.paving.linkage import Linkage, platform_joints, rotated
from planar_tui.workspace.paving.mechanism import LegMechanism
from planar_tui.workspace.paving.orientation_dexterity import range_dexterity
from planar_tui.workspace.prr import orientation, singularity
from planar_tui.workspace.prr import robot as prr
from planar_tui.workspace.prr.tolerance import TOLERANCE_KEYS_3PRR

# The registry (so the CLI's help) loads this module: the capabilities' modules (dexterity,
# interference, dynamics) are imported in the methods that use them.


class Mechanism3PRR(LegMechanism):
    """The 3-PRR's separator: the slider test of :mod:`planar_tui.kernels.workspace3prr`, its
    singularities (:mod:`.singularity`) and orientation ranges (:mod:`.orientation`)."""

    name = "3-PRR"
    tolerance_keys = TOLERANCE_KEYS_3PRR
    singular_boxes_per_step = 10.0
    tolerance_boxes = MappingProxyType({"all": 5.0, "some": 16.0})
    has_dexterity = True
    has_tolerant_dexterity = True
    robot_module = prr
    singularity_module = singularity
    orientation_module = orientation

    has_interference = True
    accuracy_unit = "cm"

    def level_kernel(self) -> Callable[..., None]:
        from planar_tui.kernels.workspace3prr import prr_level

        return prr_level

    def resolve_centre(self, job: Any) -> object:
        return singularity.resolve_circle(job)

    def dexterity(self, job: Any, prepared: Any) -> Callable[[Any], tuple[Any, Any]]:
        from planar_tui.workspace.prr.dexterity import evaluator, working_modes

        if isinstance(job.spec.orientation_deg, tuple):
            length = self.characteristic_length_cm(job.robot, job.spec)
            return range_dexterity(self, job, length)
        return evaluator(job, working_modes(job, prepared))

    def accuracy(self, job: Any, prepared: Any) -> Callable[[Any], tuple[Any, Any]]:
        from planar_tui.workspace.prr.accuracy import evaluator, pose_evaluator
        from planar_tui.workspace.prr.dexterity import working_modes

        if isinstance(job.spec.orientation_deg, tuple):
            return range_accuracy(self, job, lambda: pose_evaluator(job, job.spec.slider_modes))
        return evaluator(job, working_modes(job, prepared))

    def path_box_test(self, robot: Any, spec: Any) -> Callable[[Any], tuple[Any, Any, Any]]:
        from planar_tui.kernels.path_certify_prismatic import prr_pose_boxes  # numba
        from planar_tui.kernels.path_interference_prismatic import prr_pose_clearance  # numba

        inputs = pose_inputs(robot, spec)
        test = box_test(prr_pose_boxes, *inputs, self.characteristic_length_cm(robot, spec))
        return with_leg_width(test, spec, prr_pose_clearance, *inputs)

    def pose_clearance(self, robot: Any, spec: Any) -> Callable[[Any], tuple[Any, Any]]:
        from planar_tui.kernels.path_interference_prismatic import prr_pose_clearance  # numba

        width = float(spec.leg_width_cm)
        return clearance_test(prr_pose_clearance, *pose_inputs(robot, spec), width)

    def interference(self, job: Any, prepared: Any) -> Callable[[Any], tuple[Any, Any]]:
        from planar_tui.workspace.prr.dexterity import working_modes
        from planar_tui.workspace.prr.interference import evaluator

        if isinstance(job.spec.orientation_deg, tuple):
            return range_interference(self, job)
        return evaluator(job, working_modes(job, prepared))

    def path_model(self, robot: Any) -> PathModel:
        return PathModel(pose_dimension=3, actuators=3, prismatic=True)

    def inverse_dynamics(
        self, robot: Any, spec: Any, pose: Any, rate: Any, acceleration: Any
    ) -> PathSolution:
        from planar_tui.workspace.prr.dynamics import solve_path

        return solve_path(robot, spec, pose, rate, acceleration)

    def path_arrays(self, robot: Any, spec: Any) -> tuple[int, Any, Any]:
        from planar_tui.workspace.prr.dynamics import path_arrays  # numpy

        return path_arrays(robot, spec)

    def direct_kinematics(self, robot: Any, actuators: Any) -> Any:
        """The poses at strokes ``actuators`` = :math:`s_i` (cm): the three-distance problem
        with bases the sliders' joints :math:`B_i + s_i u_i` and distances :math:`l_i`."""
        from planar_tui.kernels.direct_kinematics import three_distance_poses  # numpy

        bases = prr.slider_joints_cm(robot, actuators)
        return three_distance_poses(bases, robot.platform_points_cm, robot.distal_cm)

    def linkage(self, robot: Any, pose: Any, actuators: Any) -> Linkage:
        """Legs from the sliders' joints :math:`B_i + s_i u_i` to :math:`C_i`, the rails
        (each stroke's ends) as the frame."""
        rails = tuple(
            (rotated(b, lo, math.radians(angle)), rotated(b, hi, math.radians(angle)))
            for b, angle, (lo, hi) in zip(
                robot.slider_points_cm, robot.slider_angles_deg, robot.strokes_cm, strict=True
            )
        )
        platform = platform_joints(pose, robot.platform_points_cm)
        legs = tuple(zip(prr.slider_joints_cm(robot, actuators), platform, strict=True))
        return Linkage(frame=rails, legs=legs, platform=platform)


def pose_inputs(robot: Any, spec: Any) -> tuple[Any, Any, Any]:
    """The pose-box kernels' ``(g, modes, q)``: the slider lines' rows (unshifted,
    :func:`~planar_tui.workspace.prr.singularity.slider_rows`), the spec's ``slider_modes``
    and the platform points in its frame."""
    import numpy as np

    modes = np.array(spec.slider_modes, dtype=np.float64)
    q = np.array(robot.platform_points_cm, dtype=np.float64)
    return singularity.slider_rows(robot), modes, q


MECHANISM = Mechanism3PRR()

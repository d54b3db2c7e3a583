"""The 3-PRR's separator (:class:`~planar_tui.workspace.paving.mechanism.Mechanism`), the
:class:`~planar_tui.workspace.paving.runner.PlanarSpec` of its job names."""

from __future__ import annotations

from collections.abc import Callable
from types import MappingProxyType
from typing import Any

from planar_tui.workspace.path.model import PathModel, PathSolution
from planar_tui.workspace.paving.mechanism import Mechanism
from planar_tui.workspace.prr import orientation, singularity
from planar_tui.workspace.prr import robot as prr
from planar_tui.workspace.prr.tolerance import TOLERANCE_KEYS_3PRR


class Mechanism3PRR(Mechanism):
    """The 3-PRR's separator (:class:`~planar_tui.workspace.paving.mechanism.Mechanism`):
    the slider test of :mod:`planar_tui.kernels.workspace3prr`, its singularities
    (:mod:`.singularity`) and orientation ranges (:mod:`.orientation`)."""

    name = "3-PRR"
    explores = False
    tolerance_keys = TOLERANCE_KEYS_3PRR
    singular_boxes_per_step = 10.0
    tolerance_boxes = MappingProxyType({"all": 5.0, "some": 16.0})
    has_singularities = True
    has_orientation_ranges = True
    has_dexterity = True
    has_interference = True

    def parameters(self, robot: Any, spec: Any) -> Any:
        return prr.leg_parameters(robot, spec)

    def level_kernel(self) -> Callable[..., None]:
        from planar_tui.kernels.workspace3prr import prr_level

        return prr_level

    def reach_box(self, robot: Any, spec: Any) -> tuple[float, float, float, float]:
        return prr.reach_box(robot, spec)

    def polygon(self, robot: Any, spec: Any, segments_per_turn: int, outward: bool) -> Any:
        return prr.workspace_polygon(robot, spec, segments_per_turn, outward)

    def resolve_centre(self, job: Any) -> object:
        return singularity.resolve_circle(job)

    def compute_singularities(self, job: Any, prepared: Any, extent: Any, budget: Any) -> Any:
        return singularity.compute_singularities(job, prepared, extent, budget)

    def dexterity(self, job: Any, prepared: Any) -> Callable[[Any], tuple[Any, Any]]:
        from planar_tui.workspace.prr.dexterity import evaluator, working_modes

        return evaluator(job, working_modes(job, prepared))

    def interference(self, job: Any, prepared: Any) -> Callable[[Any], tuple[Any, Any]]:
        from planar_tui.workspace.prr.dexterity import working_modes
        from planar_tui.workspace.prr.interference import evaluator

        return evaluator(job, working_modes(job, prepared))

    def compute_range(self, robot: Any, spec: Any, budget: Any) -> Any:
        return orientation.compute_range(robot, spec, budget)

    def path_model(self, robot: Any) -> PathModel:
        return PathModel(pose_dimension=3, actuators=3, prismatic=True)

    def inverse_dynamics(
        self, robot: Any, spec: Any, pose: Any, rate: Any, acceleration: Any
    ) -> PathSolution:
        from planar_tui.workspace.prr.dynamics import solve_path  # numba

        return solve_path(robot, spec, pose, rate, acceleration)

    def direct_kinematics(self, robot: Any, actuators: Any) -> Any:
        """The poses at strokes ``actuators`` = :math:`s_i` (cm): the three-distance problem
        with bases the sliders' joints :math:`B_i + s_i u_i` and distances :math:`l_i`."""
        from planar_tui.kernels.direct_kinematics import three_distance_poses  # numpy

        bases = prr.slider_joints_cm(robot, actuators)
        return three_distance_poses(bases, robot.platform_points_cm, robot.distal_cm)


MECHANISM = Mechanism3PRR()

"""The 3-RPR's separator (:class:`~planar_tui.workspace.paving.mechanism.Mechanism`), the
:class:`~planar_tui.workspace.paving.runner.PlanarSpec` of its job names."""

from __future__ import annotations

from collections.abc import Callable
from types import MappingProxyType
from typing import Any

from planar_tui.workspace.path.model import PathModel, PathSolution
from planar_tui.workspace.paving.mechanism import Mechanism
from planar_tui.workspace.rpr import orientation, singularity
from planar_tui.workspace.rpr import robot as rpr
from planar_tui.workspace.rpr.tolerance import TOLERANCE_KEYS_3RPR


class Mechanism3RPR(Mechanism):
    """The 3-RPR's separator (:class:`~planar_tui.workspace.paving.mechanism.Mechanism`):
    the annulus test of :mod:`planar_tui.kernels.workspace3rpr`, its singularities
    (:mod:`.singularity`) and orientation ranges (:mod:`.orientation`)."""

    name = "3-RPR"
    explores = False
    tolerance_keys = TOLERANCE_KEYS_3RPR
    singular_boxes_per_step = 10.0
    tolerance_boxes = MappingProxyType({"all": 5.0, "some": 5.0})
    has_singularities = True
    has_orientation_ranges = True
    has_dexterity = True
    has_interference = True

    def parameters(self, robot: Any, spec: Any) -> Any:
        return rpr.leg_parameters(robot, spec)

    def level_kernel(self) -> Callable[..., None]:
        from planar_tui.kernels.workspace3rpr import rpr_level

        return rpr_level

    def reach_box(self, robot: Any, spec: Any) -> tuple[float, float, float, float]:
        return rpr.reach_box(robot, spec)

    def polygon(self, robot: Any, spec: Any, segments_per_turn: int, outward: bool) -> Any:
        return rpr.workspace_polygon(robot, spec, segments_per_turn, outward)

    def resolve_centre(self, job: Any) -> object:
        return singularity.resolve_centre(job)

    def compute_singularities(self, job: Any, prepared: Any, extent: Any, budget: Any) -> Any:
        return singularity.compute_singularities(job, prepared, extent, budget)

    def interference(self, job: Any, prepared: Any) -> Callable[[Any], tuple[Any, Any]]:
        from planar_tui.workspace.rpr.interference import evaluator

        return evaluator(job.robot, job.spec)

    def dexterity(self, job: Any, prepared: Any) -> Callable[[Any], tuple[Any, Any]]:
        from planar_tui.workspace.rpr.dexterity import evaluator

        return evaluator(job.robot, job.spec)

    def compute_range(self, robot: Any, spec: Any, budget: Any) -> Any:
        return orientation.compute_range(robot, spec, budget)

    def path_model(self, robot: Any) -> PathModel:
        return PathModel(pose_dimension=3, actuators=3, prismatic=True)

    def inverse_dynamics(
        self, robot: Any, spec: Any, pose: Any, rate: Any, acceleration: Any
    ) -> PathSolution:
        from planar_tui.workspace.rpr.dynamics import solve_path  # numba

        return solve_path(robot, spec, pose, rate, acceleration)

    def direct_kinematics(self, robot: Any, actuators: Any) -> Any:
        """The poses at leg lengths ``actuators`` = :math:`\\rho_i` (cm): the three-distance
        problem with bases :math:`A_i` and distances :math:`\\rho_i`."""
        from planar_tui.kernels.direct_kinematics import three_distance_poses  # numpy

        return three_distance_poses(robot.base_joints_cm, robot.platform_points_cm, actuators)


MECHANISM = Mechanism3RPR()

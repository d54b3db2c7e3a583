"""The :class:`Mechanism` protocol: what the paving core asks of one parallel robot.

The core paves (x, y) boxes level by level (:func:`~planar_tui.workspace.paving.levels.
pave_in_levels`) and certifies ``|inside| <= exact area <= |kept|``; a robot is the
*separator* it paves with, as codac and pyIbex compose one paver with many separators.
Each robot subpackage (:mod:`planar_tui.workspace.rrr`, :mod:`~planar_tui.workspace.rpr`,
:mod:`~planar_tui.workspace.prr`, :mod:`~planar_tui.workspace.fivebar`) provides one
instance, its specs' ``mechanism``; the core never names a robot.

A new parallel robot is one subpackage (its robot table, its job and its ``Mechanism``),
its kernels (``kernels/``) and its registry lines (:mod:`planar_tui.registry`);
``tests/test_new_mechanism.py`` defines one in a test file.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import TYPE_CHECKING, Any, Protocol, runtime_checkable

from planar_tui.workspace.paving.dexterity import circumradius_cm

if TYPE_CHECKING:
    from planar_tui.workspace.paving.geometry import GeometricArea
    from planar_tui.workspace.paving.linkage import Linkage


@runtime_checkable
class Mechanism(Protocol):
    """One parallel robot's separator: its leg test kernel, reach box, exact polygon,
    singularity test, orientation-range test, tolerance bounds and estimate constants.

    Every method takes the robot (its table's model) and the job's spec. The leg test is
    ``level_kernel()(parameters(robot, spec), precision_cm, rows, start, stop, children,
    outcome)``: one level of the paving in parallel, writing per row ``start + i`` its
    outcome (:func:`~planar_tui.kernels.workspace_arc.settle_xy_box`: inside, boundary,
    outside or split) and its halves. A box it proves inside or outside is never split.

    Later capabilities are methods of this protocol, each written once per robot and never
    inside the core: dexterity (:meth:`dexterity`: the condition number over a box), certified paths
    (a segment inside the singularity-free workspace), dynamics (the platform's inverse
    dynamics) and direct kinematics (the assembly modes at given actuator values).
    """

    #: The robot's name in messages and titles (``"3-RPR"``).
    name: str
    #: Whether the app's workspace tab explores its map (the robot drawn at the cursor).
    explores: bool
    #: The toleranced quantities (the keys of ``tolerances_cm``; ``()``: none).
    tolerance_keys: tuple[str, ...]
    #: The estimate's singularity boxes per ε_s of the search box's width + height
    #: (:mod:`planar_tui.workspace.paving.estimate`).
    singular_boxes_per_step: float
    #: The estimate's boxes per ε² of boundary length × tolerance, by ``tolerance_mode``.
    tolerance_boxes: Mapping[str, float]
    #: Whether it certifies singularities (:meth:`resolve_centre`,
    #: :meth:`compute_singularities`) and paves orientation ranges (:meth:`compute_range`).
    has_singularities: bool
    has_orientation_ranges: bool
    #: Whether it certifies dexterous regions (``kappa_max``, :meth:`dexterity`), and with a
    #: tolerance (:mod:`~planar_tui.workspace.paving.tolerance_dexterity`).
    has_dexterity: bool = False
    has_tolerant_dexterity: bool = False
    #: Whether it certifies interference-free regions (``leg_width_cm``, :meth:`interference`).
    has_interference: bool = False
    #: Its actuators' unit where it certifies its worst-case accuracy (``accuracy``,
    #: :meth:`accuracy`): ``"deg"`` revolute, ``"cm"`` prismatic; ``""``: none.
    accuracy_unit: str = ""

    def parameters(self, robot: Any, spec: Any) -> Any:
        """The leg test kernel's parameter array (its tolerance bounds included)."""
        ...

    def level_kernel(self) -> Callable[..., None]:
        """The leg test kernel (imported when called: kernels load numba)."""
        ...

    def decider(self, robot: Any, spec: Any, precision_cm: float) -> Callable[..., None]:
        """One level's decision ``decide(rows, start, stop, children, outcome)`` at
        ``precision_cm``: the leg test kernel with this robot's parameters bound in (a
        robot whose kernel takes other arguments overrides this)."""
        p, level = self.parameters(robot, spec), self.level_kernel()

        def decide(rows: Any, start: int, stop: int, children: Any, outcome: Any) -> None:
            level(p, precision_cm, rows, start, stop, children, outcome)

        return decide

    def reach_box(self, robot: Any, spec: Any) -> tuple[float, float, float, float]:
        """A box ``(x_lo, x_hi, y_lo, y_hi)`` holding the nominal robot's workspace (empty
        when ``lo > hi``)."""
        ...

    def polygon(self, robot: Any, spec: Any, segments_per_turn: int, outward: bool) -> Any:
        """The inner (``outward=False``) or outer shapely polygon of the exact workspace."""
        ...

    def geometric_area(self, robot: Any, spec: Any) -> GeometricArea:
        """The exact area's bracket from :meth:`polygon`
        (:func:`~planar_tui.workspace.paving.geometry.polygon_bracket`)."""
        from planar_tui.workspace.paving.geometry import polygon_bracket  # numpy

        def polygon(segments: int, outward: bool) -> Any:
            return self.polygon(robot, spec, segments, outward)

        return polygon_bracket(polygon, 2e-5, 1 << 18)

    def resolve_centre(self, job: Any) -> object:
        """The singularity-free circle's centre of a job with ``singularities``, checked
        before anything runs (``None`` without)."""
        return None

    def compute_singularities(self, job: Any, prepared: Any, extent: Any, budget: Any) -> Any:
        """The singular boxes and the certified circle (a
        :class:`~planar_tui.workspace.paving.result.SingularOverlay` with ``columns()``)."""
        problem = f"{self.name} certifies no singularities (has_singularities is false)"
        raise NotImplementedError(problem)

    def dexterity(self, job: Any, prepared: Any) -> Callable[[Any], tuple[Any, Any]]:
        """The κ evaluator of a job with ``kappa_max`` in its working mode (resolved by
        ``prepare``): (k, 4) boxes ``x_lo, x_hi, y_lo, y_hi`` to each box's verdict (0 some
        leg out, 1 unsure, 2 every leg in) and its certified κ enclosure (k, 2)
        (:mod:`planar_tui.workspace.paving.dexterity`)."""
        problem = f"{self.name} certifies no dexterous region (has_dexterity is false)"
        raise NotImplementedError(problem)

    def interference(self, job: Any, prepared: Any) -> Callable[[Any], tuple[Any, Any]]:
        """The clearance evaluator of a job with ``leg_width_cm`` in its working mode
        (resolved by ``prepare``): (k, 4) boxes to each box's verdict (as
        :meth:`dexterity`'s) and its certified gap enclosure (k, 2), cm
        (:mod:`planar_tui.workspace.paving.interference`)."""
        problem = f"{self.name} certifies no interference (has_interference is false)"
        raise NotImplementedError(problem)

    def characteristic_length_cm(self, robot: Any, spec: Any) -> float:
        """:math:`L` weighting the platform's rotation: the spec's
        ``characteristic_length_cm`` or the platform's circumradius (a robot with a
        platform)."""
        problem = f"{self.name} has no platform"
        raise NotImplementedError(problem)

    def pose_clearance(self, robot: Any, spec: Any) -> Callable[[Any], tuple[Any, Any]]:
        """The certified clearance of platform pose boxes with the spec's ``leg_width_cm``
        in its working mode: (k, 6) rows ``x_lo, x_hi, y_lo, y_hi, phi_lo, phi_hi`` (cm,
        rad) to each box's verdict (as :meth:`dexterity`'s) and its gap enclosure (k, 2),
        cm (:mod:`planar_tui.workspace.paving.interference`, over orientation ranges)."""
        problem = f"{self.name} certifies no interference over pose boxes"
        raise NotImplementedError(problem)

    def accuracy(self, job: Any, prepared: Any) -> Callable[[Any], tuple[Any, Any]]:
        """The pose error evaluator of a job with ``accuracy`` in its working mode
        (resolved by ``prepare``): (k, 4) boxes to each box's verdict (as
        :meth:`dexterity`'s) and its certified bounds (k, 3) of :math:`|\\Delta x|`,
        :math:`|\\Delta y|` (cm), :math:`|\\Delta\\varphi|` (rad) ((k, 2) without
        orientation; ``inf`` not certified) over the box's poses and every robot within the
        errors (:mod:`planar_tui.workspace.paving.accuracy`)."""
        problem = f"{self.name} certifies no accuracy (accuracy_unit is empty)"
        raise NotImplementedError(problem)

    def compute_range(self, robot: Any, spec: Any, budget: Any) -> Any:
        """The maximal or total orientation workspace over ``orientation_deg = [lo, hi]``
        (a :class:`~planar_tui.workspace.paving.levels.WorkspaceOutcome`)."""
        problem = f"{self.name} paves no orientation range (has_orientation_ranges is false)"
        raise NotImplementedError(problem)

    def path_box_test(self, robot: Any, spec: Any) -> Callable[[Any], tuple[Any, Any, Any]]:
        """The certified box test of a path job with ``kappa_max`` in its working mode
        (resolved by ``prepare``): (k, 6) pose boxes ``x_lo, x_hi, y_lo, y_hi, phi_lo,
        phi_hi`` (cm, rad) to each box's verdict (0 some leg out, 1 unsure, 2 every leg
        in), the reason of an out box (1 leg, 2 joint or leg limit, 3 interference) and a
        κ enclosure (k, 2) (:mod:`planar_tui.workspace.path.certify`)."""
        problem = f"{self.name} certifies no path"
        raise NotImplementedError(problem)

    def direct_kinematics(self, robot: Any, actuators: Any) -> Any:
        """Every real assembly mode at the actuator values ``actuators`` (revolute joints in
        rad, prismatic ones in cm, one per actuator): an array (m, 3) of platform poses
        ``x_cm, y_cm, phi_rad`` sorted by ``phi_rad`` (a platform-less robot: (m, 2) of
        ``x_cm, y_cm``); m = 0 when the robot cannot be assembled there
        (:mod:`planar_tui.kernels.direct_kinematics`)."""
        raise NotImplementedError(f"{self.name} has no direct kinematics")

    def path_model(self, robot: Any) -> Any:
        """The path columns' shape: a :class:`~planar_tui.workspace.path.model.PathModel`
        (pose dimension, actuators, revolute or prismatic)."""
        problem = f"{self.name} has no path dynamics"
        raise NotImplementedError(problem)

    def inverse_dynamics(
        self, robot: Any, spec: Any, pose: Any, rate: Any, acceleration: Any
    ) -> Any:
        """Path kinematics and inverse dynamics at sampled platform states ((n, d) arrays
        in SI units: m, rad) in the working mode of ``spec``: a
        :class:`~planar_tui.workspace.path.model.PathSolution` (actuator coordinates,
        rates, accelerations, efforts, status and closure residual per time)."""
        problem = f"{self.name} has no path dynamics"
        raise NotImplementedError(problem)

    def path_arrays(self, robot: Any, spec: Any) -> tuple[int, Any, Any]:
        """What :meth:`inverse_dynamics` solves with, for many robots at once
        (:func:`~planar_tui.kernels.dynamics_robots.robots_path_efforts`): the leg family,
        the leg rows and the body entries of ``robot`` in the working mode of ``spec``."""
        problem = f"{self.name} has no path dynamics"
        raise NotImplementedError(problem)

    def linkage(self, robot: Any, pose: Any, actuators: Any) -> Linkage:
        """The robot's bodies for a drawing (a
        :class:`~planar_tui.workspace.paving.linkage.Linkage`, cm) with the platform at
        ``pose`` (``x_cm, y_cm, phi_rad``; a platform-less robot: ``x_cm, y_cm``) and the
        actuators at ``actuators`` (rad or cm, as :meth:`direct_kinematics` takes them)
        that assemble it there: what the app's path tabs play back."""
        raise NotImplementedError(f"{self.name} draws no linkage")

    def pave(self, robot: Any, spec: Any, budget: Any) -> Any:
        """The paving at the spec's one orientation in its own form and search box (a
        :class:`~planar_tui.workspace.paving.levels.WorkspaceOutcome`): what the app's
        live preview of a map it ``explores`` runs."""
        problem = f"{self.name} has no live preview (explores is false)"
        raise NotImplementedError(problem)

    def leg_poses(
        self, robot: Any, spec: Any, point_cm: tuple[float, float], modes: Any = None
    ) -> list[tuple[float, int] | None]:
        """Per leg, the active joint's angle (rad) and its working mode with the platform at
        ``point_cm``, within the joint limits (the mode ``modes[i]`` where given; else as
        the robot chooses), or ``None`` where the leg cannot close there: the robot a
        figure or the app draws at a point."""
        problem = f"{self.name} draws no legs"
        raise NotImplementedError(problem)


class LegMechanism(Mechanism):
    """A separator whose parts are its robot subpackage's functions (the 3-RPR's and the
    3-PRR's, whose leg test kernels share the signature of
    :func:`~planar_tui.kernels.workspace3rpr.rpr_level`). A subclass sets its constants
    (:class:`Mechanism`'s), its kernel (:meth:`level_kernel`), its singularity-free
    circle's check (:meth:`resolve_centre`) and three modules of its subpackage:
    ``robot_module`` (``leg_parameters(robot, spec)``, ``reach_box(robot, spec)``,
    ``workspace_polygon(robot, spec, segments_per_turn, outward)``),
    ``singularity_module`` (``compute_singularities(job, prepared, extent, budget)``) and
    ``orientation_module`` (``compute_range(robot, spec, budget)``)."""

    explores = False
    has_singularities = True
    has_orientation_ranges = True
    robot_module: Any
    singularity_module: Any
    orientation_module: Any

    def parameters(self, robot: Any, spec: Any) -> Any:
        return self.robot_module.leg_parameters(robot, spec)

    def reach_box(self, robot: Any, spec: Any) -> tuple[float, float, float, float]:
        box: tuple[float, float, float, float] = self.robot_module.reach_box(robot, spec)
        return box

    def polygon(self, robot: Any, spec: Any, segments_per_turn: int, outward: bool) -> Any:
        return self.robot_module.workspace_polygon(robot, spec, segments_per_turn, outward)

    def compute_singularities(self, job: Any, prepared: Any, extent: Any, budget: Any) -> Any:
        return self.singularity_module.compute_singularities(job, prepared, extent, budget)

    def compute_range(self, robot: Any, spec: Any, budget: Any) -> Any:
        return self.orientation_module.compute_range(robot, spec, budget)

    def characteristic_length_cm(self, robot: Any, spec: Any) -> float:
        return spec.characteristic_length_cm or circumradius_cm(robot.platform_points_cm)


__all__ = ["LegMechanism", "Mechanism"]

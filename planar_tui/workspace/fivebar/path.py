"""The ``[[path5r]]`` job: the five-bar's actuator torques along a quintic path of its
end-effector joint ``P`` (:mod:`planar_tui.workspace.path.job`, the equations in
:mod:`planar_tui.kernels.dynamics5r`), its masses and joint limits from ``[robot5r]``."""

from __future__ import annotations

from dataclasses import dataclass, replace

from planar_tui.jobkind import Job
from planar_tui.schema import TableReader, plot_setting, setting
from planar_tui.workspace.fivebar.mechanism import MECHANISM
from planar_tui.workspace.fivebar.robot import Robot5R, leg_angles
from planar_tui.workspace.path.certify import kappa_setting, width_setting
from planar_tui.workspace.path.job import (
    PathSpec,
    constant_efforts_setting,
    feed_forward_setting,
    path_job_kind,
    pose_setting,
    resolved_modes,
)
from planar_tui.workspace.paving.legs import closing_modes

ELBOW_DOC = "2 signs, each 1 or -1"


def _elbow(reader: TableReader, name, default, robot, values):
    """Two elbow signs, each ``1`` or ``-1``."""
    if not reader.has(name):
        return default
    signs = reader.numbers(name, length=2, items_doc=ELBOW_DOC)
    if any(s not in (1.0, -1.0) for s in signs):
        raise reader.error(name, f"is {list(signs)}", ELBOW_DOC)
    return tuple(int(s) for s in signs)


@dataclass(frozen=True, kw_only=True)
class Path5RSpec(PathSpec):
    """A quintic rest-to-rest path of the five-bar's end-effector joint (cm, seconds)."""

    from_pose: tuple[float, ...] = pose_setting(2, "the point P at t = 0")
    to_pose: tuple[float, ...] = pose_setting(2, "the point P at t = duration_s")
    elbow: tuple[int, int] | None = setting(
        _elbow,
        default=None,
        default_doc="(the robot's working_mode, else the mode the limits allow at from_pose)",
        type_doc="2 signs, each `1` or `-1`",
        doc="working mode per leg: θ = α + β (`1`) or α − β (`-1`)",
    )
    feed_forward: bool = feed_forward_setting()
    constant_efforts: tuple[float, ...] | None = constant_efforts_setting(2, "N m")
    kappa_max: float | None = kappa_setting()
    leg_width_cm: float | None = width_setting()
    plot: str | None = plot_setting()

    mechanism = MECHANISM


def prepare_path(job: Job[Path5RSpec, Robot5R]) -> Path5RSpec:
    """The spec with its working mode resolved: ``elbow`` as given, else the robot's
    ``working_mode``, else per leg the mode the limits allow at ``from_pose`` (a leg with
    both asks for ``elbow``: exit code 2; one with none is left to fail the run at t = 0)."""
    spec, robot = job.spec, job.robot
    if spec.elbow is not None:
        return spec
    if robot.working_mode != "any":
        return replace(spec, elbow=robot.elbows)
    per_leg = [
        closing_modes(angles, lo, hi)
        for angles, (lo, hi) in zip(
            leg_angles(robot, spec.from_pose), robot.limits_rad, strict=True
        )
    ]
    example = "elbow = [s1, s2], each 1 or -1 (or the robot's working_mode)"
    elbow = resolved_modes(job, "elbow", per_leg, example)
    return replace(spec, elbow=(elbow[0], elbow[1]))


JOB_KIND = path_job_kind(
    "path5r",
    "robot5r",
    Path5RSpec,
    "five-bar",
    prepare_path,
    "[[path5r]]\nfrom_pose = [0, 60]\nto_pose = [5, 65]\nsteps = 4\nkappa_max = 1000\n",
)

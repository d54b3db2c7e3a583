"""The ``[[path3rrr]]`` job: the 3-RRR's actuator torques along a quintic platform path
(:mod:`planar_tui.workspace.path.job`, the equations in
:mod:`planar_tui.kernels.dynamics3rrr`), its masses from ``[robot3rrr]``."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from planar_tui.jobkind import Job
from planar_tui.schema import TableReader, plot_setting, setting
from planar_tui.workspace.path.certify import kappa_setting, width_setting
from planar_tui.workspace.path.job import (
    PathSpec,
    constant_efforts_setting,
    feed_forward_setting,
    path_job_kind,
    resolved_modes,
)
from planar_tui.workspace.paving.dexterity import length_setting
from planar_tui.workspace.paving.legs import closing_modes
from planar_tui.workspace.paving.settings import modes_setting
from planar_tui.workspace.rrr.job import _joint_limits
from planar_tui.workspace.rrr.mechanism import MECHANISM
from planar_tui.workspace.rrr.robot import Robot3RRR
from planar_tui.workspace.rrr.singularity import leg_angles


def _optional_limits(reader: TableReader, name, default, robot, values):
    """The workspace job's ``joint_limits_deg`` where given; ``None``: no limits."""
    return _joint_limits(reader, name, default, robot, values) if reader.has(name) else None


@dataclass(frozen=True, kw_only=True)
class Path3RRRSpec(PathSpec):
    """A quintic rest-to-rest path of the 3-RRR's platform (cm, degrees, seconds)."""

    elbow: tuple[int, int, int] | None = modes_setting(
        default_doc="(the mode the limits allow at from_pose)"
    )
    joint_limits_deg: tuple[tuple[float, float], ...] | None = setting(
        _optional_limits,
        default=None,
        default_doc="(none)",
        type_doc="3 rows `[min, max]`",
        doc="active-joint limits θ1, θ2, θ3, as the workspace job's",
    )
    feed_forward: bool = feed_forward_setting()
    constant_efforts: tuple[float, ...] | None = constant_efforts_setting(3, "N m")
    kappa_max: float | None = kappa_setting()
    characteristic_length_cm: float | None = length_setting()
    leg_width_cm: float | None = width_setting()
    plot: str | None = plot_setting()

    mechanism = MECHANISM

    @property
    def limits_rad(self) -> tuple[tuple[float, float], ...] | None:
        """Joint limits in radians (``None``: none)."""
        if self.joint_limits_deg is None:
            return None
        return tuple((math.radians(lo), math.radians(hi)) for lo, hi in self.joint_limits_deg)


def prepare_path(job: Job[Path3RRRSpec, Robot3RRR]) -> Path3RRRSpec:
    """The spec with its working mode resolved: ``elbow`` as given, else per leg the mode
    the limits allow at ``from_pose`` (a leg with both asks for ``elbow``: exit code 2; a
    leg with none is left to fail the run at t = 0)."""
    spec = job.spec
    x, y, phi = spec.from_pose
    if spec.elbow is not None:
        return spec
    limits = spec.limits_rad or ((0.0, 2.0 * math.pi),) * 3
    per_leg = [
        closing_modes(angles, lo, hi)
        for angles, (lo, hi) in zip(
            leg_angles(job.robot, math.radians(phi), (x, y)), limits, strict=True
        )
    ]
    elbow = resolved_modes(job, "elbow", per_leg, "elbow = [s1, s2, s3], each 1 or -1")
    return replace(spec, elbow=(elbow[0], elbow[1], elbow[2]))


JOB_KIND = path_job_kind(
    "path3rrr",
    "robot3rrr",
    Path3RRRSpec,
    "3-RRR",
    prepare_path,
    "[[path3rrr]]\nfrom_pose = [40, 21, 0]\nto_pose = [42, 23, 5]\nsteps = 4\nelbow = [1, 1, 1]\n"
    "kappa_max = 1000\n",
)

"""The ``[[path3rpr]]`` job: the 3-RPR's leg forces along a quintic platform path
(:mod:`planar_tui.workspace.path.job`, the equations in :mod:`planar_tui.kernels.dynamics3rpr`),
its masses from ``[robot3rpr]``. The legs' lengths follow from the pose: no working mode."""

from __future__ import annotations

from dataclasses import dataclass

from planar_tui.jobkind import Job
from planar_tui.schema import TableReader, plot_setting, setting
from planar_tui.workspace.path.certify import kappa_setting, width_setting
from planar_tui.workspace.path.job import (
    PathSpec,
    constant_efforts_setting,
    feed_forward_setting,
    path_job_kind,
)
from planar_tui.workspace.paving.dexterity import length_setting
from planar_tui.workspace.rpr.job import _leg_limits
from planar_tui.workspace.rpr.mechanism import MECHANISM
from planar_tui.workspace.rpr.robot import Robot3RPR


def _optional_leg_limits(reader: TableReader, name, default, robot, values):
    """The workspace job's ``leg_limits_cm`` where given; ``None``: no limits."""
    return _leg_limits(reader, name, default, robot, values) if reader.has(name) else None


@dataclass(frozen=True, kw_only=True)
class Path3RPRSpec(PathSpec):
    """A quintic rest-to-rest path of the 3-RPR's platform (cm, degrees, seconds)."""

    leg_limits_cm: tuple[tuple[float, float], ...] | None = setting(
        _optional_leg_limits,
        default=None,
        default_doc="(none)",
        type_doc="3 rows `[lo, hi]`, 0 ≤ lo < hi",
        doc="actuated leg lengths ρ1, ρ2, ρ3, as the workspace job's",
    )
    feed_forward: bool = feed_forward_setting()
    constant_efforts: tuple[float, ...] | None = constant_efforts_setting(3, "N")
    kappa_max: float | None = kappa_setting()
    characteristic_length_cm: float | None = length_setting()
    leg_width_cm: float | None = width_setting()
    plot: str | None = plot_setting()

    mechanism = MECHANISM


def prepare_path(job: Job[Path3RPRSpec, Robot3RPR]) -> Path3RPRSpec:
    """The spec as read: a 3-RPR's legs have one length per pose."""
    return job.spec


JOB_KIND = path_job_kind(
    "path3rpr",
    "robot3rpr",
    Path3RPRSpec,
    "3-RPR",
    prepare_path,
    "[[path3rpr]]\nfrom_pose = [35, 15, 0]\nto_pose = [37, 17, 5]\nsteps = 4\nkappa_max = 1000\n",
)

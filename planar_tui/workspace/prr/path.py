"""The ``[[path3prr]]`` job: the 3-PRR's slider forces along a quintic platform path
(:mod:`planar_tui.workspace.path.job`, the equations in :mod:`planar_tui.kernels.dynamics3prr`),
its masses and strokes from ``[robot3prr]``. The actuated coordinate is each slider's stroke
along its rail, the CSV's ``rho1_cm`` ... (a prismatic actuator's column names)."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from types import SimpleNamespace

from planar_tui.jobkind import Job
from planar_tui.schema import plot_setting
from planar_tui.workspace.path.certify import kappa_setting, width_setting
from planar_tui.workspace.path.job import (
    PathSpec,
    constant_efforts_setting,
    feed_forward_setting,
    path_job_kind,
    resolved_modes,
)
from planar_tui.workspace.paving.dexterity import length_setting
from planar_tui.workspace.paving.settings import modes_setting
from planar_tui.workspace.prr.mechanism import MECHANISM
from planar_tui.workspace.prr.robot import Robot3PRR
from planar_tui.workspace.prr.singularity import float_links


@dataclass(frozen=True, kw_only=True)
class Path3PRRSpec(PathSpec):
    """A quintic rest-to-rest path of the 3-PRR's platform (cm, degrees, seconds)."""

    slider_modes: tuple[int, int, int] | None = modes_setting(
        name="slider_modes",
        default_doc="(the mode the strokes allow at from_pose)",
        doc="working mode per leg, as the workspace job's: the slider ahead (`1`) or behind "
        "(`-1`) the foot of the perpendicular from the platform joint to its line",
    )
    feed_forward: bool = feed_forward_setting()
    constant_efforts: tuple[float, ...] | None = constant_efforts_setting(3, "N")
    kappa_max: float | None = kappa_setting()
    characteristic_length_cm: float | None = length_setting()
    leg_width_cm: float | None = width_setting()
    plot: str | None = plot_setting()

    mechanism = MECHANISM


def prepare_path(job: Job[Path3PRRSpec, Robot3PRR]) -> Path3PRRSpec:
    """The spec with its working mode resolved: ``slider_modes`` as given, else per leg the
    mode the strokes allow at ``from_pose`` (a leg with both asks for ``slider_modes``:
    exit code 2; a leg with none is left to fail the run at t = 0)."""
    spec = job.spec
    if spec.slider_modes is not None:
        return spec
    x, y, phi = spec.from_pose
    at = SimpleNamespace(orientation_rad=math.radians(phi))
    per_leg = [
        [s for s, link in zip((1, -1), per_mode, strict=True) if link is not None][
            : 1 if per_mode[0] == per_mode[1] else 2
        ]
        for per_mode in float_links(job.robot, at, (x, y))
    ]
    example = "slider_modes = [s1, s2, s3], each 1 or -1"
    modes = resolved_modes(job, "slider_modes", per_leg, example)
    return replace(spec, slider_modes=(modes[0], modes[1], modes[2]))


JOB_KIND = path_job_kind(
    "path3prr",
    "robot3prr",
    Path3PRRSpec,
    "3-PRR",
    prepare_path,
    "[[path3prr]]\nfrom_pose = [40, 25, 0]\nto_pose = [42, 27, 5]\nsteps = 4\nkappa_max = 1000\n",
)

"""The ``[[path3rrr_sensitivity]]`` job: the 3-RRR's ``[[path3rrr]]`` keys and the
sampling keys (:mod:`planar_tui.pathsensitivity.job`). Inputs: the base and platform sides
(or the explicit base joints and platform points, one input per coordinate), the proximal
and distal lengths (one each: the robot table gives every leg the same), every positive
mass and, with ``tolerance_inertia_kgm2``, every positive inertia."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar

from planar_tui.pathsensitivity.job import (
    SensitivityKeys,
    check_sensitivity,
    path_sensitivity_kind,
)
from planar_tui.schema import TableReader
from planar_tui.workspace.rrr.path import Path3RRRSpec, prepare_path


@dataclass(frozen=True, kw_only=True)
class Path3RRRSensitivitySpec(SensitivityKeys, Path3RRRSpec):
    """A 3-RRR path (its path job's keys) and the tolerances moving its torques."""

    key_names: ClassVar[dict[str, str]] = {
        "base_joints": "base_joints_cm",
        "platform_points": "platform_points_cm",
    }

    @staticmethod
    def length_fields(robot: Any) -> tuple[str, ...]:
        base = "base_side_cm" if robot.base_joints is None else "base_joints"
        platform = "platform_side_cm" if robot.platform_points is None else "platform_points"
        return (base, platform, "proximal_cm", "distal_cm")

    @staticmethod
    def check(values: dict[str, Any], reader: TableReader, robot: Any) -> dict[str, Any]:
        """:func:`~planar_tui.pathsensitivity.job.check_sensitivity`."""
        return check_sensitivity(values, reader, robot, Path3RRRSensitivitySpec)


JOB_KIND = path_sensitivity_kind(
    "path3rrr_sensitivity",
    "robot3rrr",
    Path3RRRSensitivitySpec,
    "3-RRR",
    prepare_path,
    "[path3rrr_sensitivity]\nfrom_pose = [40, 21, 0]\nto_pose = [42, 23, 5]\nsteps = 4\n"
    'elbow = [1, 1, 1]\nsamples = 8\nmethods = ["sobol"]\n'
    "[path3rrr_sensitivity.robot3rrr]\nplatform_mass_kg = 1\n",
)

"""The ``[[path3rpr_sensitivity]]`` job: the 3-RPR's ``[[path3rpr]]`` keys and the
sampling keys (:mod:`planar_tui.pathsensitivity.job`). Inputs: the base joints and the
platform points (one input per coordinate, ``base_joints_cm[1].x`` ...), the centre-of-mass
distances ``cylinder_com_cm`` and ``piston_com_cm`` of a body with a mass where they are
positive (one at its joint, 0, stays there: a tolerance would move it off the leg), every
positive mass and, with ``tolerance_inertia_kgm2``, every positive inertia."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from planar_tui.pathsensitivity.job import (
    SensitivityKeys,
    check_sensitivity,
    path_sensitivity_kind,
)
from planar_tui.schema import TableReader
from planar_tui.workspace.rpr.path import Path3RPRSpec, prepare_path


@dataclass(frozen=True, kw_only=True)
class Path3RPRSensitivitySpec(SensitivityKeys, Path3RPRSpec):
    """A 3-RPR path (its path job's keys) and the tolerances moving its leg forces."""

    @staticmethod
    def length_fields(robot: Any) -> tuple[str, ...]:
        centres = tuple(
            f"{body}_com_cm"
            for body in ("cylinder", "piston")
            if getattr(robot, f"{body}_mass_kg") > 0 and getattr(robot, f"{body}_com_cm") > 0
        )
        return ("base_joints_cm", "platform_points_cm", *centres)

    @staticmethod
    def check(values: dict[str, Any], reader: TableReader, robot: Any) -> dict[str, Any]:
        """:func:`~planar_tui.pathsensitivity.job.check_sensitivity`."""
        return check_sensitivity(values, reader, robot, Path3RPRSensitivitySpec)


JOB_KIND = path_sensitivity_kind(
    "path3rpr_sensitivity",
    "robot3rpr",
    Path3RPRSensitivitySpec,
    "3-RPR",
    prepare_path,
    "[path3rpr_sensitivity]\nfrom_pose = [35, 15, 0]\nto_pose = [37, 17, 5]\nsteps = 4\n"
    'samples = 8\nmethods = ["sobol"]\n'
    "[path3rpr_sensitivity.robot3rpr]\nplatform_mass_kg = 1\n",
)

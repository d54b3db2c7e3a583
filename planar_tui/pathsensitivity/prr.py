"""The ``[[path3prr_sensitivity]]`` job: the 3-PRR's ``[[path3prr]]`` keys and the
sampling keys (:mod:`planar_tui.pathsensitivity.job`). Inputs: the sliders' line points
and the platform points (one input per coordinate, ``slider_points_cm[1].x`` ...), each
leg's distal length (``distal_cm[1]`` ...), every positive mass and, with
``tolerance_inertia_kgm2``, every positive inertia. The rails' directions (degrees) and the
strokes (limits, not geometry) stay fixed."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from planar_tui.pathsensitivity.job import (
    SensitivityKeys,
    check_sensitivity,
    path_sensitivity_kind,
)
from planar_tui.schema import TableReader
from planar_tui.workspace.prr.path import Path3PRRSpec, prepare_path


@dataclass(frozen=True, kw_only=True)
class Path3PRRSensitivitySpec(SensitivityKeys, Path3PRRSpec):
    """A 3-PRR path (its path job's keys) and the tolerances moving its slider forces."""

    @staticmethod
    def length_fields(robot: Any) -> tuple[str, ...]:
        return ("slider_points_cm", "platform_points_cm", "distal_cm")

    @staticmethod
    def check(values: dict[str, Any], reader: TableReader, robot: Any) -> dict[str, Any]:
        """:func:`~planar_tui.pathsensitivity.job.check_sensitivity`."""
        return check_sensitivity(values, reader, robot, Path3PRRSensitivitySpec)


JOB_KIND = path_sensitivity_kind(
    "path3prr_sensitivity",
    "robot3prr",
    Path3PRRSensitivitySpec,
    "3-PRR",
    prepare_path,
    "[path3prr_sensitivity]\nfrom_pose = [40, 25, 0]\nto_pose = [42, 27, 5]\nsteps = 4\n"
    'samples = 8\nmethods = ["sobol"]\n'
    "[path3prr_sensitivity.robot3prr]\nplatform_mass_kg = 1\n",
)

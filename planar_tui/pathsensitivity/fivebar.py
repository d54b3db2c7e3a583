"""The ``[[path5r_sensitivity]]`` job: the five-bar's ``[[path5r]]`` keys and the sampling
keys (:mod:`planar_tui.pathsensitivity.job`). Inputs: the base separation, each leg's
proximal and distal length (``proximal_cm[1]``, ``proximal_cm[2]`` ...: the robot table
gives each leg its own), every positive mass and, with ``tolerance_inertia_kgm2``, every
positive inertia."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from planar_tui.pathsensitivity.job import (
    SensitivityKeys,
    check_sensitivity,
    path_sensitivity_kind,
)
from planar_tui.schema import TableReader
from planar_tui.workspace.fivebar.path import Path5RSpec, prepare_path


@dataclass(frozen=True, kw_only=True)
class Path5RSensitivitySpec(SensitivityKeys, Path5RSpec):
    """A five-bar path (its path job's keys) and the tolerances moving its torques."""

    @staticmethod
    def length_fields(robot: Any) -> tuple[str, ...]:
        return ("base_separation_cm", "proximal_cm", "distal_cm")

    @staticmethod
    def check(values: dict[str, Any], reader: TableReader, robot: Any) -> dict[str, Any]:
        """:func:`~planar_tui.pathsensitivity.job.check_sensitivity`."""
        return check_sensitivity(values, reader, robot, Path5RSensitivitySpec)


JOB_KIND = path_sensitivity_kind(
    "path5r_sensitivity",
    "robot5r",
    Path5RSensitivitySpec,
    "five-bar",
    prepare_path,
    "[path5r_sensitivity]\nfrom_pose = [0, 60]\nto_pose = [5, 65]\nsteps = 4\n"
    'samples = 8\nmethods = ["sobol"]\n'
    '[path5r_sensitivity.robot5r]\nworking_mode = "+-"\nend_mass_kg = 1\n',
)

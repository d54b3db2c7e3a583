"""The ``[[workspace3prr]]`` job: the constant-orientation workspace of a 3-PRR
(:mod:`planar_tui.workspace.prr`), paved with the exact per-leg distance test
(:mod:`planar_tui.kernels.workspace3prr`) by the shared runner
(:mod:`planar_tui.workspace.planar`)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar

from planar_tui.jobkind import Tab
from planar_tui.schema import TableReader, setting, string
from planar_tui.workspace import prr
from planar_tui.workspace.planar import (
    Mechanism,
    PlanarSpec,
    check_range_and_reference,
    planar_job_kind,
    same_key,
)
from planar_tui.workspace.prr_tolerance import TOLERANCE_KEYS_3PRR
from planar_tui.workspace.tolerance import check_tolerance, tolerance_fields

MECHANISM = Mechanism(
    parameters=prr.leg_parameters,
    reach_box=prr.reach_box,
    polygon=prr.workspace_polygon,
    level="planar_tui.kernels.workspace3prr:prr_level",
    singularities="planar_tui.workspace.prr_singularity",
    orientation_range="planar_tui.workspace.prr_orientation",
)


@dataclass(frozen=True, kw_only=True)
class Spec3PRR(PlanarSpec):
    """Settings of one 3-PRR workspace job (lengths in cm, the orientation in degrees); the
    strokes and links are the robot's (``[robot3prr]``)."""

    orientation_deg: float | tuple[float, float] = same_key("orientation_deg")
    orientation_mode: str | None = same_key("orientation_mode")
    form: str = setting(
        string(choices=("distance", "geometric")),
        default="distance",
        type_doc="`distance`, `geometric`",
        doc="the per-leg distance test of each box (see docs/workspace.md), or the exact area only",
    )

    slider_modes: tuple[int, int, int] | None = same_key(
        "elbow",
        name="slider_modes",
        default_doc="(the mode the strokes allow at the centre)",
        doc="working mode per leg: the slider ahead (`1`) or behind (`-1`) the foot of the "
        "perpendicular from the platform joint to its line",
    )
    tolerance_cm: float | None
    tolerances_cm: tuple[tuple[str, float], ...] | None
    tolerance_mode: str | None
    tolerance_cm, tolerances_cm, tolerance_mode = tolerance_fields(
        TOLERANCE_KEYS_3PRR,
        "manufacturing tolerance ± on every slider line point, platform joint coordinate and "
        "distal length (cm; the line directions and strokes are exact)",
    )
    mechanism: ClassVar[Any] = MECHANISM
    kind: ClassVar[str] = "workspace3prr"
    tolerance_keys: ClassVar[tuple[str, ...]] = TOLERANCE_KEYS_3PRR
    circle_keys: ClassVar[tuple[str, ...]] = (
        "slider_modes",
        "circle_centre_cm",
        "singularity_precision_cm",
    )

    @classmethod
    def check(cls, values: dict[str, Any], reader: TableReader, robot: Any) -> dict[str, Any]:
        """A tolerance (:mod:`planar_tui.workspace.prr_tolerance`) is below the shortest
        distal, takes the distance form, no singularities and no geometric reference (as
        the 3-RPR's); an orientation range (:mod:`planar_tui.workspace.prr_orientation`)
        as the 3-RPR's (:func:`~planar_tui.workspace.planar.check_range_and_reference`);
        then the shared checks."""
        check_tolerance(values, reader, TOLERANCE_KEYS_3PRR, {"distal_cm": min(robot.distal_cm)})
        check_range_and_reference(values, reader, "distance")
        return super().check(values, reader, robot)


JOB_KIND = planar_job_kind(
    "workspace3prr",
    "3-PRR",
    Spec3PRR,
    "3-PRR constant-orientation workspace: stadiums minus lenses intersected, "
    "certified by a per-leg distance test",
    Tab("3-PRR", 7, "planar_tui.app.widgets.parallel_panes:Workspace3PRRPane"),
    "[[workspace3prr]]\nprecision_cm = 8.0\nrefine_precision_cm = 4.0\n"
    "geometric_reference = false\nsingularities = true\n",
)

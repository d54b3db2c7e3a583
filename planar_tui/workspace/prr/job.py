"""The ``[[workspace3prr]]`` job: the constant-orientation workspace of a 3-PRR
(:mod:`planar_tui.workspace.prr.robot`), paved with the exact per-leg distance test
(:mod:`planar_tui.kernels.workspace3prr`) by the shared runner
(:mod:`planar_tui.workspace.paving.runner`)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar

from planar_tui.jobkind import Tab
from planar_tui.schema import setting, string
from planar_tui.workspace.paving.mechanism import Mechanism
from planar_tui.workspace.paving.ranged import RangedSpec
from planar_tui.workspace.paving.runner import planar_job_kind
from planar_tui.workspace.paving.settings import modes_setting
from planar_tui.workspace.paving.tolerance import tolerance_fields
from planar_tui.workspace.prr.mechanism import MECHANISM
from planar_tui.workspace.prr.tolerance import TOLERANCE_KEYS_3PRR


@dataclass(frozen=True, kw_only=True)
class Spec3PRR(RangedSpec):
    """Settings of one 3-PRR workspace job (lengths in cm, the orientation in degrees); the
    strokes and links are the robot's (``[robot3prr]``). A tolerance
    (:mod:`planar_tui.workspace.prr.tolerance`) stays below the shortest distal; with it or
    an orientation range (:mod:`planar_tui.workspace.prr.orientation`) the job takes the
    ``distance`` form (:class:`~planar_tui.workspace.paving.ranged.RangedSpec`)."""

    form: str = setting(
        string(choices=("distance", "geometric")),
        default="distance",
        type_doc="`distance`, `geometric`",
        doc="the per-leg distance test of each box (see docs/workspace.md), or the exact area only",
    )

    slider_modes: tuple[int, int, int] | None = modes_setting(
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
    mechanism: ClassVar[Mechanism] = MECHANISM
    kind: ClassVar[str] = "workspace3prr"
    tolerance_keys: ClassVar[tuple[str, ...]] = TOLERANCE_KEYS_3PRR
    circle_keys: ClassVar[tuple[str, ...]] = (
        "slider_modes",
        "circle_centre_cm",
        "singularity_precision_cm",
    )
    #: The circle key that ``kappa_max`` takes too (its working mode).
    mode_keys: ClassVar[tuple[str, ...]] = ("slider_modes",)
    box_form: ClassVar[str] = "distance"

    @classmethod
    def tolerance_bounds(cls, robot: Any) -> dict[str, float]:
        return {"distal_cm": min(robot.distal_cm)}


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

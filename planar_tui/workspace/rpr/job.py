"""The ``[[workspace3rpr]]`` job: the constant-orientation workspace of a 3-RPR
(:mod:`planar_tui.workspace.rpr.robot`), paved with the exact per-leg annulus test
(:mod:`planar_tui.kernels.workspace3rpr`) by the shared runner
(:mod:`planar_tui.workspace.paving.runner`)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from planar_tui.jobkind import Tab
from planar_tui.schema import TableReader, setting
from planar_tui.workspace.paving.mechanism import Mechanism
from planar_tui.workspace.paving.ranged import RangedSpec
from planar_tui.workspace.paving.runner import planar_job_kind
from planar_tui.workspace.paving.tolerance import tolerance_fields
from planar_tui.workspace.rpr.mechanism import MECHANISM
from planar_tui.workspace.rpr.tolerance import TOLERANCE_KEYS_3RPR

#: Longest leg (cm), as lengths are bounded: a leg limit far beyond the reach (1e199 cm,
#: an unlimited stroke) is capped at the reach box; beyond this one the geometry overflows.
MAX_LEG_CM = 1e200


def _leg_limits(reader: TableReader, name, default, robot, values):
    """Three ``[lo, hi]`` rows in cm with ``0 <= lo < hi <=`` :data:`MAX_LEG_CM`."""
    rows = reader.number_rows(name, columns=2, row_doc="[lo, hi] in cm")
    if len(rows) != 3:
        raise reader.error(name, f"has {len(rows)} rows", "3 rows [lo, hi], one per leg")
    for leg, (lo, hi) in enumerate(rows, start=1):
        if not 0.0 <= lo < hi <= MAX_LEG_CM:
            raise reader.error(
                name, f"leg {leg} range [{lo:g}, {hi:g}]", f"0 <= lo < hi <= {MAX_LEG_CM:g}"
            )
    return rows


@dataclass(frozen=True, kw_only=True)
class Spec3RPR(RangedSpec):
    """Settings of one 3-RPR workspace job (lengths in cm, the orientation in degrees); a
    tolerance (:mod:`planar_tui.workspace.rpr.tolerance`; the leg limits are exact) or an
    orientation range (:mod:`planar_tui.workspace.rpr.orientation`) takes the ``natural``
    form (:class:`~planar_tui.workspace.paving.ranged.RangedSpec`)."""

    leg_limits_cm: tuple[tuple[float, float], ...] = setting(
        _leg_limits,
        type_doc="3 rows `[lo, hi]`, 0 ≤ lo < hi",
        doc="actuated leg lengths ρ1, ρ2, ρ3 (prismatic strokes)",
    )
    tolerance_cm: float | None
    tolerances_cm: tuple[tuple[str, float], ...] | None
    tolerance_mode: str | None
    tolerance_cm, tolerances_cm, tolerance_mode = tolerance_fields(
        TOLERANCE_KEYS_3RPR,
        "manufacturing tolerance ± on every joint coordinate (cm; the leg limits are exact)",
    )

    mechanism: ClassVar[Mechanism] = MECHANISM
    kind: ClassVar[str] = "workspace3rpr"
    tolerance_keys: ClassVar[tuple[str, ...]] = TOLERANCE_KEYS_3RPR


JOB_KIND = planar_job_kind(
    "workspace3rpr",
    "3-RPR",
    Spec3RPR,
    "3-RPR constant-orientation workspace: the intersection of three annuli, "
    "certified by an exact per-leg interval test",
    Tab("3-RPR", 6, "planar_tui.app.widgets.parallel_panes:Workspace3RPRPane"),
    "[[workspace3rpr]]\nleg_limits_cm = [[40, 90], [40, 90], [40, 90]]\n"
    "precision_cm = 8.0\nrefine_precision_cm = 4.0\ngeometric_reference = false\n"
    "orientation_deg = 30\nsingularities = true\n",
)

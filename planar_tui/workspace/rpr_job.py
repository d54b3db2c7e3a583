"""The ``[[workspace3rpr]]`` job: the constant-orientation workspace of a 3-RPR
(:mod:`planar_tui.workspace.rpr`), paved with the exact per-leg annulus test
(:mod:`planar_tui.kernels.workspace3rpr`) by the shared runner
(:mod:`planar_tui.workspace.planar`)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar

from planar_tui.jobkind import Command, JobKind, Option, OutputOption, Tab
from planar_tui.schema import TableReader, setting
from planar_tui.workspace import rpr
from planar_tui.workspace.planar import (
    Mechanism,
    PlanarSpec,
    extra_outputs,
    render_workspace,
    run_planar,
)

MECHANISM = Mechanism(
    parameters=rpr.leg_parameters,
    reach_box=rpr.reach_box,
    polygon=rpr.workspace_polygon,
    level="planar_tui.kernels.workspace3rpr:rpr_level",
)


def _leg_limits(reader: TableReader, name, default, robot, values):
    """Three ``[lo, hi]`` rows in cm with ``0 <= lo < hi``."""
    rows = reader.number_rows(name, columns=2, row_doc="[lo, hi] in cm")
    if len(rows) != 3:
        raise reader.error(name, f"has {len(rows)} rows", "3 rows [lo, hi], one per leg")
    for leg, (lo, hi) in enumerate(rows, start=1):
        if not 0.0 <= lo < hi:
            raise reader.error(name, f"leg {leg} range [{lo:g}, {hi:g}]", "0 <= lo < hi")
    return rows


@dataclass(frozen=True, kw_only=True)
class Spec3RPR(PlanarSpec):
    """Settings of one 3-RPR workspace job (lengths in cm, the orientation in degrees)."""

    leg_limits_cm: tuple[tuple[float, float], ...] = setting(
        _leg_limits,
        type_doc="3 rows `[lo, hi]`, 0 ≤ lo < hi",
        doc="actuated leg lengths ρ1, ρ2, ρ3 (prismatic strokes)",
    )

    mechanism: ClassVar[Any] = MECHANISM


JOB_KIND = JobKind(
    name="workspace3rpr",
    robot_kind="robot3rpr",
    settings=Spec3RPR,
    run=run_planar,
    summary="3-RPR constant-orientation workspace: the intersection of three annuli, "
    "certified by an exact per-leg interval test",
    render=render_workspace,
    extra_outputs=extra_outputs,
    command=Command(
        "workspace3rpr",
        "3-RPR workspace of every workspace3rpr job: summary CSV, boxes CSV (--boxes or the "
        "preset's boxes_output) and a map titled with the job and precision.",
        options=(
            Option("--precision", "precision_cm",
                   "Precision epsilon in cm; overrides `precision_cm`.", float),
        ),
        outputs=(OutputOption("--boxes", "boxes",
                              "CSV of the kept boxes (with several jobs: FILE-1.csv ...)."),),
        view=("--map/--no-map", "Print the character-cell map."),
    ),
    tab=Tab("3-RPR", 3, "planar_tui.app.widgets.parallel_panes:Workspace3RPRPane"),
    figure="planar_tui.figures.workspace:from_planar_result",
    warmup="[[workspace3rpr]]\nleg_limits_cm = [[40, 90], [40, 90], [40, 90]]\n"
    "precision_cm = 8.0\nrefine_precision_cm = 4.0\ngeometric_reference = false\n",
)  # fmt: skip

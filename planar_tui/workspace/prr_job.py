"""The ``[[workspace3prr]]`` job: the constant-orientation workspace of a 3-PRR
(:mod:`planar_tui.workspace.prr`), paved with the exact per-leg distance test
(:mod:`planar_tui.kernels.workspace3prr`) by the shared runner
(:mod:`planar_tui.workspace.planar`)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar

from planar_tui.jobkind import Command, JobKind, Option, OutputOption, Tab
from planar_tui.schema import setting, string
from planar_tui.workspace import prr
from planar_tui.workspace.planar import (
    Mechanism,
    PlanarSpec,
    extra_outputs,
    render_workspace,
    run_planar,
)

MECHANISM = Mechanism(
    parameters=prr.leg_parameters,
    reach_box=prr.reach_box,
    polygon=prr.workspace_polygon,
    level="planar_tui.kernels.workspace3prr:prr_level",
)


@dataclass(frozen=True, kw_only=True)
class Spec3PRR(PlanarSpec):
    """Settings of one 3-PRR workspace job (lengths in cm, the orientation in degrees); the
    strokes and links are the robot's (``[robot3prr]``)."""

    form: str = setting(
        string(choices=("distance", "geometric")),
        default="distance",
        type_doc="`distance`, `geometric`",
        doc="the per-leg distance test of each box (see docs/workspace.md), or the exact area only",
    )

    mechanism: ClassVar[Any] = MECHANISM


JOB_KIND = JobKind(
    name="workspace3prr",
    robot_kind="robot3prr",
    settings=Spec3PRR,
    run=run_planar,
    summary="3-PRR constant-orientation workspace: stadiums minus lenses intersected, "
    "certified by a per-leg distance test",
    render=render_workspace,
    extra_outputs=extra_outputs,
    command=Command(
        "workspace3prr",
        "3-PRR workspace of every workspace3prr job: summary CSV, boxes CSV (--boxes or the "
        "preset's boxes_output) and a map titled with the job and precision.",
        options=(
            Option("--precision", "precision_cm",
                   "Precision epsilon in cm; overrides `precision_cm`.", float),
        ),
        outputs=(OutputOption("--boxes", "boxes",
                              "CSV of the kept boxes (with several jobs: FILE-1.csv ...)."),),
        view=("--map/--no-map", "Print the character-cell map."),
    ),
    tab=Tab("3-PRR", 4, "planar_tui.app.widgets.parallel_panes:Workspace3PRRPane"),
    figure="planar_tui.figures.workspace:from_planar_result",
    warmup="[[workspace3prr]]\nprecision_cm = 8.0\nrefine_precision_cm = 4.0\n"
    "geometric_reference = false\n",
)  # fmt: skip

"""The ``[workspace]`` job: constant-orientation workspace of a 3-RRR (paper B)."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from planar_tui.jobs.base import JobKind
from planar_tui.presets import TableReader
from planar_tui.workspace.model import Robot3RRR

FORMS = ("natural", "mean-value", "slope", "arc-distance", "geometric")

#: Default cap on the boxes processed by one job (each costs ~1 µs and ≤ 112 bytes).
DEFAULT_BOX_BUDGET = 50_000_000


@dataclass(frozen=True)
class WorkspaceSpec:
    """Settings of one workspace computation (angles in degrees, lengths in cm)."""

    joint_limits_deg: tuple[tuple[float, float], ...]
    orientation_deg: float
    precision_cm: float
    form: str = "mean-value"
    search_box_cm: tuple[tuple[float, float], tuple[float, float]] | None = None
    angle_scale: float = 10.0
    expanded: bool = False
    refine_precision_cm: float | None = None
    box_budget: int = DEFAULT_BOX_BUDGET
    geometric_reference: bool = True
    boxes_output: str | None = None

    @property
    def limits_rad(self) -> tuple[tuple[float, float], ...]:
        """Joint limits in radians."""
        return tuple((math.radians(lo), math.radians(hi)) for lo, hi in self.joint_limits_deg)

    @property
    def orientation_rad(self) -> float:
        """Platform orientation :math:`\\varphi` in radians."""
        return math.radians(self.orientation_deg)


def default_search_box(
    robot: Robot3RRR, orientation_rad: float, precision_cm: float
) -> tuple[tuple[float, float], tuple[float, float]]:
    """A square about the reach box whose side is ``precision_cm * 2**n`` (smallest n), so
    that the bisection's leaves are exactly ``precision_cm`` wide."""
    xlo, xhi, ylo, yhi = robot.reach_box_cm(orientation_rad)
    if xlo > xhi or ylo > yhi:  # the legs' reach discs do not meet: any small box will do
        xlo = xhi = ylo = yhi = 0.0
    side = precision_cm
    while side < max(xhi - xlo, yhi - ylo):
        side *= 2.0
    cx, cy = 0.5 * (xlo + xhi), 0.5 * (ylo + yhi)
    return ((cx - 0.5 * side, cx + 0.5 * side), (cy - 0.5 * side, cy + 0.5 * side))


def _joint_limits(reader: TableReader) -> tuple[tuple[float, float], ...]:
    rows = reader.number_rows("joint_limits_deg", columns=2)
    if len(rows) != 3:
        raise reader.error("joint_limits_deg", f"has {len(rows)} rows", "3 rows [min, max]")
    for leg, (lo, hi) in enumerate(rows, start=1):
        if not lo < hi:
            raise reader.error(
                "joint_limits_deg",
                f"leg {leg} range [{lo:g}, {hi:g}] is empty or reversed",
                "min < max",
            )
        if hi - lo > 360.0:
            raise reader.error(
                "joint_limits_deg", f"leg {leg} range spans {hi - lo:g} deg", "at most 360 deg"
            )
    return rows


def _search_box(reader: TableReader, robot: Robot3RRR, orientation_rad: float):
    if not reader.has("search_box_cm"):
        return None
    rows = reader.number_rows("search_box_cm", columns=2)
    if len(rows) != 2 or any(not lo < hi for lo, hi in rows):
        raise reader.error(
            "search_box_cm", f"is {[list(r) for r in rows]}", "[[x_min, x_max], [y_min, y_max]]"
        )
    (xlo, xhi), (ylo, yhi) = rows
    rxlo, rxhi, rylo, ryhi = robot.reach_box_cm(orientation_rad)
    if (
        rxlo <= rxhi
        and rylo <= ryhi
        and not (xlo <= rxlo and rxhi <= xhi and ylo <= rylo and ryhi <= yhi)
    ):
        raise reader.error(
            "search_box_cm",
            "cannot contain the robot's reach "
            f"x in [{rxlo:.4g}, {rxhi:.4g}], y in [{rylo:.4g}, {ryhi:.4g}] cm",
            "a box containing it",
        )
    return rows


def parse_workspace(reader: TableReader, robot: Robot3RRR) -> WorkspaceSpec:
    """Validate a ``[workspace]`` table against its 3-RRR."""
    limits = _joint_limits(reader)
    orientation_deg = reader.number("orientation_deg", 0.0)
    precision_cm = reader.number("precision_cm", positive=True)
    form = reader.string("form", "mean-value", choices=FORMS)
    expanded = reader.boolean("expanded", False)
    if expanded and form != "natural":
        raise reader.error("expanded", f"is true with form = {form!r}", 'form = "natural"')
    if expanded and not robot.paper_layout:
        raise reader.error(
            "expanded", "needs the paper's layout", "no base_joints_cm / platform_points_cm"
        )
    refine = reader.number("refine_precision_cm", None, positive=True)
    if refine is not None and refine > precision_cm:
        raise reader.error(
            "refine_precision_cm", f"is {refine:g} > precision_cm", "<= precision_cm"
        )
    return WorkspaceSpec(
        joint_limits_deg=limits,
        orientation_deg=orientation_deg,
        precision_cm=precision_cm,
        form=form,
        search_box_cm=_search_box(reader, robot, math.radians(orientation_deg)),
        angle_scale=reader.number("angle_scale", 10.0, positive=True),
        expanded=expanded,
        refine_precision_cm=refine,
        box_budget=reader.integer("box_budget", DEFAULT_BOX_BUDGET, minimum=1),
        geometric_reference=reader.boolean("geometric_reference", True),
        boxes_output=reader.relative_path("boxes_output", None),
    )


def dump_workspace(spec: WorkspaceSpec) -> dict:
    """The settings as a ``[workspace]`` table."""
    table: dict = {
        "joint_limits_deg": [list(row) for row in spec.joint_limits_deg],
        "orientation_deg": spec.orientation_deg,
        "precision_cm": spec.precision_cm,
        "form": spec.form,
        "angle_scale": spec.angle_scale,
        "expanded": spec.expanded,
        "box_budget": spec.box_budget,
        "geometric_reference": spec.geometric_reference,
    }
    if spec.search_box_cm is not None:
        table["search_box_cm"] = [list(row) for row in spec.search_box_cm]
    if spec.refine_precision_cm is not None:
        table["refine_precision_cm"] = spec.refine_precision_cm
    if spec.boxes_output is not None:
        table["boxes_output"] = spec.boxes_output
    return table


def with_overrides(spec: WorkspaceSpec, *, form=None, precision_cm=None) -> WorkspaceSpec:
    """The spec with command-line overrides applied (``None`` keeps the preset's value)."""
    if form is not None:
        spec = replace(spec, form=form, expanded=spec.expanded and form == "natural")
    if precision_cm is not None:
        refine = spec.refine_precision_cm
        spec = replace(
            spec,
            precision_cm=precision_cm,
            refine_precision_cm=None if refine is None else min(refine, precision_cm),
        )
    return spec


WORKSPACE = JobKind(
    name="workspace",
    robot_kind="robot3rrr",
    keys=(
        "joint_limits_deg",
        "orientation_deg",
        "precision_cm",
        "form",
        "search_box_cm",
        "angle_scale",
        "expanded",
        "refine_precision_cm",
        "box_budget",
        "geometric_reference",
        "boxes_output",
    ),
    parse=parse_workspace,
    dump=dump_workspace,
    runner="planar_tui.workspace.runner:run_workspace",
    summary="3-RRR constant-orientation workspace by interval analysis",
    render="planar_tui.workspace.render:show_workspace",
    extra_outputs=lambda spec: {"boxes": spec.boxes_output} if spec.boxes_output else {},
)

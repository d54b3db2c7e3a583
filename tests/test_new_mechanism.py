"""A parallel robot defined in this file alone, as the README's recipe for a new robot says:
a 2-RPR point robot (two prismatic legs from the fixed base joints A1, A2 to one platform
point P, the leg lengths within ``[lo_i, hi_i]``). Its robot table, settings, separator
(:class:`~planar_tui.workspace.paving.mechanism.Mechanism`) and leg test kernel are here;
registered for the test, the paving core's runner paves it in ``planar-tui run``, in a
``[[sweep]]`` and as an app tab.

Its exact workspace is the intersection of the two annuli :math:`lo_i \\le |P - A_i| \\le
hi_i`; its area has a closed form by inclusion-exclusion over the four disc pairs,
:math:`|W| = L(hi_1, hi_2) - L(hi_1, lo_2) - L(lo_1, hi_2) + L(lo_1, lo_2)` with
:math:`L(a, b)` the area of the lens of discs of radii a, b about A1, A2: the certified
bracket must hold it, and the exact polygons' (shapely) bracket too."""

from __future__ import annotations

import asyncio
import csv
import math
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any, ClassVar

import pytest
from typer.testing import CliRunner

from planar_tui.app.widgets.workspace_pane import WorkspacePane
from planar_tui.jobkind import RobotKind, Tab
from planar_tui.registry import ROBOT_KINDS, registered
from planar_tui.schema import TableReader, number_rows, setting
from planar_tui.workspace.paving.mechanism import Mechanism
from planar_tui.workspace.paving.runner import PlanarSpec, planar_job_kind

BASE_CM = ((0.0, 0.0), (30.0, 0.0))
LIMITS_CM = ((10.0, 25.0), (8.0, 22.0))


@dataclass(frozen=True, kw_only=True)
class Robot2RPR:
    """The ``[robot2rpr]`` table: the two base joints (cm)."""

    base_joints_cm: tuple[tuple[float, float], ...] = setting(
        number_rows(columns=2), default=BASE_CM, type_doc="2 rows `[x, y]`", doc="A1, A2"
    )


def read_leg_limits(reader: TableReader, name, default, robot, values):
    rows = reader.number_rows(name, columns=2, row_doc="[lo, hi] in cm")
    if len(rows) != 2 or any(not 0.0 <= lo < hi for lo, hi in rows):
        raise reader.error(name, f"is {[list(r) for r in rows]}", "2 rows [lo, hi], 0 <= lo < hi")
    return rows


def point_box_distances(bx: float, by: float, box) -> tuple[float, float]:
    """Least and greatest distance from ``(bx, by)`` to the box ``x_lo, x_hi, y_lo, y_hi``."""
    xlo, xhi, ylo, yhi = box
    near_x = max(xlo - bx, 0.0, bx - xhi)
    near_y = max(ylo - by, 0.0, by - yhi)
    far_x, far_y = max(abs(xlo - bx), abs(xhi - bx)), max(abs(ylo - by), abs(yhi - by))
    return math.hypot(near_x, near_y), math.hypot(far_x, far_y)


def toy_level(p, precision, rows, start, stop, children, outcome) -> None:
    """The toy's leg test kernel (plain Python): a box whose distance range to every A_i lies
    in ``[lo_i, hi_i]`` is inside, one whose range misses some ``[lo_i, hi_i]`` is outside,
    any other is split (or kept as boundary at ``precision``) by the core's settle step."""
    from planar_tui.kernels.workspace_arc import BOUNDARY, INSIDE, OUTSIDE, settle_xy_box

    for i in range(stop - start):
        box = rows[start + i]
        label = INSIDE
        for ax, ay, lo, hi in p:
            near, far = point_box_distances(ax, ay, box)
            if far < lo or near > hi:
                label = OUTSIDE
                break
            if not (lo <= near and far <= hi):
                label = BOUNDARY
        outcome[i] = settle_xy_box(label, rows, start + i, children, 2 * i, precision)


class Mechanism2RPR(Mechanism):
    """The 2-RPR point robot's separator."""

    name = "2-RPR"
    explores = False
    tolerance_keys = ()
    singular_boxes_per_step = 10.0
    tolerance_boxes = MappingProxyType({})
    has_singularities = False
    has_orientation_ranges = False

    def parameters(self, robot: Any, spec: Any) -> Any:
        import numpy as np

        legs = zip(robot.base_joints_cm, spec.leg_limits_cm, strict=True)
        return np.array([(ax, ay, lo, hi) for (ax, ay), (lo, hi) in legs])

    def level_kernel(self):
        return toy_level

    def reach_box(self, robot: Any, spec: Any) -> tuple[float, float, float, float]:
        legs = list(zip(robot.base_joints_cm, spec.leg_limits_cm, strict=True))
        return (
            max(ax - hi for (ax, _), (_, hi) in legs),
            min(ax + hi for (ax, _), (_, hi) in legs),
            max(ay - hi for (_, ay), (_, hi) in legs),
            min(ay + hi for (_, ay), (_, hi) in legs),
        )

    def polygon(self, robot: Any, spec: Any, segments_per_turn: int, outward: bool) -> Any:
        """Each outer circle inscribed and each hole circumscribed (``outward=False``), or
        the reverse: the inner and outer polygons of the exact workspace."""
        from shapely import Point, intersection_all

        def disc(centre, radius, grow):
            # a regular polygon inscribed in the circle, or circumscribed about it (grow)
            scale = 1.0 / math.cos(math.pi / segments_per_turn) if grow else 1.0
            return Point(centre).buffer(radius * scale, quad_segs=segments_per_turn // 4)

        annuli = [
            disc(a, hi, outward).difference(disc(a, lo, not outward))
            for a, (lo, hi) in zip(robot.base_joints_cm, spec.leg_limits_cm, strict=True)
        ]
        return intersection_all(annuli)


@dataclass(frozen=True, kw_only=True)
class Spec2RPR(PlanarSpec):
    """A 2-RPR workspace job: the shared keys and the leg limits."""

    leg_limits_cm: tuple[tuple[float, float], ...] = setting(
        read_leg_limits, type_doc="2 rows `[lo, hi]`", doc="leg lengths ρ1, ρ2"
    )

    mechanism: ClassVar[Mechanism] = Mechanism2RPR()
    kind: ClassVar[str] = "workspace2rpr"


class Workspace2RPRPane(WorkspacePane):
    """The toy's app tab: the workspace pane on ``[[workspace2rpr]]`` jobs."""

    kind = "workspace2rpr"


ROBOT_KIND = RobotKind("robot2rpr", Robot2RPR, example="[robot2rpr]\n")
JOB_KIND = planar_job_kind(
    "workspace2rpr",
    "2-RPR",
    Spec2RPR,
    "2-RPR point robot: the intersection of two annuli",
    Tab("2-RPR", 9, "tests.test_new_mechanism:Workspace2RPRPane"),
    "[[workspace2rpr]]\nleg_limits_cm = [[10, 25], [8, 22]]\nprecision_cm = 4.0\n",
)

PRESET = f"""[robot2rpr]
base_joints_cm = {[list(a) for a in BASE_CM]}

[[workspace2rpr]]
leg_limits_cm = {[list(limits) for limits in LIMITS_CM]}
precision_cm = 0.5
output = "toy.csv"
"""
SWEEP = """
[[sweep]]
job = "workspace2rpr"
values.precision_cm = [1.0, 0.5]
output = "toy-sweep.csv"
"""


def lens_cm2(a: float, b: float, d: float) -> float:
    """The area of the intersection of discs of radii ``a``, ``b`` whose centres are ``d``
    apart (the circular-segment formula; a disc inside the other, or apart)."""
    if d >= a + b:
        return 0.0
    if d <= abs(a - b):
        return math.pi * min(a, b) ** 2
    alpha = math.acos((d * d + a * a - b * b) / (2.0 * d * a))
    beta = math.acos((d * d + b * b - a * a) / (2.0 * d * b))
    kite = 0.5 * math.sqrt((-d + a + b) * (d + a - b) * (d - a + b) * (d + a + b))
    return a * a * alpha + b * b * beta - kite


def exact_area_cm2() -> float:
    """Inclusion-exclusion over the annuli's discs (module docstring)."""
    d = math.dist(*BASE_CM)
    (lo1, hi1), (lo2, hi2) = LIMITS_CM
    return (
        lens_cm2(hi1, hi2, d)
        - lens_cm2(hi1, lo2, d)
        - lens_cm2(lo1, hi2, d)
        + lens_cm2(lo1, lo2, d)
    )


@pytest.fixture
def toy():
    ROBOT_KINDS[ROBOT_KIND.name] = ROBOT_KIND
    try:
        with registered(JOB_KIND) as kind:
            yield kind
    finally:
        del ROBOT_KINDS[ROBOT_KIND.name]


def invoke(*args):
    from planar_tui.cli import build_app

    return CliRunner().invoke(build_app(), [str(a) for a in args], catch_exceptions=False)


def rows_of(path) -> list[dict[str, str]]:
    with open(path, newline="", encoding="utf-8") as stream:
        return list(csv.DictReader(stream))


def test_the_closed_form_is_the_lens_formula_on_cases_known_by_hand():
    assert lens_cm2(1.0, 1.0, 0.0) == pytest.approx(math.pi)
    assert lens_cm2(1.0, 2.0, 3.5) == 0.0
    # two unit discs one radius apart: 2π/3 - √3/2
    assert lens_cm2(1.0, 1.0, 1.0) == pytest.approx(2 * math.pi / 3 - math.sqrt(3) / 2)


def test_the_toy_robot_runs_from_run_with_a_bracket_holding_the_closed_form(toy, tmp_path):
    (tmp_path / "toy.toml").write_text(PRESET, encoding="utf-8")
    result = invoke("run", tmp_path / "toy.toml", "--out-dir", tmp_path)
    assert result.exit_code == 0, result.output
    (row,) = rows_of(tmp_path / "toy.csv")
    exact = exact_area_cm2()
    inside, kept = float(row["area_inside_cm2"]), float(row["area_kept_cm2"])
    assert inside <= exact <= kept
    # the boundary leaves (side <= ε) meet the boundary, so they lie within r = ε√2 of it:
    # the band is at most the r-sausages about its (at most 8) arcs, 2 r L + 8 π r²
    r = 0.5 * math.sqrt(2.0)
    length = (
        Mechanism2RPR()
        .polygon(Robot2RPR(), Spec2RPR(leg_limits_cm=LIMITS_CM, precision_cm=0.5), 4096, True)
        .length
    )
    assert kept - inside <= 2.0 * r * length + 8.0 * math.pi * r * r
    assert float(row["area_geometric_cm2"]) == pytest.approx(exact, rel=1e-4)
    assert row["form"] == "natural" and int(row["boxes_inside"]) > 0


def test_the_toy_robot_runs_in_a_sweep(toy, tmp_path):
    (tmp_path / "toy.toml").write_text(PRESET + SWEEP, encoding="utf-8")
    result = invoke("sweep", tmp_path / "toy.toml", "--workers", "1", "-d", tmp_path)
    assert result.exit_code == 0, result.output
    rows = rows_of(tmp_path / "toy-sweep.csv")
    assert [row["status"] for row in rows] == ["ok", "ok"]
    exact = exact_area_cm2()
    widths = []
    for row in rows:
        inside, kept = float(row["area_inside_cm2"]), float(row["area_kept_cm2"])
        assert inside <= exact <= kept
        widths.append(kept - inside)
    assert widths[1] < widths[0]  # a finer precision, a narrower bracket


@pytest.mark.slow  # an end-to-end app test
def test_the_toy_robot_has_an_app_tab(toy, tmp_path):
    asyncio.run(_app_tab(tmp_path))


async def _app_tab(tmp_path):
    from planar_tui.app.app import WorkbenchApp
    from planar_tui.app.workbench import Workbench

    (tmp_path / "toy.toml").write_text(PRESET, encoding="utf-8")
    app = WorkbenchApp(Workbench.open(tmp_path / "toy.toml"), output_dir=tmp_path)
    async with app.run_test(size=(120, 40)) as pilot:
        assert ("2-RPR", "workspace2rpr") in app.tabs()
        pane = app.query_one("#pane-workspace2rpr", WorkspacePane)  # (imported twice)
        app.action_show_tab("workspace2rpr")
        await pilot.pause()
        assert "1 job valid" in str(app.query_one("#validation").render())
        assert pane.available()

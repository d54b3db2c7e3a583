"""The braille canvas (its cells, its line rasteriser) and the robot drawings on it.

Expected cells are built here from the Unicode braille table (dot k raises bit k - 1 of
U+2800 + bits; dots 1-3 and 7 are the left column top to bottom, 4-6 and 8 the right) and
from closed-form joint positions, not from the drawing code."""

from __future__ import annotations

import itertools
import math
import tomllib
from pathlib import Path

import pytest

from planar_tui.app.widgets.canvas import Canvas, Viewport, bresenham, nice_length
from planar_tui.app.widgets.robot_drawing import (
    draw_serial_robot,
    render_scene,
    rrr_scene,
    serial_scene,
)
from planar_tui.workspace.rrr.pose import leg_modes

REPO = Path(__file__).resolve().parent.parent
#: Unicode's braille dot number of the dot at (x, y) within a cell.
DOT_NUMBER = {
    (0, 0): 1,
    (0, 1): 2,
    (0, 2): 3,
    (1, 0): 4,
    (1, 1): 5,
    (1, 2): 6,
    (0, 3): 7,
    (1, 3): 8,
}


def braille(dots_in_cell: set[tuple[int, int]]) -> str:
    return chr(0x2800 + sum(1 << (DOT_NUMBER[d] - 1) for d in dots_in_cell))


def expected_cells(dots: set[tuple[int, int]], columns: int, rows: int) -> list[list[str]]:
    cells = [[" "] * columns for _ in range(rows)]
    for column in range(columns):
        for row in range(rows):
            inside = {(x - 2 * column, y - 4 * row) for x, y in dots}
            inside &= set(DOT_NUMBER)
            if inside:
                cells[row][column] = braille(inside)
    return cells


def test_single_dots_follow_the_unicode_braille_table():
    for (x, y), number in DOT_NUMBER.items():
        canvas = Canvas(1, 1)
        canvas.dot(x, y)
        assert canvas.char(0, 0) == chr(0x2800 + (1 << (number - 1)))
    full = Canvas(1, 1)
    for x, y in DOT_NUMBER:
        full.dot(x, y)
    assert full.char(0, 0) == "⣿"
    assert Canvas(2, 1).lines() == ["  "]


def test_dots_outside_the_canvas_are_ignored():
    canvas = Canvas(2, 1)
    canvas.dot(-1, 0)
    canvas.dot(4, 0)
    canvas.dot(0, 4)
    assert canvas.lines() == ["  "]


@pytest.mark.parametrize(
    ("start", "end"),
    [((0, 0), (7, 3)), ((7, 3), (0, 0)), ((2, 9), (5, 0)), ((0, 0), (0, 5)), ((3, 3), (3, 3))],
)
def test_bresenham_is_connected_and_within_half_a_dot_of_the_segment(start, end):
    points = bresenham(*start, *end)
    assert points[0] == start and points[-1] == end
    for (xa, ya), (xb, yb) in itertools.pairwise(points):
        assert max(abs(xb - xa), abs(yb - ya)) == 1  # 8-connected, no repeats
    assert len(points) == max(abs(end[0] - start[0]), abs(end[1] - start[1])) + 1
    (x0, y0), (x1, y1) = start, end
    length = math.hypot(x1 - x0, y1 - y0)
    for x, y in points:
        if length:  # distance to the line, in the major axis' unit: at most 1/2
            distance = abs((x1 - x0) * (y0 - y) - (x0 - x) * (y1 - y0)) / length
            cosine = max(abs(x1 - x0), abs(y1 - y0)) / length
            assert distance * cosine <= 0.5 + 1e-9 * max(1.0, length) or distance <= 0.5


def test_a_diagonal_line_cell_by_cell():
    canvas = Canvas(2, 1)
    canvas.line(0, 0, 3, 3)
    assert canvas.lines() == [braille({(0, 0), (1, 1)}) + braille({(0, 2), (1, 3)})]


def test_glyph_hides_dots_and_text_is_cut_at_the_edge():
    canvas = Canvas(3, 1)
    canvas.line(0, 0, 5, 0)
    canvas.glyph(1, 0, "o", "bold")
    canvas.text(2, 0, "ab")
    assert canvas.lines() == [braille({(0, 0), (1, 0)}) + "oa"]
    assert canvas.styles[0][1] == "bold"


def test_viewport_maps_the_extent_corners_to_the_first_and_last_dots():
    view = Viewport.fit((-1.0, 1.0, -2.0, 2.0), 20, 39)
    assert view.to_dot(-1.0, 0.0)[0] == 0 and view.to_dot(1.0, 0.0)[0] == 19
    assert view.to_dot(0.0, 2.0)[1] == 0 and view.to_dot(0.0, -2.0)[1] == 38
    x, y = view.to_point(*view.to_dot(0.3, -0.7))
    assert abs(x - 0.3) <= 0.5 / view.scale and abs(y + 0.7) <= 0.5 / view.scale


@pytest.mark.parametrize(("most", "length"), [(0.37, 0.2), (1.0, 1.0), (0.099, 0.05), (7.0, 5.0)])
def test_nice_length(most, length):
    assert nice_length(most) == pytest.approx(length)


def table1_lengths() -> list[float]:
    with open(REPO / "presets" / "paper-a-table1.toml", "rb") as handle:
        return handle and tomllib.load(handle)["robot"]["lengths_m"]


def test_table1_arm_at_a_known_posture_cell_by_cell():
    """The 6R of paper A Table 1 at θ = [90, -90, 0, -90, 0, 90]° (relative): every link
    is axis-aligned, so its dots are the straight runs between its ends' dots."""
    lengths = table1_lengths()
    theta_deg = [90, -90, 0, -90, 0, 90]
    columns, rows = 17, 9
    # closed form: absolute angles 90, 0, 0, -90, -90, 0
    absolute = [90, 0, 0, -90, -90, 0]
    points = [(0.0, 0.0)]
    for length, angle in zip(lengths, absolute, strict=True):
        x, y = points[-1]
        points.append(
            (
                x + length * round(math.cos(math.radians(angle))),
                y + length * round(math.sin(math.radians(angle))),
            )
        )
    assert points[-1] == pytest.approx((0.6, -0.1))
    reach = sum(lengths)
    width, height = 2 * columns, 4 * (rows - 1)  # the last row: the scale bar
    scale = min((width - 1) / (2 * reach), (height - 1) / (2 * reach))

    def dot(x: float, y: float) -> tuple[int, int]:
        return math.floor(width / 2 + x * scale), math.floor(height / 2 - y * scale)

    dots = set()
    for (xa, ya), (xb, yb) in itertools.pairwise(points):
        (c0, r0), (c1, r1) = dot(xa, ya), dot(xb, yb)
        assert c0 == c1 or r0 == r1
        for c in range(min(c0, c1), max(c0, c1) + 1):
            for r in range(min(r0, r1), max(r0, r1) + 1):
                dots.add((c, r))
    expected = expected_cells(dots, columns, rows - 1)
    glyphs = ["#"] + ["o"] * 5 + ["+"]
    for (x, y), glyph in zip(points, glyphs, strict=True):
        c, r = dot(x, y)
        expected[r // 4][c // 2] = glyph
    canvas = render_scene(serial_scene(lengths, theta_deg), columns, rows)
    got = canvas.lines()
    for row in range(rows - 1):
        for column in range(columns):
            assert got[row][column] == expected[row][column], (row, column, got)
    # the scale bar: 40 % of the 34 dots at 31 / 2.4 dots per m is 1.05 m → 1 m
    bar_cells = round(1.0 * scale / 2)
    assert bar_cells == 6
    assert got[-1].startswith("├────┤ 1 m")
    assert (
        draw_serial_robot(lengths, theta_deg, columns, rows).splitlines()[0]
        == "".join(expected[0]).rstrip()
    )


def test_rrr_legs_close_in_the_working_mode_of_the_limits():
    """The leg angles at a point satisfy |C_i - B_i| = l2 with B_i = A_i + l1 e(θ_i), and
    lie within the joint limits (checked by forward kinematics here)."""
    from planar_tui.workspace.rrr.robot import Robot3RRR

    robot = Robot3RRR()
    limits = [(math.radians(-180), math.radians(180))] * 3
    point = (40.0, 20.0)
    legs = leg_modes(robot, 0.0, point, limits)
    base = robot.base_joints_cm()
    for (theta, mode), (ax, ay), (qx, qy) in zip(
        legs, base, robot.platform_points_cm(), strict=True
    ):
        assert mode in (1, -1)
        bx, by = ax + 30 * math.cos(theta), ay + 30 * math.sin(theta)
        assert math.hypot(point[0] + qx - bx, point[1] + qy - by) == pytest.approx(30.0)
    narrow = [(0.0, 0.1)] * 3  # no leg reaches (40, 20) with θ in [0, 0.1] rad
    assert leg_modes(robot, 0.0, point, narrow) == [None, None, None] or any(
        leg is None for leg in leg_modes(robot, 0.0, point, narrow)
    )
    canvas = render_scene(rrr_scene(robot, point, 0.0, legs), 40, 12)
    text = "\n".join(canvas.lines())
    assert text.count("#") == 3 and text.count("*") == 3 and text.count("o") == 3

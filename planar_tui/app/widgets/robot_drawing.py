"""Drawings of the robots on a braille canvas (:mod:`.canvas`): the serial arm in a
posture and the 3-RRR at a platform position, with a scale bar in metres.

A :class:`Scene` is a set of polylines (links) and joint glyphs in metres; :func:`render_scene`
fits its extent into a canvas of ``columns × rows`` cells (the last row holds the scale
bar) and draws the links as dots (Bresenham), then the joints as glyphs on top:
``#`` a base (actuated) joint, ``o`` a passive joint, ``+`` the serial arm's tip, ``*`` a
platform joint of the 3-RRR. :class:`SceneView` is the Textual widget that draws a scene
sized to its pane.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

from textual.widget import Widget

from planar_tui.app.widgets.canvas import Canvas, Viewport, nice_length

BASE_GLYPH, JOINT_GLYPH, TIP_GLYPH, PLATFORM_GLYPH = "#", "o", "+", "*"
LINK_STYLE, JOINT_STYLE, BASE_STYLE, TIP_STYLE = (
    "bold cyan",
    "bold yellow",
    "bold red",
    "bold green",
)
DISTAL_STYLE, PLATFORM_STYLE, TRIANGLE_STYLE = "green", "bold magenta", "blue"
#: The legend of a drawing's glyphs (the help screen and docs/app.md say the same).
GLYPH_LEGEND = f"{BASE_GLYPH} base  {JOINT_GLYPH} joint  {TIP_GLYPH} tip  ⠿ links"


@dataclass
class Scene:
    """What to draw, in metres: ``links`` ``(points, style)`` polylines, ``joints``
    ``(point, glyph, style)``, within ``extent`` ``(x_lo, x_hi, y_lo, y_hi)``."""

    extent: tuple[float, float, float, float]
    links: list[tuple[list[tuple[float, float]], str]] = field(default_factory=list)
    joints: list[tuple[tuple[float, float], str, str]] = field(default_factory=list)
    caption: str = ""


def joint_positions_m(
    lengths_m: Sequence[float], theta_deg: Sequence[float]
) -> list[tuple[float, float]]:
    """Joint positions (base first, tip last) for relative joint angles (paper A eq. 1):
    ``p_{i+1} = p_i + l_i (cos Σ_{j<=i} θ_j, sin Σ_{j<=i} θ_j)``."""
    points = [(0.0, 0.0)]
    angle = 0.0
    for length, theta in zip(lengths_m, theta_deg, strict=False):
        angle += math.radians(theta)
        x, y = points[-1]
        points.append((x + length * math.cos(angle), y + length * math.sin(angle)))
    return points


def serial_scene(
    lengths_m: Sequence[float],
    theta_deg: Sequence[float],
    ghosts: Sequence[tuple[Sequence[float], str]] = (),
    caption: str = "",
) -> Scene:
    """The serial arm at relative angles ``theta_deg`` (missing angles: 0) in the square
    ``[-R, R]²`` of its reach ``R = Σ l_i`` (fixed, so a moving arm keeps its scale), base
    at the origin; ``ghosts`` are other postures ``(theta_deg, style)`` drawn as links only
    (a band's 5 % and 95 % arms)."""
    reach = sum(abs(length) for length in lengths_m) or 1.0
    scene = Scene((-reach, reach, -reach, reach), caption=caption)
    for theta, style in ghosts:
        scene.links.append((joint_positions_m(lengths_m, _padded(theta, lengths_m)), style))
    points = joint_positions_m(lengths_m, _padded(theta_deg, lengths_m))
    scene.links.append((points, LINK_STYLE))
    scene.joints.append((points[0], BASE_GLYPH, BASE_STYLE))
    scene.joints += [(point, JOINT_GLYPH, JOINT_STYLE) for point in points[1:-1]]
    scene.joints.append((points[-1], TIP_GLYPH, TIP_STYLE))
    return scene


def _padded(theta_deg: Sequence[float], lengths_m: Sequence[float]) -> list[float]:
    return list(theta_deg)[: len(lengths_m)] + [0.0] * max(0, len(lengths_m) - len(theta_deg))


def render_scene(scene: Scene, columns: int, rows: int) -> Canvas:
    """``scene`` drawn in ``columns × rows`` cells: the extent fitted into the dots of the
    first ``rows - 1`` rows (:class:`~.canvas.Viewport`), each link a Bresenham line
    between its points' dots, each joint's glyph in the cell of its dot, and on the last
    row a scale bar ``├──┤ 0.2 m`` of a 1-2-5 length at most 40 % of the width."""
    canvas = Canvas(columns, rows)
    drawn_rows = max(1, canvas.rows - 1) if canvas.rows >= 3 else canvas.rows
    view = Viewport.fit(scene.extent, canvas.width_dots, 4 * drawn_rows)
    for points, style in scene.links:
        dots = [view.to_dot(x, y) for x, y in points]
        for (x0, y0), (x1, y1) in itertools.pairwise(dots):
            canvas.line(x0, y0, x1, y1, style)
    for (x, y), glyph, style in scene.joints:
        x_dot, y_dot = view.to_dot(x, y)
        if 0 <= y_dot < 4 * drawn_rows:
            canvas.glyph(x_dot // 2, y_dot // 4, glyph, style)
    if drawn_rows < canvas.rows:
        length_m = nice_length(0.4 * canvas.width_dots / view.scale)
        cells = max(2, round(length_m * view.scale / 2))
        bar = "├" + "─" * (cells - 2) + "┤"
        canvas.text(0, canvas.rows - 1, f"{bar} {length_m:g} m", "dim")
        if scene.caption:
            start = max(len(bar) + 8, canvas.columns - len(scene.caption))
            canvas.text(start, canvas.rows - 1, scene.caption, "dim")
    return canvas


def draw_serial_robot(
    lengths_m: Sequence[float], theta_deg: Sequence[float], width: int = 36, height: int = 11
) -> str:
    """The serial arm as plain text in ``width × height`` cells (:func:`render_scene`)."""
    canvas = render_scene(serial_scene(lengths_m, theta_deg), width, height)
    return "\n".join(line.rstrip() for line in canvas.lines())


# -- the 3-RRR --------------------------------------------------------------------------
def rrr_scene(
    robot,
    point_cm: tuple[float, float],
    orientation_rad: float,
    legs: Sequence[tuple[float, int] | None],
    caption: str = "",
) -> Scene:
    """The 3-RRR at the platform position ``point_cm``: the base triangle ``A1A2A3``, each
    leg ``A_i → B_i = A_i + l1(cos θ_i, sin θ_i) → C_i`` (a leg that cannot close is not
    drawn), the platform ``C_i = p + R(φ) q_i``; drawn in metres within the base joints'
    bounding box grown by ``l1`` (fixed, so a moving cursor keeps the scale)."""
    to_m = 0.01
    base = [(x * to_m, y * to_m) for x, y in robot.base_joints_cm()]
    c, s = math.cos(orientation_rad), math.sin(orientation_rad)
    platform = [
        ((point_cm[0] + c * qx - s * qy) * to_m, (point_cm[1] + s * qx + c * qy) * to_m)
        for qx, qy in robot.platform_points_cm()
    ]
    grow = robot.proximal_cm * to_m
    extent = (
        min(x for x, _ in base) - grow,
        max(x for x, _ in base) + grow,
        min(y for _, y in base) - grow,
        max(y for _, y in base) + grow,
    )
    scene = Scene(extent, caption=caption)
    scene.links.append(([*base, base[0]], TRIANGLE_STYLE))
    elbows = []
    for (ax, ay), tip, leg in zip(base, platform, legs, strict=True):
        if leg is None:
            continue
        elbow = (
            ax + robot.proximal_cm * to_m * math.cos(leg[0]),
            ay + robot.proximal_cm * to_m * math.sin(leg[0]),
        )
        scene.links.append(([(ax, ay), elbow], LINK_STYLE))
        scene.links.append(([elbow, tip], DISTAL_STYLE))
        elbows.append(elbow)
    scene.links.append(([*platform, platform[0]], PLATFORM_STYLE))
    scene.joints += [(point, BASE_GLYPH, BASE_STYLE) for point in base]
    scene.joints += [(point, JOINT_GLYPH, JOINT_STYLE) for point in elbows]
    scene.joints += [(point, PLATFORM_GLYPH, PLATFORM_STYLE) for point in platform]
    return scene


class SceneView(Widget):
    """A :class:`Scene` drawn to the widget's size (redrawn when it changes)."""

    DEFAULT_CSS = "SceneView { width: 1fr; height: 1fr; min-height: 4; }"

    def __init__(self, placeholder: str = "", **kwargs):
        super().__init__(**kwargs)
        self.scene: Scene | None = None
        self.placeholder = placeholder

    def show(self, scene: Scene | None) -> None:
        self.scene = scene
        self.refresh()

    def render(self):
        from rich.text import Text

        if self.scene is None:
            return Text(self.placeholder)
        size = self.content_region.size
        return render_scene(self.scene, size.width, size.height).to_text()


def numbers_or_zeros(value: Any, n: int) -> list[float]:
    """``value`` as n floats when it is a list of numbers, else n zeros (for drawings)."""
    if isinstance(value, list) and all(
        isinstance(v, int | float) and not isinstance(v, bool) for v in value
    ):
        return [float(v) for v in value[:n]] + [0.0] * max(0, n - len(value))
    return [0.0] * n

"""Figure of a 3-RRR workspace (paper B, figures 4-6): the kept boxes coloured inside /
boundary, the exact boundary (the geometric form's inner polygon,
:func:`planar_tui.workspace.rrr.geometry.workspace_polygon`) drawn over them, and the robot at
a pose inside the workspace (base triangle, legs, platform); axes in cm, equal aspect.

The pose: the platform point at a point inside the exact workspace, then each leg's
passive joint :math:`B_i` where the circles :math:`|B - A_i| = l_1` and
:math:`|B - C_i| = l_2` meet, the solution whose active angle lies within the joint's
limits (:math:`C_i = (x, y) + R(\\varphi) q_i`).

From the CSVs alone: the boxes CSV (``x_lo_cm, x_hi_cm, y_lo_cm, y_hi_cm, status``) gives
the boxes; the summary CSV gives the certified bracket
``area_inside_cm2 ≤ exact ≤ area_kept_cm2`` beside the exact area, as bars.
"""

from __future__ import annotations

import math
from typing import Any

from planar_tui.csvio import CsvTable
from planar_tui.figures.canvas import DISPLAY_NOTE, new_figure
from planar_tui.figures.table import column, has_columns, text_column
from planar_tui.workspace.paving.result import map_title

BOXES = ("x_lo_cm", "x_hi_cm", "y_lo_cm", "y_hi_cm", "status")
SUMMARY = ("form", "precision_cm", "area_kept_cm2", "area_inside_cm2")
INSIDE_COLOUR, BOUNDARY_COLOUR = "#4c9f70", "#f2b134"
#: Boxes above which the box layers are rasterised in SVG and PDF (the file stays small).
RASTER_ABOVE = 2000
#: Segments per turn of the drawn exact boundary.
BOUNDARY_SEGMENTS = 720
#: Boxes above which the boxes are drawn as one image (:func:`box_image`), not one
#: rectangle each: 200 000 rectangles took 15 s on an idle machine, 43 s under load.
MAX_DRAWN_BOXES = 20_000
#: That image's pixels along the longer side of the boxes' extent.
IMAGE_PIXELS = 1200


def matches_boxes(header: tuple[str, ...]) -> bool:
    return has_columns(header, BOXES)


def matches_summary(header: tuple[str, ...]) -> bool:
    return has_columns(header, SUMMARY)


def coverage(boxes: Any, origin: tuple[float, float], scale: float, shape: Any) -> Any:
    """The pixels of a grid of ``shape`` (rows along y) that the boxes cover, each box from
    pixel :math:`\\lfloor (x_{lo} - x_0) s \\rfloor` to :math:`\\lceil (x_{hi} - x_0) s
    \\rceil` (at least one pixel; the same along y): a 2-D difference array, +1 at the
    corners (lo, lo) and (hi, hi), -1 at (lo, hi) and (hi, lo), summed along both axes,
    counts the boxes over each pixel."""
    import numpy as np

    ny, nx = shape
    edges = []
    for lo, hi, origin_cm, n in ((0, 1, origin[0], nx), (2, 3, origin[1], ny)):
        first = np.clip(np.floor((boxes[:, lo] - origin_cm) * scale), 0, n - 1).astype(np.intp)
        last = np.clip(np.ceil((boxes[:, hi] - origin_cm) * scale), first + 1, n)
        edges.append((first, last.astype(np.intp)))
    (i0, i1), (j0, j1) = edges
    counts = np.zeros((ny + 1, nx + 1), dtype=np.int64)
    for rows, cols, sign in ((j0, i0, 1), (j0, i1, -1), (j1, i0, -1), (j1, i1, 1)):
        np.add.at(counts, (rows, cols), sign)
    return counts.cumsum(axis=0).cumsum(axis=1)[:ny, :nx] > 0


def box_image(ax: Any, boxes: Any, inside: Any) -> str:
    """The kept boxes painted on one image of :data:`IMAGE_PIXELS` along the longer side
    (:func:`coverage`; a boundary box over an inside one, as the collections are stacked),
    with legend entries for both colours; the note saying so, returned."""
    import numpy as np
    from matplotlib.colors import to_rgba
    from matplotlib.patches import Rectangle

    x0, x1 = float(boxes[:, 0].min()), float(boxes[:, 1].max())
    y0, y1 = float(boxes[:, 2].min()), float(boxes[:, 3].max())
    scale = IMAGE_PIXELS / max(x1 - x0, y1 - y0, 1e-300)
    shape = (max(1, math.ceil((y1 - y0) * scale)), max(1, math.ceil((x1 - x0) * scale)))
    image = np.zeros((*shape, 4))
    for mask, face, label in (
        (inside, INSIDE_COLOUR, "inside (proved)"),
        (~inside, BOUNDARY_COLOUR, "boundary (kept)"),
    ):
        image[coverage(boxes[mask], (x0, y0), scale, shape)] = to_rgba(face)
        ax.add_patch(Rectangle((x0, y0), 0.0, 0.0, facecolor=face, label=label))  # legend
    ax.imshow(
        image, origin="lower", extent=(x0, x1, y0, y1), interpolation="nearest", gid="boxes-image"
    )
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    return (
        f"{len(boxes):,} boxes drawn as one image of {shape[1]} × {shape[0]} pixels "
        "(a box narrower than a pixel fills one)"
    )


def draw_boxes(ax: Any, boxes: Any, inside: Any) -> None:
    """The kept boxes as two collections (inside, boundary), one rectangle per box; past
    :data:`MAX_DRAWN_BOXES`, one image (:func:`box_image`) and its note under the axes
    (:data:`~planar_tui.figures.canvas.DISPLAY_NOTE`)."""
    import numpy as np
    from matplotlib.collections import PolyCollection

    if len(boxes) > MAX_DRAWN_BOXES:
        note = box_image(ax, boxes, inside)
        ax.text(
            0.01,
            0.01,
            note,
            transform=ax.transAxes,
            fontsize="small",
            gid=DISPLAY_NOTE,
            bbox={"facecolor": "white", "alpha": 0.8, "edgecolor": "none"},
        )
        return
    for mask, face, label in (
        (inside, INSIDE_COLOUR, "inside (proved)"),
        (~inside, BOUNDARY_COLOUR, "boundary (kept)"),
    ):
        b = boxes[mask]
        verts = (
            np.stack([b[:, [0, 2]], b[:, [1, 2]], b[:, [1, 3]], b[:, [0, 3]]], axis=1)
            if len(b)
            else np.zeros((0, 4, 2))
        )
        collection = PolyCollection(
            verts,
            facecolors=face,
            edgecolors="none",
            label=label,
            gid=label.split()[0],
            rasterized=len(boxes) > RASTER_ABOVE,
        )
        ax.add_collection(collection)
    if len(boxes):
        ax.set_xlim(boxes[:, 0].min(), boxes[:, 1].max())
        ax.set_ylim(boxes[:, 2].min(), boxes[:, 3].max())


def _polygon_rings(polygon: Any) -> list[Any]:
    """Exterior and interior rings of a shapely (multi)polygon as coordinate arrays."""
    import numpy as np

    parts = getattr(polygon, "geoms", [polygon])
    rings = []
    for part in parts:
        if part.is_empty or not hasattr(part, "exterior"):
            continue
        rings.append(np.asarray(part.exterior.coords))
        rings.extend(np.asarray(ring.coords) for ring in part.interiors)
    return rings


def leg_pose(a, c, l1, l2, lo, hi) -> tuple[float, float] | None:
    """The passive joint ``B`` of a leg from base joint ``a`` to platform point ``c``
    whose active angle lies in ``[lo, hi]`` (radians, modulo 2π), or ``None``."""
    dx, dy = c[0] - a[0], c[1] - a[1]
    d = math.hypot(dx, dy)
    if d == 0 or d > l1 + l2 or d < abs(l1 - l2):
        return None
    base = math.atan2(dy, dx)
    spread = math.acos(max(-1.0, min(1.0, (l1 * l1 + d * d - l2 * l2) / (2 * l1 * d))))
    for angle in (base + spread, base - spread):
        if (angle - lo) % (2 * math.pi) <= (hi - lo) + 1e-9:
            return (a[0] + l1 * math.cos(angle), a[1] + l1 * math.sin(angle))
    return None


def draw_robot(ax: Any, robot: Any, spec: Any, point: tuple[float, float]) -> bool:
    """The 3-RRR with its platform point at ``point``: base triangle, legs, platform.
    False (nothing drawn) when a leg cannot reach within its limits."""
    phi = spec.orientation_rad
    c_, s_ = math.cos(phi), math.sin(phi)
    base = robot.base_joints_cm()
    platform = [
        (point[0] + c_ * qx - s_ * qy, point[1] + s_ * qx + c_ * qy)
        for qx, qy in robot.platform_points_cm()
    ]
    joints = [
        leg_pose(a, c, robot.proximal_cm, robot.distal_cm, lo, hi)
        for a, c, (lo, hi) in zip(base, platform, spec.limits_rad, strict=True)
    ]
    if any(b is None for b in joints):
        return False
    closed = [*base, base[0]]
    ax.fill(*zip(*closed, strict=True), color="0.85", zorder=0, gid="base")
    ax.plot(*zip(*closed, strict=True), color="0.4", lw=1.0, gid="base")
    for a, b, c in zip(base, joints, platform, strict=True):
        ax.plot(
            [a[0], b[0], c[0]], [a[1], b[1], c[1]], "-o", color="#3a5fcd", lw=1.6, ms=3.5, gid="leg"
        )
    tri = [*platform, platform[0]]
    ax.fill(*zip(*tri, strict=True), color="#c0504d", alpha=0.5, gid="platform")
    ax.plot(*point, marker="+", color="k", ms=8, gid="point")
    return True


def draw_singularity(ax: Any, singularity: Any) -> None:
    """Type II singularities over the boxes: the boxes that may hold a singular pose (one
    collection, ``gid`` ``"singular"``, one rectangle each) and the certified
    singularity-free circle of radius ``radius_lo_cm`` about its centre (``gid``
    ``"circle"``), the centre marked."""
    import numpy as np
    from matplotlib.collections import PolyCollection
    from matplotlib.patches import Circle

    b = np.asarray(singularity.singular_boxes).reshape(-1, 4)
    verts = np.stack([b[:, [0, 2]], b[:, [1, 2]], b[:, [1, 3]], b[:, [0, 3]]], axis=1)
    ax.add_collection(
        PolyCollection(
            verts,
            facecolors="#c0392b",
            edgecolors="#c0392b",
            linewidths=0.5,
            zorder=3,
            gid="singular",
            label="may be singular (type II)",
            rasterized=len(b) > RASTER_ABOVE,
        )
    )
    x, y = singularity.centre_cm
    ax.add_patch(
        Circle(
            (x, y),
            singularity.radius_lo_cm,
            fill=False,
            color="#1f4e79",
            lw=1.5,
            gid="circle",
            zorder=4,
            label=f"singularity-free, r ≥ {singularity.radius_lo_cm:.4g} cm",
        )
    )
    ax.plot(x, y, marker="+", color="#1f4e79", ms=10, gid="circle-centre")


def draw(
    boxes: Any,
    inside: Any,
    title: str,
    robot: Any = None,
    spec: Any = None,
    summary: str = "",
    singularity: Any = None,
    exact: Any = None,
) -> Any:
    """Boxes (rows ``x_lo, x_hi, y_lo, y_hi``; ``inside`` a boolean per box), with the
    exact boundary and the robot when ``robot`` and ``spec`` are given (a 3-RRR), the
    boundary of the polygon ``exact`` alone (another mechanism), and the type II
    singularities and singularity-free circle when ``singularity`` is given
    (:class:`~planar_tui.workspace.rrr.singularity.SingularityOutcome`)."""
    with_robot = robot is not None and spec is not None
    fig = new_figure(12.0 if with_robot else 7.0, 6.0)
    if with_robot:
        overview, ax = fig.subplots(1, 2)
    else:
        ax, overview = fig.add_subplot(), None
    draw_boxes(ax, boxes, inside)
    if singularity is not None:
        draw_singularity(ax, singularity)
    if with_robot:
        polygon = spec.mechanism.polygon(robot, spec, BOUNDARY_SEGMENTS, False)
        for k, ring in enumerate(_polygon_rings(polygon)):
            for target in (ax, overview):
                target.plot(
                    ring[:, 0],
                    ring[:, 1],
                    color="k",
                    lw=1.0,
                    gid="exact",
                    label="exact boundary" if k == 0 else None,
                )
        if not polygon.is_empty:
            centre = polygon.centroid
            inner = centre if polygon.contains(centre) else polygon.representative_point()
            draw_robot(overview, robot, spec, (inner.x, inner.y))
            ax.plot(inner.x, inner.y, marker="+", color="k", ms=10)
            if not len(boxes):
                x0, y0, x1, y1 = polygon.bounds
                pad = 0.05 * max(x1 - x0, y1 - y0, 1e-9)
                ax.set(xlim=(x0 - pad, x1 + pad), ylim=(y0 - pad, y1 + pad))
        overview.set(
            xlabel="x (cm)", ylabel="y (cm)", aspect="equal", title="the robot at a pose inside"
        )
        overview.grid(alpha=0.3)
    elif exact is not None:
        for k, ring in enumerate(_polygon_rings(exact)):
            ax.plot(
                ring[:, 0],
                ring[:, 1],
                color="k",
                lw=1.0,
                gid="exact",
                label="exact boundary" if k == 0 else None,
            )
    import textwrap

    ax.set(
        xlabel="x (cm)",
        ylabel="y (cm)",
        aspect="equal",
        title=textwrap.fill(summary or "workspace", 64),
    )
    ax.grid(alpha=0.3)
    ax.legend(loc="upper right", fontsize="small")
    fig.suptitle(title)
    return fig


def from_boxes_table(table: CsvTable, title: str) -> Any:
    """The boxes of a boxes CSV (no robot: no exact boundary, no pose); a header-only CSV
    (a geometric-form job keeps no boxes, nor does an empty workspace): the empty axes in
    cm with a "no boxes kept" note."""
    import numpy as np

    if not len(table.rows):
        fig = draw(np.zeros((0, 4)), np.zeros(0, dtype=bool), title, summary="no boxes kept")
        ax = fig.axes[0]
        ax.get_legend().remove()
        ax.text(
            0.5, 0.5, "no boxes kept", transform=ax.transAxes, ha="center", va="center", gid="note"
        )
        return fig
    boxes = np.column_stack([column(table, name) for name in BOXES[:4]])
    inside = np.array([s == "inside" for s in text_column(table, "status")], dtype=bool)
    return draw(boxes.reshape(-1, 4), inside, title, summary=f"{len(boxes)} kept boxes")


def from_summary_table(table: CsvTable, title: str) -> Any:
    """The certified area bracket of each summary row beside the exact area."""
    import numpy as np

    forms = text_column(table, "form")
    kept, inside = column(table, "area_kept_cm2"), column(table, "area_inside_cm2")
    exact = column(table, "area_geometric_cm2") if "area_geometric_cm2" in table.header else None
    fig = new_figure(8.5, 1.6 + 0.5 * len(forms))
    ax = fig.add_subplot()
    y = np.arange(len(forms))
    ax.barh(y, kept - inside, left=inside, color=BOUNDARY_COLOUR, label="bracket [inside, kept]")
    ax.barh(y, inside, color=INSIDE_COLOUR, alpha=0.35, label="inside (proved)")
    if exact is not None and np.isfinite(exact).any():
        ax.plot(exact, y, "k|", ms=16, mew=2, label="exact (geometric)")
    labels = [f"{f}, ε = {e:g}" for f, e in zip(forms, column(table, "precision_cm"), strict=True)]
    ax.set_yticks(y, labels)
    ax.set(xlabel="area (cm²)", title="certified area bracket")
    # beside the bars, never over them: the exact-area marker sits at a bar's end
    ax.legend(fontsize="small", loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0)
    fig.suptitle(title)
    return fig


def from_result(job: Any, result: Any) -> Any:
    """The figure of a finished workspace job: boxes, exact boundary, the robot."""
    import numpy as np

    from planar_tui.workspace.paving.levels import INSIDE

    outcome = result.outcome
    if outcome is None:
        return from_summary_table(result.table, job.label)
    if getattr(result, "companions", None):
        return draw_tolerance(job, result)
    boxes = np.asarray(outcome.boxes)[:, :4] if len(outcome.boxes) else np.zeros((0, 4))
    inside = np.asarray(outcome.status) == INSIDE
    if isinstance(job.spec.orientation_deg, tuple):  # a range of φ: no single exact boundary
        return draw(boxes, inside, map_title(job, outcome), summary=result.summary)
    return draw(
        boxes,
        inside,
        map_title(job, outcome),
        job.robot,
        job.spec,
        result.summary,
        getattr(result, "singularity", None),
    )


#: Tolerance figure layers, drawn bottom up: which outcome, which boxes, colour, label.
TOLERANCE_LAYERS = (
    ("some", "kept", "#c6dbef", 'some robot ("some", kept)'),
    ("nominal", "kept", "#6baed6", "nominal robot (kept)"),
    ("all", "kept", "#fd8d3c", 'every robot ("all", boundary)'),
    ("all", "inside", "#08306b", 'every robot ("all", proved)'),
)


def draw_tolerance(job: Any, result: Any, exact: Any = None) -> Any:
    """A tolerance-certified job: the "some", nominal and robust ("all") workspaces
    overlaid, each bracket in the legend, and the nominal exact boundary (``exact``, the
    kind's inner polygon; default its robot's, :meth:`Mechanism.polygon`)."""
    import textwrap

    import numpy as np
    from matplotlib.collections import PolyCollection

    from planar_tui.workspace.paving.levels import INSIDE

    outcomes = {job.spec.tolerance_mode: result.outcome, **result.companions}
    fig = new_figure(9.0, 5.5)
    ax = fig.add_subplot()
    for name, which, colour, label in TOLERANCE_LAYERS:
        o = outcomes[name]
        b = o.boxes[o.status == INSIDE] if which == "inside" else o.boxes
        verts = np.stack([b[:, [0, 2]], b[:, [1, 2]], b[:, [1, 3]], b[:, [0, 3]]], axis=1)
        area = o.area_inside_cm2 if which == "inside" else o.area_kept_cm2
        ax.add_collection(
            PolyCollection(
                verts,
                facecolors=colour,
                edgecolors="none",
                gid=f"{name}-{which}",
                label=f"{label}: {area:.5g} cm2",
                rasterized=len(b) > RASTER_ABOVE,
            )
        )
    polygon = exact
    if polygon is None:  # the robot's own (a 3-RRR job passes none)
        polygon = job.spec.mechanism.polygon(job.robot, job.spec, BOUNDARY_SEGMENTS, False)
    for k, ring in enumerate(_polygon_rings(polygon)):
        ax.plot(
            ring[:, 0],
            ring[:, 1],
            color="k",
            lw=0.8,
            gid="exact",
            label="nominal exact boundary" if k == 0 else None,
        )
    every = np.concatenate([o.boxes for o in outcomes.values()])
    if len(every):
        ax.set_xlim(every[:, 0].min(), every[:, 1].max())
        ax.set_ylim(every[:, 2].min(), every[:, 3].max())
    ax.set(
        xlabel="x (cm)", ylabel="y (cm)", aspect="equal", title=textwrap.fill(result.summary, 72)
    )
    ax.title.set_fontsize("small")
    ax.grid(alpha=0.3)
    ax.legend(loc="upper right", fontsize="small")
    fig.suptitle(map_title(job, result.outcome))
    return fig


def from_planar_result(job: Any, result: Any) -> Any:
    """The figure of a finished 3-RPR or 3-PRR job (:mod:`planar_tui.workspace.paving.runner`):
    boxes and the exact boundary (the inner polygon of the kind's exact reference); with a
    tolerance, :func:`draw_tolerance`."""
    import numpy as np

    from planar_tui.workspace.paving.levels import INSIDE

    outcome = result.outcome
    boxes = np.asarray(outcome.boxes)[:, :4] if len(outcome.boxes) else np.zeros((0, 4))
    exact = (
        None
        if isinstance(job.spec.orientation_deg, tuple)  # a range: no single boundary
        else job.spec.mechanism.polygon(job.robot, job.spec, BOUNDARY_SEGMENTS, False)
    )
    if getattr(result, "companions", None):
        return draw_tolerance(job, result, exact)
    return draw(
        boxes,
        np.asarray(outcome.status) == INSIDE,
        map_title(job, outcome),
        summary=result.summary,
        exact=exact,
    )

"""The dexterous region in a workspace figure: a κ heat-map panel and the dexterous layer.

Each kept box of the dexterity paving
(:class:`~planar_tui.workspace.paving.dexterity.DexterityOutcome`) is coloured by the
*bin* of its certified upper bound :math:`\\bar\\kappa` (``kappa_hi``): :data:`KAPPA_BINS`
equal bins of :math:`[1, \\kappa_{max}]`,

.. math:: b = \\min\\left(\\left\\lfloor N \\frac{\\bar\\kappa - 1}{\\kappa_{max} - 1}
   \\right\\rfloor, N - 1\\right) \\quad (\\bar\\kappa \\le \\kappa_{max}),

the colour is capped at :math:`b = N` for a finite bound above :math:`\\kappa_{max}` (a
boundary box), and a box whose bound is unbounded (it may hold a singular pose) is drawn
hatched in its own collection. The workspace panel gets the proved dexterous boxes as a
translucent layer. Past :data:`~planar_tui.figures.workspace.MAX_DRAWN_BOXES` boxes the
heat map is one image (:func:`~planar_tui.figures.workspace.coverage`, the worst bin of the
boxes over a pixel wins)."""

from __future__ import annotations

import math
from typing import Any

from planar_tui.figures.canvas import DISPLAY_NOTE
from planar_tui.figures.workspace import IMAGE_PIXELS, MAX_DRAWN_BOXES, RASTER_ABOVE, coverage

#: Equal bins of [1, kappa_max]; bin KAPPA_BINS holds finite bounds above kappa_max.
KAPPA_BINS = 8
#: The colour of the capped bin (a finite bound above kappa_max).
CAPPED_COLOUR = "#bdbdbd"
DEXTEROUS_COLOUR = "#6a3d9a"
#: The gids of the workspace's box layers (:func:`~planar_tui.figures.workspace.draw_boxes`).
BOX_GIDS = ("inside", "boundary", "boxes-image")
#: The heat-map panel's title (tests find the panel by it).
PANEL_TITLE = "κ upper bound per box"


def kappa_bins(kappa_hi: Any, kappa_max: float) -> Any:
    """Each box's colour bin (module docstring): ``0 .. KAPPA_BINS - 1`` for
    :math:`\\bar\\kappa \\le \\kappa_{max}`, ``KAPPA_BINS`` for a finite bound above it,
    ``-1`` for an unbounded one."""
    import numpy as np

    hi = np.asarray(kappa_hi, dtype=float)
    scaled = np.floor(KAPPA_BINS * (np.minimum(hi, kappa_max) - 1.0) / (kappa_max - 1.0))
    bins = np.clip(np.nan_to_num(scaled), 0, KAPPA_BINS - 1).astype(np.int64)
    bins[hi > kappa_max] = KAPPA_BINS
    bins[~np.isfinite(hi)] = -1
    return bins


def colour_map() -> tuple[Any, Any]:
    """The heat map's colours (``viridis`` reversed over the bins, grey for the capped
    bin) and the norm that maps bin ``b`` to colour ``b``."""
    import numpy as np
    from matplotlib import colormaps
    from matplotlib.colors import BoundaryNorm, ListedColormap

    steps = [colormaps["viridis_r"](k / (KAPPA_BINS - 1)) for k in range(KAPPA_BINS)]
    cmap = ListedColormap([*steps, CAPPED_COLOUR])
    return cmap, BoundaryNorm(np.arange(KAPPA_BINS + 2) - 0.5, KAPPA_BINS + 1)


def box_verts(boxes: Any) -> Any:
    """Each box ``x_lo, x_hi, y_lo, y_hi`` as its four corners (a PolyCollection's input)."""
    import numpy as np

    b = np.asarray(boxes).reshape(-1, 4)
    return np.stack([b[:, [0, 2]], b[:, [1, 2]], b[:, [1, 3]], b[:, [0, 3]]], axis=1)


def heat_image(
    ax: Any, boxes: Any, bins: Any, cmap: Any, norm: Any, gid: str = "kappa-image", levels=None
) -> None:
    """The boxes' bins (``0 .. max``) painted on one image, the worst bin over a pixel
    wins; each pixel holds its bin, or ``levels[bin]`` when given."""
    import numpy as np

    x0, x1 = float(boxes[:, 0].min()), float(boxes[:, 1].max())
    y0, y1 = float(boxes[:, 2].min()), float(boxes[:, 3].max())
    scale = IMAGE_PIXELS / max(x1 - x0, y1 - y0, 1e-300)
    shape = (max(1, math.ceil((y1 - y0) * scale)), max(1, math.ceil((x1 - x0) * scale)))
    image = np.full(shape, np.nan)
    for b in range(int(bins.max()) + 1 if len(bins) else 0):
        image[coverage(boxes[bins == b], (x0, y0), scale, shape)] = (
            b if levels is None else levels[b]
        )
    ax.imshow(
        np.ma.masked_invalid(image),
        origin="lower",
        extent=(x0, x1, y0, y1),
        interpolation="nearest",
        cmap=cmap,
        norm=norm,
        gid=gid,
    )
    ax.text(
        0.01,
        0.01,
        f"{len(boxes):,} boxes drawn as one image",
        transform=ax.transAxes,
        fontsize="small",
        gid=DISPLAY_NOTE,
    )


def draw_heat(
    ax: Any,
    boxes: Any,
    known: Any,
    values: Any,
    levels: Any,
    colours: tuple[Any, Any],
    gid: str,
    unknown: dict[str, Any],
    title: str,
    image_levels: Any = None,
) -> Any:
    """A heat-map panel on ``ax``: the ``known`` boxes coloured by ``values`` as one
    collection (``gid``), or past :data:`MAX_DRAWN_BOXES` one image (``gid-image``) of
    their integer ``levels`` (:func:`heat_image`, ``image_levels``), and the other boxes
    hatched in their own collection (``unknown``: its colours, ``gid`` and label); returns
    the mappable of ``colours`` (colour map, norm) for a colour bar."""
    import numpy as np
    from matplotlib.cm import ScalarMappable
    from matplotlib.collections import PolyCollection

    cmap, norm = colours
    if np.count_nonzero(known) > MAX_DRAWN_BOXES:
        heat_image(ax, boxes[known], levels[known], cmap, norm, f"{gid}-image", image_levels)
    else:
        ax.add_collection(
            PolyCollection(
                box_verts(boxes[known]),
                array=values[known],
                cmap=cmap,
                norm=norm,
                edgecolors="none",
                gid=gid,
                rasterized=len(boxes) > RASTER_ABOVE,
            )
        )
    ax.add_collection(
        PolyCollection(box_verts(boxes[~known]), hatch="xxx", linewidths=0.3, **unknown)
    )
    if len(boxes):
        ax.set_xlim(boxes[:, 0].min(), boxes[:, 1].max())
        ax.set_ylim(boxes[:, 2].min(), boxes[:, 3].max())
    ax.set(xlabel="x (cm)", ylabel="y (cm)", aspect="equal", title=title)
    ax.grid(alpha=0.3)
    if np.any(~known):
        ax.legend(loc="upper right", fontsize="small")
    return ScalarMappable(norm=norm, cmap=cmap)


def draw_kappa(ax: Any, outcome: Any) -> Any:
    """The κ heat map of ``outcome`` on ``ax``: the bounded boxes as one collection
    (``gid`` ``"kappa"``, its array the bins) or one image, the unbounded ones hatched
    (``gid`` ``"kappa-unbounded"``); returns the mappable for a colour bar."""
    import numpy as np

    boxes = np.asarray(outcome.boxes, dtype=float).reshape(-1, 4)
    bins = kappa_bins(np.asarray(outcome.kappa).reshape(-1, 2)[:, 1], outcome.kappa_max)
    unbounded = {
        "facecolors": "white",
        "edgecolors": "#c0392b",
        "gid": "kappa-unbounded",
        "label": "κ unbounded (may be singular)",
    }
    return draw_heat(
        ax, boxes, bins >= 0, bins, bins, colour_map(), "kappa", unbounded, PANEL_TITLE
    )


def box_axes(fig: Any) -> Any:
    """The axes of a workspace figure that holds its boxes (else its first)."""
    return next(
        (ax for ax in fig.axes if any(a.get_gid() in BOX_GIDS for a in ax.get_children())),
        fig.axes[0],
    )


def new_panel(fig: Any) -> Any:
    """A new axes to the right of ``fig``'s panels, the figure 6 inches wider."""
    axes = [ax for ax in fig.axes if ax.get_subplotspec() is not None]
    width, height = fig.get_size_inches()
    fig.set_size_inches(width + 6.0, height)
    grid = fig.add_gridspec(1, len(axes) + 1)
    for k, ax in enumerate(axes):
        ax.set_subplotspec(grid[0, k])
    return fig.add_subplot(grid[0, len(axes)])


def add_kappa_panel(fig: Any, result: Any) -> Any:
    """``fig`` (a workspace figure, its first axes the boxes) with the dexterous layer on
    the boxes and a κ heat-map panel to the right, when ``result`` has a dexterity
    outcome; ``fig`` unchanged otherwise."""
    import numpy as np
    from matplotlib.collections import PolyCollection

    outcome = getattr(result, "dexterity", None)
    if outcome is None:
        return fig
    boxes = np.asarray(outcome.boxes).reshape(-1, 4)
    proved = boxes[np.asarray(outcome.status) == 2]
    main = box_axes(fig)
    main.add_collection(
        PolyCollection(
            box_verts(proved),
            facecolors=DEXTEROUS_COLOUR,
            alpha=0.35,
            edgecolors="none",
            gid="dexterous",
            label=f"dexterous, κ ≤ {outcome.kappa_max:g} (proved)",
            rasterized=len(proved) > RASTER_ABOVE,
            zorder=2,
        )
    )
    main.legend(loc="upper right", fontsize="small")
    panel = new_panel(fig)
    mappable = draw_kappa(panel, outcome)
    edges = 1.0 + (outcome.kappa_max - 1.0) * np.arange(KAPPA_BINS + 1) / KAPPA_BINS
    bar = fig.colorbar(mappable, ax=panel, ticks=np.arange(KAPPA_BINS + 1) - 0.5, shrink=0.8)
    bar.ax.set_yticklabels([f"{e:.3g}" for e in edges])
    bar.set_label(f"κ upper bound (grey: > {outcome.kappa_max:g})")
    return fig

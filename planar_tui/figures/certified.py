"""The certified performance in a workspace figure: the κ panel
(:mod:`planar_tui.figures.dexterity`), the interference-free layer and the error panel.

With ``leg_width_cm`` the workspace panel gets the proved interference-free boxes
(:class:`~planar_tui.workspace.paving.interference.InterferenceOutcome`, status 2) as a
translucent layer. With ``accuracy`` a panel to the right colours each accuracy box
(:class:`~planar_tui.workspace.paving.accuracy.AccuracyOutcome`) by its certified position
error

.. math:: e = \\max(\\overline{|\\Delta x|}, \\overline{|\\Delta y|}) \\quad \\text{(cm)},

on a colour scale from 0 to the largest certified :math:`e`; a box not certified
(:math:`e = \\infty`) is drawn grey and hatched in its own collection. Past
:data:`~planar_tui.figures.workspace.MAX_DRAWN_BOXES` boxes the certified ones are one
image of :data:`ERROR_LEVELS` levels, each pixel the upper edge of the worst level over it.
The kinds' ``figure`` entries point to the wrappers here."""

from __future__ import annotations

from typing import Any

from planar_tui.figures.dexterity import (
    add_kappa_panel,
    box_axes,
    box_verts,
    draw_heat,
    new_panel,
)
from planar_tui.figures.workspace import RASTER_ABOVE
from planar_tui.workspace.paving.accuracy import position_error

INTERFERENCE_COLOUR = "#1f78b4"
UNCERTIFIED_COLOUR = "#bdbdbd"
ERROR_CMAP = "magma_r"
#: Levels of the error image (past MAX_DRAWN_BOXES boxes).
ERROR_LEVELS = 64
#: The error panel's title (tests find the panel by it).
PANEL_TITLE = "certified max(|Δx|, |Δy|) per box"


def add_interference_layer(fig: Any, result: Any) -> Any:
    """``fig`` with the proved interference-free boxes as a layer on its boxes (``gid``
    ``"interference-free"``), when ``result`` has an interference outcome."""
    import numpy as np
    from matplotlib.collections import PolyCollection

    outcome = getattr(result, "interference", None)
    if outcome is None:
        return fig
    boxes = np.asarray(outcome.boxes).reshape(-1, 4)
    clear = boxes[np.asarray(outcome.status) == 2]
    main = box_axes(fig)
    main.add_collection(
        PolyCollection(
            box_verts(clear),
            facecolors="none",
            edgecolors=INTERFERENCE_COLOUR,
            hatch="//",
            linewidths=0.0,
            gid="interference-free",
            label=f"interference-free, links {outcome.width_cm:g} cm wide (proved)",
            rasterized=len(clear) > RASTER_ABOVE,
            zorder=3,
        )
    )
    main.legend(loc="upper right", fontsize="small")
    return fig


def draw_errors(ax: Any, outcome: Any) -> Any:
    """The error map of ``outcome`` on ``ax`` (module docstring): the certified boxes as
    one collection (``gid`` ``"accuracy"``, its array the errors in cm) or one image
    (``"accuracy-image"``), the others hatched (``"accuracy-uncertified"``); returns the
    mappable for a colour bar."""
    import numpy as np
    from matplotlib import colormaps
    from matplotlib.colors import Normalize

    boxes = np.asarray(outcome.boxes, dtype=float).reshape(-1, 4)
    error = position_error(outcome)
    certified = np.isfinite(error)
    top = float(error[certified].max()) if certified.any() else 1.0
    norm = Normalize(0.0, top if top > 0 else 1.0)
    levels = np.ceil(ERROR_LEVELS * np.nan_to_num(error, posinf=0.0) / norm.vmax) - 1
    levels = np.clip(levels, 0, ERROR_LEVELS - 1).astype(np.int64)
    edges = norm.vmax * np.arange(1, ERROR_LEVELS + 1) / ERROR_LEVELS
    uncertified = {
        "facecolors": UNCERTIFIED_COLOUR,
        "edgecolors": "#7f7f7f",
        "gid": "accuracy-uncertified",
        "label": "not certified",
    }
    colours = (colormaps[ERROR_CMAP], norm)
    return draw_heat(
        ax, boxes, certified, error, levels, colours, "accuracy", uncertified, PANEL_TITLE, edges
    )


def add_error_panel(fig: Any, result: Any) -> Any:
    """``fig`` with the error panel to the right, when ``result`` has an accuracy
    outcome; ``fig`` unchanged otherwise."""
    outcome = getattr(result, "accuracy", None)
    if outcome is None:
        return fig
    panel = new_panel(fig)
    bar = fig.colorbar(draw_errors(panel, outcome), ax=panel, shrink=0.8)
    bar.set_label("certified max(|Δx|, |Δy|) (cm)")
    return fig


def add_certified(fig: Any, result: Any) -> Any:
    """``fig`` with every certified layer and panel ``result`` has."""
    fig = add_kappa_panel(fig, result)
    fig = add_interference_layer(fig, result)
    return add_error_panel(fig, result)


def from_result(job: Any, result: Any) -> Any:
    """A 3-RRR workspace job's figure (:func:`planar_tui.figures.workspace.from_result`)
    with its certified layers and panels."""
    from planar_tui.figures.workspace import from_result as workspace_figure

    return add_certified(workspace_figure(job, result), result)


def from_planar_result(job: Any, result: Any) -> Any:
    """A 3-RPR or 3-PRR workspace job's figure
    (:func:`planar_tui.figures.workspace.from_planar_result`) with its certified layers."""
    from planar_tui.figures.workspace import from_planar_result as planar_figure

    return add_certified(planar_figure(job, result), result)


def from_fivebar_result(job: Any, result: Any) -> Any:
    """A five-bar workspace job's figure (:func:`planar_tui.figures.fivebar.from_result`)
    with its certified layers."""
    from planar_tui.figures.fivebar import from_result as fivebar_figure

    return add_certified(fivebar_figure(job, result), result)

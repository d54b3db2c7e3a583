"""A matplotlib figure without ``pyplot`` (Agg backend) and its atomic, reproducible save.

The format is the file's suffix (:data:`planar_tui.schema.FIGURE_SUFFIXES`); SVG and PDF
are written without a date and with a fixed hash salt, so the same result gives the same
file. A PNG has ``width_in × dpi`` by ``height_in × dpi`` pixels (no tight bounding box).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from planar_tui.csvio import write_atomic

#: Resolution of PNG figures (dots per inch; vector formats ignore it).
DPI = 120
#: Colours of the parameters, joints and outputs: matplotlib's ``tab20`` for up to 20
#: series, cycling beyond.
CMAP = "tab20"


#: The gid of a text saying how a figure shows its data for display (boxes merged into an
#: image ...): ``planar-tui plot`` repeats it on stderr (:func:`display_notes`).
DISPLAY_NOTE = "display-note"


def display_notes(figure: Any) -> list[str]:
    """The texts of ``figure`` with the gid :data:`DISPLAY_NOTE`."""
    return [t.get_text() for t in figure.findobj(lambda a: a.get_gid() == DISPLAY_NOTE)]


def new_figure(width_in: float, height_in: float) -> Any:
    """A :class:`matplotlib.figure.Figure` of that size with constrained layout."""
    import matplotlib

    matplotlib.use("Agg")
    matplotlib.rcParams["svg.hashsalt"] = "planar-tui"
    from matplotlib.figure import Figure

    return Figure(figsize=(width_in, height_in), layout="constrained")


def colour(index: int, count: int = 20) -> Any:
    """The ``index``-th series colour (``tab10`` up to 10 series, ``tab20`` beyond)."""
    from matplotlib import colormaps

    if count <= 10:
        return colormaps["tab10"](index % 10)
    return colormaps[CMAP](index % 20)


def save(figure: Any, path: Path | str, *, dpi: float = DPI) -> Path:
    """Write ``figure`` to ``path`` atomically, in the format its suffix names."""
    path = Path(path)
    fmt = path.suffix.lower().lstrip(".")
    metadata: dict[str, Any] = {}
    if fmt == "svg":
        metadata = {"Date": None}
    elif fmt == "pdf":
        metadata = {"CreationDate": None, "ModDate": None}
    return write_atomic(
        path,
        lambda stream: figure.savefig(stream, format=fmt, dpi=dpi, metadata=metadata),
        binary=True,
    )

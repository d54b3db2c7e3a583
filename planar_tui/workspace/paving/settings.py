"""The settings every workspace kind shares, declared once: the paving keys (precision,
refinement, search box, box budget, geometric reference, boxes output, singularity
precision) as field factories each kind's settings dataclass calls, and the box budget's
memory check (:func:`checked_box_budget`)."""

from __future__ import annotations

from typing import Any

from planar_tui.schema import (
    TableReader,
    boolean,
    integer,
    number,
    relative_path,
    setting,
    string,
)
from planar_tui.workspace.paving.circle import read_centre, read_elbow
from planar_tui.workspace.paving.orientation import MODES, read_orientation

#: Default cap on the boxes processed by one job (each costs ~1 µs and ≤ 112 bytes).
DEFAULT_BOX_BUDGET = 50_000_000


#: Most memory one processed box may hold (kept boxes, the bisection stack).
BYTES_PER_BOX = 112


def constructor_default(value, read, **key):
    """:func:`~planar_tui.schema.setting` with a callable preset default (``key["default"]``)
    whose dataclass field still defaults to ``value`` when the spec is built in code."""
    field = setting(read, **key)
    field.default = value
    return field


def checked_box_budget(budget: int, reader: TableReader) -> int:
    """The box budget within the memory limit (:mod:`planar_tui.limits`, at most
    :data:`BYTES_PER_BOX` per box): a larger budget set in the preset is refused, the
    default is lowered to fit."""
    from planar_tui.limits import memory_limit_bytes, memory_problem

    problem = memory_problem(budget * BYTES_PER_BOX)
    if problem is None:
        return budget
    if not reader.has("box_budget"):
        return memory_limit_bytes() // BYTES_PER_BOX
    raise reader.error(
        "box_budget",
        f"is {budget:,} boxes: {problem} at {BYTES_PER_BOX} bytes a box",
        f"at most {memory_limit_bytes() // BYTES_PER_BOX:,} boxes",
    )


def check_paving(values: dict[str, Any], reader: TableReader) -> dict[str, Any]:
    """The rules of the workspace kinds' paving keys: the refinement precision cannot
    exceed the precision; the box budget within the memory limit."""
    refine = values["refine_precision_cm"]
    if refine is not None and refine > values["precision_cm"]:
        raise reader.error(
            "refine_precision_cm", f"is {refine:g} > precision_cm", "<= precision_cm"
        )
    values["box_budget"] = checked_box_budget(values["box_budget"], reader)
    return values


def search_box_setting(read: Any) -> Any:
    """``search_box_cm`` of the workspace kinds, read (and checked) by ``read``."""
    return setting(
        read,
        default=None,
        default_doc="a square about the reach",
        type_doc="`[[x_min, x_max], [y_min, y_max]]`",
        doc="initial (x, y) box; must contain the legs' reach",
    )


def refine_setting(doc: str = "boundary-only refinement with the exact leg-wise test") -> Any:
    """``refine_precision_cm`` of the workspace kinds."""
    return setting(
        number(positive=True), default=None, type_doc="number > 0, ≤ `precision_cm`", doc=doc
    )


def budget_setting(doc: str) -> Any:
    """``box_budget`` of the workspace kinds (:func:`checked_box_budget` in ``check``)."""
    return setting(
        integer(minimum=1),
        default=DEFAULT_BOX_BUDGET,
        type_doc="integer ≥ 1, × 112 bytes ≤ the memory limit",
        doc=doc,
    )


def reference_setting() -> Any:
    """``geometric_reference`` of the workspace kinds."""
    return setting(
        boolean(),
        default=True,
        type_doc="boolean",
        doc="also compute the exact (shapely) area and its error bound",
    )


def boxes_setting() -> Any:
    """``boxes_output`` of the workspace kinds."""
    return setting(
        relative_path(),
        default=None,
        type_doc="relative path",
        doc="CSV of the kept boxes (`--boxes` on the command line)",
    )


def singularity_precision_setting() -> Any:
    """``singularity_precision_cm`` of the workspace kinds."""
    return setting(
        number(positive=True),
        default=None,
        type_doc="number > 0",
        default_doc="`precision_cm`",
        doc="bisection precision of the singularity paving",
    )


def read_search_box(reader: TableReader, name, default, robot, values):
    """``[[x_min, x_max], [y_min, y_max]]`` in cm, each non-empty (whether it holds the
    reach is checked by :meth:`PlanarSpec.check`, once every key is read)."""
    if not reader.has(name):
        return None
    rows = reader.number_rows(name, columns=2, row_doc="[min, max] in cm")
    if len(rows) != 2 or any(not lo < hi for lo, hi in rows):
        raise reader.error(
            name, f"is {[list(r) for r in rows]}", "[[x_min, x_max], [y_min, y_max]]"
        )
    return rows


# -- the shared keys, declared once (each kind's settings dataclass calls these) --------
def orientation_setting(
    doc: str = "platform orientation φ, or a range of them (needs `orientation_mode`)",
) -> Any:
    """``orientation_deg``: one orientation or a range ``[lo, hi]`` in degrees."""
    return setting(
        read_orientation,
        default=0.0,
        type_doc="number, or `[lo, hi]` (lo < hi, at most 360 apart)",
        doc=doc,
    )


def orientation_mode_setting() -> Any:
    """``orientation_mode``: over a range, ``maximal`` or ``total``."""
    return setting(
        string(choices=MODES),
        default=None,
        type_doc="`maximal` or `total`",
        default_doc="(none; required with a range)",
        doc="over a range: positions reachable with some φ (`maximal`) or with every φ (`total`)",
    )


def precision_setting(doc: str = "bisection precision ε") -> Any:
    """``precision_cm``: the paving's precision (required)."""
    return setting(number(positive=True), type_doc="number > 0", doc=doc)


def singularities_setting(
    doc: str = "also map the type II singularities and certify the singularity-free circle",
) -> Any:
    """``singularities``: also pave the singularities."""
    return setting(boolean(), default=False, type_doc="boolean", doc=doc)


def centre_setting() -> Any:
    """``circle_centre_cm``: the singularity-free circle's centre."""
    return setting(
        read_centre,
        default=None,
        type_doc="`[x, y]`",
        default_doc="(the workspace's centroid)",
        doc="centre of the singularity-free circle (must be reachable) and of the dexterous "
        "disc (with kappa_max)",
    )


def modes_setting(
    name: str | None = None,
    default_doc: str = "(the mode the limits allow at the centre)",
    doc: str = "working mode per leg: θ = α + β (`1`) or α − β (`-1`)",
) -> Any:
    """``elbow`` (or the kind's ``name`` for it): three working-mode signs, one per leg."""
    return setting(
        read_elbow,
        default=None,
        type_doc="3 signs, each `1` or `-1`",
        default_doc=default_doc,
        doc=doc,
        name=name,
    )

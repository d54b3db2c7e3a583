"""The three-leg layouts the parallel robots share: three ``[x, y]`` points per table
(base joints, platform points) and paper B's equilateral base and platform as defaults."""

from __future__ import annotations

import math

from planar_tui.schema import setting


def three_points(reader, name, default, context, values):
    """Three ``[x, y]`` points, one per leg (absent: the paper's layout)."""
    if not reader.has(name):
        return default
    rows = reader.number_rows(name, columns=2, row_doc="a point [x, y] in cm")
    if len(rows) != 3:
        raise reader.error(name, f"has {len(rows)} points", "3 points [x, y], one per leg")
    return rows


#: Paper B's base (an equilateral triangle of side 120 cm) and platform (base and height
#: 40 cm): the illustrative 3-RPR's geometry.
PAPER_B_BASE_CM = ((0.0, 0.0), (120.0, 0.0), (60.0, 60.0 * math.sqrt(3.0)))
PAPER_B_PLATFORM_CM = ((0.0, 0.0), (40.0, 0.0), (20.0, 40.0))


def paper_b_points(default, default_doc: str, doc: str):
    """A robot key of three ``[x, y]`` points (cm) defaulting to paper B's ``default``."""
    return setting(
        three_points,
        default=default,
        default_doc=default_doc,
        type_doc="3 points `[x, y]`",
        doc=doc,
    )


def platform_points():
    """The ``platform_points_cm`` key of the 3-RPR and the 3-PRR (paper B's platform)."""
    return paper_b_points(
        PAPER_B_PLATFORM_CM,
        "paper B's platform triangle (40 × 40)",
        "platform joints `q1, q2, q3` in the platform frame",
    )

"""Two runs of a kind side by side (plain data, no Textual here; the screen is
:class:`planar_tui.app.screens.history.CompareScreen`).

- Sensitivity: the rows matched by posture, speed, torque, parameter and method, each
  index of run A and run B (4 significant digits, :data:`INDEX_DIGITS`) and the
  difference B − A.
- Workspace: every summary figure (areas, boxes, precision) of A and B and B − A; with
  both runs' boxes, an overlay map (:func:`overlay_map`).
- Simulate: per column, the final values and the largest difference over the common
  times (B interpolated linearly onto A's times); the joint angles of both overlaid
  (:attr:`Comparison.series`).
- Sweep and optimisation: rows matched by point (evaluation) number, every numeric
  column of A, B and B − A.
- Any other table: rows matched by their text columns (else by position), every numeric
  column of A, B and B − A.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

from planar_tui.app.runs import Run
from planar_tui.csvio import CsvTable
from planar_tui.figures.table import column, text_column

#: Sensitivity rows are matched by these columns and compared on these.
SENSITIVITY_KEYS = ("posture", "speed_rad_s", "torque", "parameter", "method")
SENSITIVITY_VALUES = ("S1", "ST")

#: The column a sweep's (an optimisation's) rows are matched by.
STUDY_KEYS = {"sweep": "point", "optimise": "evaluation"}

#: Significant digits of a sensitivity index (A and B; B − A has 3): a Monte Carlo index
#: has fewer meaningful ones, and the eight columns then fit 80 columns.
INDEX_DIGITS = 4

#: A boxes table's status (the CSV's words, or their codes) as the code
#: :func:`overlay_map` draws by.
STATUS_CODES = {"inside": 2.0, "boundary": 1.0, "2": 2.0, "1": 1.0}

#: Most rows a comparison lists (the tables themselves are exported whole).
MAX_ROWS = 2000


@dataclass(frozen=True)
class Comparison:
    """What the compare screen shows: a table (``header``, ``rows`` of text cells), notes,
    an overlay map (text, for workspaces) and curves to overlay (``(name, t, y)``)."""

    title: str
    header: tuple[str, ...]
    rows: list[tuple[str, ...]]
    notes: tuple[str, ...] = ()
    overlay: str = ""
    series: list[tuple[str, list[float], list[float]]] = field(default_factory=list)


def number(value: Any) -> float | None:
    """A numeric cell as a float, else ``None`` (text, empty, booleans)."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        return None
    return float(value)


def shown(value: float | None, digits: int = 6) -> str:
    """A number as the comparison shows it (``digits`` significant digits), ``-`` for
    none."""
    return "-" if value is None or math.isnan(value) else f"{value:.{digits}g}"


def difference(a: float | None, b: float | None) -> str:
    """``B − A`` with its sign, ``-`` when either is missing."""
    return "-" if a is None or b is None else f"{b - a:+.3g}"


def _columns(table: CsvTable) -> dict[str, int]:
    return {name: k for k, name in enumerate(table.header)}


def _text_columns(table: CsvTable) -> list[str]:
    return [
        name
        for k, name in enumerate(table.header)
        if any(isinstance(row[k], str) for row in table.rows)
    ]


def matched_rows(
    a: CsvTable, b: CsvTable, keys: Sequence[str], values: Sequence[str], digits: int = 6
) -> tuple[tuple[str, ...], list[tuple[str, ...]]]:
    """Rows of A and B matched by the ``keys`` columns (by position when there are none):
    the keys, then for each of ``values`` A, B (``digits`` significant digits) and
    B − A; rows of one run alone show ``-`` for the other."""
    ca, cb = _columns(a), _columns(b)

    def key(row: Sequence[Any], columns: dict[str, int], position: int) -> tuple[Any, ...]:
        return tuple(row[columns[k]] for k in keys) if keys else (position + 1,)

    rows_b = {key(row, cb, k): row for k, row in enumerate(b.rows)}
    rows_a = {key(row, ca, k): row for k, row in enumerate(a.rows)}
    order = list(rows_a) + [k for k in rows_b if k not in rows_a]
    names = (f"{v} {side}" for v in values for side in ("A", "B", "B−A"))
    header = (*(keys or ("row",)), *names)
    out = []
    for k in order[:MAX_ROWS]:
        ra, rb = rows_a.get(k), rows_b.get(k)
        cells = [shown(number(part)) if number(part) is not None else str(part) for part in k]
        for v in values:
            x = number(ra[ca[v]]) if ra is not None and v in ca else None
            y = number(rb[cb[v]]) if rb is not None and v in cb else None
            cells += [shown(x, digits), shown(y, digits), difference(x, y)]
        out.append(tuple(cells))
    return header, out


def varying(keys: Sequence[str], a: CsvTable, b: CsvTable) -> tuple[list[str], str]:
    """The ``keys`` whose value differs between rows of A and B (the table's columns), and
    the others as text (``posture singular, method sobol``) for a note; one key is kept
    when none varies."""
    ca, cb = _columns(a), _columns(b)
    kept, same = [], []
    for key in keys:
        values = {row[ca[key]] for row in a.rows} | {row[cb[key]] for row in b.rows}
        if len(values) > 1:
            kept.append(key)
        elif values:
            value = next(iter(values))
            same.append(f"{key} {shown(number(value)) if number(value) is not None else value}")
    if not kept and keys:
        kept, same = [keys[-1]], same[:-1]
    return kept, ", ".join(same)


def figures_side_by_side(a: CsvTable, b: CsvTable) -> tuple[tuple[str, ...], list[tuple[str, ...]]]:
    """One-row tables (a workspace summary) turned: one row per column, A, B, B − A."""
    ra, rb = a.rows[0], b.rows[0]
    cb = _columns(b)
    rows = []
    for k, name in enumerate(a.header):
        x = ra[k]
        y = rb[cb[name]] if name in cb else None
        if number(x) is None and number(y) is None:
            rows.append(
                (name, str(x), "-" if y is None else str(y), "same" if x == y else "differs")
            )
        else:
            rows.append(
                (name, shown(number(x)), shown(number(y)), difference(number(x), number(y)))
            )
    return ("quantity", "A", "B", "B−A"), rows


def simulation_figures(
    a: CsvTable, b: CsvTable
) -> tuple[tuple[str, ...], list[tuple[str, ...]], list]:
    """Per column of both simulations: final A, final B, the largest |B − A| over A's
    times (B interpolated linearly; only within B's time span), and the joint angles of
    both as curves (degrees)."""
    import numpy as np

    ta, tb = column(a, "t_s"), column(b, "t_s")
    common = (ta >= tb[0]) & (ta <= tb[-1]) if len(tb) else np.zeros_like(ta, dtype=bool)
    rows, series = [], []
    for name in a.header[1:]:
        if name not in b.header:
            continue
        ya, yb = column(a, name), column(b, name)
        gap = (
            float(np.max(np.abs(np.interp(ta[common], tb, yb) - ya[common])))
            if common.any()
            else None
        )
        rows.append((name, shown(float(ya[-1])), shown(float(yb[-1])), shown(gap)))
        if name.startswith("theta") and name.endswith("_rad"):
            joint = name.removeprefix("theta").removesuffix("_rad")
            series.append((f"A θ{joint}", ta.tolist(), np.degrees(ya).tolist()))
            series.append((f"B θ{joint}", tb.tolist(), np.degrees(yb).tolist()))
    return ("column", "final A", "final B", "max |B−A|"), rows, series


#: Plot glyphs of run A's curves and run B's, one per curve in order: distinct without
#: colour (``NO_COLOR``), A's digits and B's letters (plotext draws the character).
SERIES_GLYPHS = {"A": "123456789", "B": "abcdefghi"}


def series_glyphs(names: Sequence[str]) -> list[str]:
    """The glyph of each curve (named ``A …`` or ``B …``): the next of its run's
    :data:`SERIES_GLYPHS`."""
    used = {side: 0 for side in SERIES_GLYPHS}
    glyphs = []
    for name in names:
        side = name[:1] if name[:1] in SERIES_GLYPHS else "A"
        pool = SERIES_GLYPHS[side]
        glyphs.append(pool[used[side] % len(pool)])
        used[side] += 1
    return glyphs


def series_legend(names: Sequence[str]) -> str:
    """One line naming each curve's glyph: ``1 A θ1  a B θ1  …`` (wrapped by the screen)."""
    return "   ".join(f"{g} {name}" for g, name in zip(series_glyphs(names), names, strict=True))


def overlay_map(a: CsvTable, b: CsvTable, width: int = 60, height: int = 20) -> str:
    """The inside boxes of two workspaces' boxes tables on one text grid over both:
    ``#`` inside both, ``A`` or ``B`` inside one only, ``.`` boundary of either, blank
    outside both (a cell counts by its centre); ``y`` up."""
    import numpy as np

    def arrays(table: CsvTable) -> tuple[Any, ...]:
        """The box bounds, and the status as its code (the CSV's ``"inside"`` 2,
        ``"boundary"`` 1; a table of codes is read as it is)."""
        status = [STATUS_CODES.get(s, math.nan) for s in text_column(table, "status")]
        return (
            *(column(table, n) for n in ("x_lo_cm", "x_hi_cm", "y_lo_cm", "y_hi_cm")),
            np.array(status, dtype=float),
        )

    boxes = [arrays(a), arrays(b)]
    if not any(len(x[0]) for x in boxes):
        return "(no boxes in either run)"
    x_lo = min(float(np.min(x[0])) for x in boxes if len(x[0]))
    x_hi = max(float(np.max(x[1])) for x in boxes if len(x[1]))
    y_lo = min(float(np.min(x[2])) for x in boxes if len(x[2]))
    y_hi = max(float(np.max(x[3])) for x in boxes if len(x[3]))
    cx = x_lo + (np.arange(width) + 0.5) * (x_hi - x_lo) / width
    cy = y_lo + (np.arange(height) + 0.5) * (y_hi - y_lo) / height

    def cover(x0: Any, x1: Any, y0: Any, y1: Any) -> Any:
        """Boolean grid (height × width): cells whose centre lies in a box (2-D
        difference array: +1 at each box's first cell, −1 past its last)."""
        i0, i1 = np.searchsorted(cx, x0), np.searchsorted(cx, x1)
        j0, j1 = np.searchsorted(cy, y0), np.searchsorted(cy, y1)
        grid = np.zeros((height + 1, width + 1))
        np.add.at(grid, (j0, i0), 1)
        np.add.at(grid, (j0, i1), -1)
        np.add.at(grid, (j1, i0), -1)
        np.add.at(grid, (j1, i1), 1)
        return grid.cumsum(0).cumsum(1)[:height, :width] > 0

    inside, boundary = [], []
    for x0, x1, y0, y1, status in boxes:
        inside.append(cover(x0[status == 2], x1[status == 2], y0[status == 2], y1[status == 2]))
        boundary.append(cover(x0[status == 1], x1[status == 1], y0[status == 1], y1[status == 1]))
    glyphs = np.full((height, width), " ")
    glyphs[boundary[0] | boundary[1]] = "."
    glyphs[inside[0] & ~inside[1]] = "A"
    glyphs[inside[1] & ~inside[0]] = "B"
    glyphs[inside[0] & inside[1]] = "#"
    lines = ["".join(row).rstrip() for row in glyphs[::-1]]
    span = f"x {x_lo:.4g}…{x_hi:.4g} cm, y {y_lo:.4g}…{y_hi:.4g} cm"
    return "\n".join([*lines, f"# both inside   A only A   B only B   . boundary   ({span})"])


def compare_runs(a: Run, b: Run) -> Comparison:
    """Runs ``a`` and ``b`` (of one kind) side by side, as the module's docstring says."""
    title = f"#{a.number} (A) vs #{b.number} (B): {a.kind}"
    notes = [f"A: {a.label} ({a.source})", f"B: {b.label} ({b.source})"]
    notes += [f"{side}: {run.note}" for side, run in (("A", a), ("B", b)) if run.note]
    notes += _settings_differences(a, b)
    if a.kind != b.kind:
        raise ValueError(f"runs of different kinds ({a.kind}, {b.kind}) are not compared")
    series: list = []
    overlay = ""
    if a.kind == "sensitivity" and set(SENSITIVITY_VALUES) <= set(a.table.header):
        keys = [k for k in SENSITIVITY_KEYS if k in a.table.header and k in b.table.header]
        keys, same = varying(keys, a.table, b.table)
        notes += [f"every row: {same}"] if same else []
        header, rows = matched_rows(a.table, b.table, keys, SENSITIVITY_VALUES, INDEX_DIGITS)
    elif len(a.table.rows) == 1 and len(b.table.rows) == 1:
        header, rows = figures_side_by_side(a.table, b.table)
    elif a.kind == "simulate" and "t_s" in a.table.header and "t_s" in b.table.header:
        header, rows, series = simulation_figures(a.table, b.table)
    elif STUDY_KEYS.get(a.kind) in a.table.header and STUDY_KEYS[a.kind] in b.table.header:
        key, text = STUDY_KEYS[a.kind], set(_text_columns(a.table))
        values = [v for v in a.table.header if v not in text | {key} and v in b.table.header]
        header, rows = matched_rows(a.table, b.table, [key], values)
    else:
        keys = [k for k in _text_columns(a.table) if k in b.table.header]
        values = [v for v in a.table.header if v not in keys and v in b.table.header]
        header, rows = matched_rows(a.table, b.table, keys, values)
    boxes = (a.extra_tables.get("boxes"), b.extra_tables.get("boxes"))
    if boxes[0] is not None and boxes[1] is not None:
        overlay = overlay_map(boxes[0], boxes[1])
    elif a.kind == "workspace":
        notes.append("overlay map: needs both runs' boxes (runs of this session)")
    return Comparison(title, header, rows, tuple(notes), overlay, series)


def _settings_differences(a: Run, b: Run) -> list[str]:
    """One line per setting (and the robot) that differs between the runs."""
    if a.provenance is None or b.provenance is None:
        return []
    lines = []
    for where, sa, sb in (
        ("", a.settings, b.settings),
        ("robot.", dict(a.provenance.robot), dict(b.provenance.robot)),
    ):
        for key in dict.fromkeys([*sa, *sb]):
            if sa.get(key) != sb.get(key):
                lines.append(f"setting {where}{key}: A {sa.get(key, '-')}, B {sb.get(key, '-')}")
    if a.provenance.preset_sha256 != b.provenance.preset_sha256:
        lines.append("the presets differ (SHA-256)")
    return lines or ["same settings"]

"""Which figure a result or a CSV gets, and writing it (atomically, format by suffix).

A table's kind is recognised from its header (:data:`RECOGNISERS`, first match wins; extra
columns are fine: ``planar-tui plot``); a finished job is drawn by the function its job kind
names (:attr:`planar_tui.jobkind.JobKind.figure`, ``module:function`` taking the job and
its typed result, which knows the robot; :func:`from_main_table` draws its main table,
recognised like a CSV: the motion-uncertainty kind). A kind that names none draws no
figure (:func:`figure_problem`).
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

from planar_tui.csvio import CsvTable
from planar_tui.figures.canvas import DPI, save
from planar_tui.figures.table import read_csv
from planar_tui.jobkind import resolve
from planar_tui.registry import JOB_KINDS

#: (kind, module, recogniser, drawing function), tried in order: a sweep's table also holds
#: its kind's summary columns, so it comes first.
RECOGNISERS: tuple[tuple[str, str, str, str], ...] = (
    ("sweep", "sweep", "matches", "draw"),
    ("sensitivity", "sensitivity", "matches", "draw"),
    ("motion uncertainty indices", "sensitivity", "matches_motion", "draw"),
    ("workspace boxes", "workspace", "matches_boxes", "from_boxes_table"),
    ("workspace summary", "workspace", "matches_summary", "from_summary_table"),
    ("motion uncertainty band", "uncertainty", "matches", "draw"),
    ("simulate", "simulate", "matches", "draw"),
    ("torques", "torques", "matches", "draw"),
    ("path", "path", "matches", "draw"),
)
#: Kinds whose header-only CSV the project writes in normal use, drawn rather than refused:
#: the boxes of a geometric-form workspace job (that form keeps no boxes) or of an empty
#: workspace.
DRAWN_EMPTY = frozenset({"workspace boxes"})


#: Kinds whose figure is drawn in seconds whatever its rows (past
#: :data:`~planar_tui.figures.workspace.MAX_DRAWN_BOXES`, the boxes are one image).
BOUNDED_FIGURES = frozenset({"workspace boxes"})


class UnknownTable(ValueError):
    """A table whose header is no result CSV this project writes."""


def _module(name: str) -> Any:
    return resolve(f"planar_tui.figures.{name}")


def recognise(header: tuple[str, ...] | list[str]) -> str | None:
    """The kind of result a CSV header belongs to (``"simulate"``, ``"sweep"`` ...), or
    ``None``. Imports no matplotlib."""
    header = tuple(header)
    for kind, module, test, _ in RECOGNISERS:
        if getattr(_module(module), test)(header):
            return kind
    return None


def _drawer(header: tuple[str, ...]) -> tuple[str, Callable[[CsvTable, str], Any]]:
    for kind, module, test, draw in RECOGNISERS:
        if getattr(_module(module), test)(header):
            return kind, getattr(_module(module), draw)
    kinds = ", ".join(dict.fromkeys(kind for kind, *_ in RECOGNISERS))
    shown = ",".join(header[:4]) + (",..." if len(header) > 4 else "")
    raise UnknownTable(
        f"is {shown!r}, the header of no result CSV of planar-tui",
        f"the header of a {kinds} CSV",
    )


def figure_for_table(table: CsvTable, title: str = "") -> Any:
    """The figure of a result table (:class:`UnknownTable` if its header is unknown,
    ``ValueError`` if it has no data rows, unless its kind is in :data:`DRAWN_EMPTY`, or
    its drawer cannot show it)."""
    kind, drawer = _drawer(tuple(table.header))
    if len(table.rows) == 0 and kind not in DRAWN_EMPTY:
        raise ValueError("the table has a header but no data rows (expected at least one row)")
    return drawer(table, title)


def figure_problem(kind: str) -> str | None:
    """Why a job of ``kind`` cannot have a figure (its kind names no figure function), or
    ``None``. Imports no matplotlib."""
    declared = JOB_KINDS.get(kind)
    if declared is not None and declared.figure is not None:
        return None
    return f"the {kind} job kind draws no figure"


def figure_for_result(job: Any, result: Any) -> Any:
    """The figure of a finished job, drawn by the function its job kind names
    (:attr:`~planar_tui.jobkind.JobKind.figure`); ``ValueError`` for a kind without one."""
    problem = figure_problem(job.kind)
    if problem is not None:
        raise ValueError(problem)
    return resolve(JOB_KINDS[job.kind].figure)(job, result)


def from_main_table(job: Any, result: Any) -> Any:
    """A finished job's figure drawn from its main table (recognised like a CSV, titled
    with the job): for a kind whose CSV holds everything its figure shows."""
    return figure_for_table(result.table, job.label)


def _saved(figure: Any, path: Path | str, dpi: float | None) -> Path:
    try:
        return save(figure, path, dpi=dpi or DPI)
    finally:
        figure.clear()


def save_result_figure(
    job: Any, result: Any, path: Path | str, *, dpi: float | None = None
) -> Path:
    """Draw a finished job's figure and write it to ``path`` (``.svg``, ``.png``, ``.pdf``)."""
    return _saved(figure_for_result(job, result), path, dpi)


def save_table_figure(
    table: CsvTable, path: Path | str, title: str = "", *, dpi: float | None = None
) -> Path:
    """Draw a result table's figure and write it to ``path``."""
    return _saved(figure_for_table(table, title), path, dpi)


def is_same_file(first: Path | str, second: Path | str) -> bool:
    """Whether two paths name one file (an existing one by identity, links included;
    otherwise by absolute, normalised path)."""
    import os

    try:
        return os.path.samefile(first, second)
    except OSError:
        return os.path.abspath(first) == os.path.abspath(second)


def read_table(path: Path | str) -> CsvTable:
    """A result CSV read back (see :func:`planar_tui.figures.table.read_csv`)."""
    return read_csv(path)


def save_csv_figure(csv_path: Path | str, path: Path | str, *, dpi: float | None = None) -> Path:
    """Draw the figure of a result CSV file (titled with its name) into ``path``."""
    table = read_table(csv_path)
    return save_table_figure(table, path, Path(csv_path).name, dpi=dpi)

"""Our sensitivity percentages next to every printed cell of paper A's Tables 4-5.

:func:`compare` takes the analyses of the bundled ``paper-a-table4``/``paper-a-table5``
jobs and the paper's cells (``tests/data/reference/paper_sensitivity_tables.csv``: table,
robot, torque, configuration, parameter, sobol_pct, efast_pct) and returns one row per
printed (table, robot, posture, torque, method): our percentages, the paper's, and the
largest absolute difference in percentage points. :func:`report` formats it as text.
"""

from __future__ import annotations

import csv
from dataclasses import dataclass
from pathlib import Path


@dataclass(frozen=True)
class ComparisonRow:
    """One printed row of Table 4 or 5 for one method, with ours beside it."""

    table: str
    robot: str
    posture: str
    torque: int
    method: str
    names: tuple[str, ...]
    ours: tuple[float, ...]
    paper: tuple[float, ...]

    @property
    def max_difference_pp(self) -> float:
        return max(abs(a - b) for a, b in zip(self.ours, self.paper, strict=True))


def read_paper_cells(path: Path | str) -> dict[tuple, tuple[float, float]]:
    """(table, robot, torque, posture, parameter) -> (Sobol' %, eFAST %)."""
    with Path(path).open(encoding="utf-8") as stream:
        return {
            (r["table"], r["robot"], int(r["torque"]), r["configuration"], r["parameter"]): (
                float(r["sobol_pct"]),
                float(r["efast_pct"]),
            )
            for r in csv.DictReader(stream)
        }


def compare(results, paper_cells, paper_posture=None) -> list[ComparisonRow]:
    """``results``: (table, robot, analyses) triples, robot as in the paper ("2R" ...).

    ``paper_posture(table, robot, torque, posture)`` maps our posture to the paper row
    compared with it (default: the same name); used to test the Table 4 3R τ3 swap.
    """
    rows = []
    for table, robot, analyses in results:
        for analysis in analyses:
            column = 0 if analysis.method == "sobol" else 1
            for torque in range(1, analysis.percent.shape[0] + 1):
                posture = analysis.posture
                if paper_posture is not None:
                    posture = paper_posture(table, robot, torque, posture)
                keys = [(table, robot, torque, posture, name) for name in analysis.names]
                if not all(key in paper_cells for key in keys):
                    continue
                rows.append(
                    ComparisonRow(
                        table,
                        robot,
                        analysis.posture,
                        torque,
                        analysis.method,
                        analysis.names,
                        tuple(float(v) for v in analysis.percent[torque - 1]),
                        tuple(paper_cells[key][column] for key in keys),
                    )
                )
    return rows


def report(rows: list[ComparisonRow]) -> str:
    """Text table: every cell as ``ours/paper`` and the largest difference per row."""
    lines = []
    for row in rows:
        cells = "  ".join(
            f"{name} {a:6.2f}/{b:6.2f}"
            for name, a, b in zip(row.names, row.ours, row.paper, strict=True)
        )
        lines.append(
            f"T{row.table} {row.robot} {row.posture:<9} τ{row.torque} {row.method:<5} "
            f"max|Δ| {row.max_difference_pp:6.2f} pp | {cells}"
        )
    return "\n".join(lines)

"""The boxes CSV of a workspace job with a certifying stage (dexterity, interference,
accuracy): the table's rows followed by the stage's labelled boxes, made when read (a run
that writes no boxes CSV never builds its Python rows)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any


class AppendedRows(Sequence):
    """``rows`` (a sequence with ``non_finite_column``), each extended by
    :meth:`table_row`, then one row a box of the stage's ``outcome`` (:meth:`stage_row`)."""

    def __init__(self, rows: Any, outcome: Any):
        self._rows = rows
        self._outcome = outcome

    def table_row(self, row: Any) -> list:
        """A row of the table, with the stage's columns (none by default)."""
        return list(row)

    def stage_row(self, i: int) -> list:
        """The row of the stage's box ``i``."""
        raise NotImplementedError

    def __len__(self) -> int:
        return len(self._rows) + len(self._outcome.boxes)

    def _row(self, index: int) -> list:
        n = len(self._rows)
        return self.table_row(self._rows[index]) if index < n else self.stage_row(index - n)

    def __getitem__(self, index):
        if isinstance(index, slice):
            return [self._row(i) for i in range(*index.indices(len(self)))]
        return self._row(index % len(self) if index < 0 else index)

    def non_finite_column(self) -> int | None:
        """The table's test (the stage's cells are finite or empty)."""
        return self._rows.non_finite_column()

"""Figures of results for reports: every job kind's result as SVG, PNG or PDF.

One module per figure kind (:mod:`.simulate`, :mod:`.torques`, :mod:`.sensitivity`,
:mod:`.workspace`, :mod:`.sweep`, :mod:`.uncertainty`); each draws from a result table
(:class:`~planar_tui.csvio.CsvTable`, the CSV the project writes, so a result computed on a
cluster is drawn later anywhere) and, where the typed result knows more than its CSV (the
robot, to draw the arm or the 3-RRR and the exact workspace boundary), from the
:class:`~planar_tui.jobkind.JobResult` too. :mod:`.dispatch` picks the module
(:func:`save_result_figure`, :func:`save_table_figure`, :func:`recognise`).

Matplotlib is imported only when a figure is drawn (the Agg backend, no ``pyplot``
state), so importing this package costs nothing; files are written atomically (a
temporary file renamed, as the CSVs are).
"""

from planar_tui.figures.dispatch import (
    UnknownTable,
    figure_for_result,
    figure_for_table,
    read_table,
    recognise,
    save_csv_figure,
    save_result_figure,
    save_table_figure,
)

__all__ = [
    "UnknownTable",
    "figure_for_result",
    "figure_for_table",
    "read_table",
    "recognise",
    "save_csv_figure",
    "save_result_figure",
    "save_table_figure",
]

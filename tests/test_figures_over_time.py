"""The figure of indices against time (:func:`planar_tui.figures.sensitivity.draw_over_time`)."""

from __future__ import annotations

import numpy as np

from planar_tui import figures
from planar_tui.csvio import CsvTable

HEADER = ("output", "t_s", "parameter", "method", "S1", "S1_conf", "ST", "ST_conf", "percent")


def table_of(times):
    rows = []
    for output in ("theta1_rad", "tip_x_m"):
        for t in times:
            share_l = 100.0 * t / times[-1]  # l1 takes over as time goes on
            for parameter, percent in (("l1", share_l), ("m1", 100.0 - share_l)):
                rows.append((output, t, parameter, "pce", 0.0, 0.0, percent / 100, 0.0, percent))
    return CsvTable(HEADER, rows)


def test_many_times_are_stacked_lines_summing_to_the_whole():
    times = np.linspace(0.0, 1.0, 21).tolist()
    fig = figures.figure_for_table(table_of(times), "motion")
    panels = [ax for ax in fig.axes if ax.get_gid() == "stacked"]
    assert [ax.get_title() for ax in panels] == ["theta1_rad (PCE)", "tip_x_m (PCE)"]
    bands = panels[0].collections
    assert len(bands) == 2  # l1 and m1
    top = bands[-1].get_paths()[0].vertices  # the upper band's outline reaches 100 %
    assert np.isclose(top[:, 1].max(), 100.0) and np.isclose(top[:, 0].max(), 1.0)


def test_a_few_times_stay_bars():
    fig = figures.figure_for_table(table_of([0.5, 1.0]), "motion")
    assert [ax.get_gid() for ax in fig.axes].count("bars") == 2

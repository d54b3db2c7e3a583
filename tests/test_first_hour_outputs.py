"""The CSVs and figures a new user reads: the 3-RPR and 3-PRR summaries carry
the 3-RRR's orientation columns; the figures plot what varies, keep the exact-area marker
in sight and name the simulate job's energy balance for what it is."""

from __future__ import annotations

import dataclasses

import pytest

from planar_tui.presets import load_preset
from planar_tui.progress import Progress
from planar_tui.registry import JOB_KINDS
from planar_tui.workspace.paving.levels import SUMMARY_HEADER
from tests.test_workspace_estimate import preset

#: The 3-RRR summary's orientation columns, as docs/workspace.md lists them.
ORIENTATION = ("orientation_mode", "orientation_lo_deg", "orientation_hi_deg")


@pytest.mark.parametrize(
    ("kind", "orientation", "cells"),
    [
        ("workspace3rpr", None, ["", "30.0", "30.0"]),
        ("workspace3prr", None, None),
        ("workspace3rpr", ((25.0, 30.0), "maximal"), ["maximal", "25.0", "30.0"]),
    ],
)
def test_the_3rpr_and_3prr_summaries_have_the_3rrrs_orientation_columns(
    tmp_path, kind, orientation, cells
):
    (job,) = load_preset(preset(tmp_path, kind, "4")).jobs
    if orientation is not None:
        (lo_hi, mode) = orientation
        spec = dataclasses.replace(job.spec, orientation_deg=lo_hi, orientation_mode=mode)
        job = dataclasses.replace(job, spec=spec)
    declared = JOB_KINDS[kind]
    result = declared.run(declared.prepare_job(job), Progress())
    header = result.table.header
    at = len(SUMMARY_HEADER) - 1  # where the 3-RRR has them: after its summary's columns
    assert header[:at] == SUMMARY_HEADER[:-1]
    assert header[at : at + 3] == ORIENTATION and header[-1] == "seconds"
    (row,) = result.table.rows
    shown = [str(cell) for cell in row[at : at + 3]]
    if cells is not None:
        assert shown == cells
    else:
        assert shown[0] == "" and shown[1] == shown[2] == str(float(job.spec.orientation_deg))
    assert declared.figure_names(job) == tuple(declared.point_figures(job, result))


def design_sweep_table():
    """A zip sweep as sweep-3rrr-design's: proximal 20 → 40 cm with distal 40 → 20 cm, an
    area that peaks at equal legs, two columns that stay 0 and one echoed setting."""
    from planar_tui.csvio import CsvTable

    header = (
        "point",
        "robot3rrr.proximal_cm",
        "robot3rrr.distal_cm",
        "area_inside_cm2",
        "singular_boxes",
        "voids",
        "precision_cm",
        "status",
        "message",
        "seconds",
    )
    rows = [
        [k + 1, 20.0 + 5 * k, 40.0 - 5 * k, 100.0 - (5 * k - 10) ** 2, 0, 0.0, 0.5, "ok", "", 1.0]
        for k in range(5)
    ]
    return CsvTable(header, rows)


def test_a_zip_sweeps_figure_plots_each_varying_output_against_the_swept_key():
    from planar_tui.figures import sweep

    fig = sweep.draw(design_sweep_table(), "sweep-3rrr-design:sweep[1]")
    shown = [ax for ax in fig.axes if ax.get_visible()]
    assert len(shown) == 1  # the area; the constant columns and the echoed ε are no panels
    (ax,) = shown
    assert ax.get_ylabel() == "area_inside_cm2"
    assert ax.get_xlabel() == ("robot3rrr.proximal_cm (with robot3rrr.distal_cm 40 → 20)")
    (line,) = [line for line in ax.lines if line.get_gid() == "sweep"]
    assert line.get_xdata().tolist() == [20.0, 25.0, 30.0, 35.0, 40.0]
    assert line.get_ydata().tolist() == [0.0, 75.0, 100.0, 75.0, 0.0]
    assert not [c for c in ax.collections if c.get_gid() == "heat"]  # no scatter of a diagonal


def test_a_grid_sweep_keeps_its_heat_map():
    from planar_tui.csvio import CsvTable
    from planar_tui.figures import sweep

    header = (
        "point",
        "robot3rrr.proximal_cm",
        "robot3rrr.distal_cm",
        "area_inside_cm2",
        "status",
        "message",
        "seconds",
    )
    cells = [(p, d) for p in (20.0, 30.0) for d in (20.0, 30.0)]
    rows = [[k + 1, p, d, p * d, "ok", "", 1.0] for k, (p, d) in enumerate(cells)]
    fig = sweep.draw(CsvTable(header, rows), "grid")
    assert "heat" in [c.get_gid() for ax in fig.axes for c in ax.collections]


def test_the_workspace_summary_figures_legend_leaves_the_exact_area_marker_in_sight():
    from planar_tui.csvio import CsvTable
    from planar_tui.figures import workspace

    header = ("form", "precision_cm", "area_inside_cm2", "area_kept_cm2", "area_geometric_cm2")
    table = CsvTable(header, [["arc-distance", 0.05, 99.0, 101.0, 100.4]])
    fig = workspace.from_summary_table(table, "workspace-3rpr:workspace3rpr[1]")
    fig.canvas.draw()
    (ax,) = fig.axes
    (marker,) = [line for line in ax.lines if line.get_label() == "exact (geometric)"]
    legend = ax.get_legend().get_window_extent()
    assert not legend.overlaps(marker.get_window_extent())
    for patch in ax.patches:  # nor over the bars
        assert not legend.overlaps(patch.get_window_extent())

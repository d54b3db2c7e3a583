"""The CSVs and figures a new user reads (issue 34): the 3-RPR and 3-PRR summaries carry
the 3-RRR's orientation columns; the figures plot what varies, keep the exact-area marker
in sight and name the simulate job's energy balance for what it is."""

from __future__ import annotations

import dataclasses

import pytest

from planar_tui.presets import load_preset
from planar_tui.progress import Progress
from planar_tui.registry import JOB_KINDS
from planar_tui.workspace.compute import SUMMARY_HEADER
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

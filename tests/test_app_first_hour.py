"""The workbench's rough edges a new user met in the first hour (issue 34): the
comparison of two workspace runs' maps, ..."""

from __future__ import annotations

import shutil
from pathlib import Path

from planar_tui.app.compare import compare_runs
from planar_tui.app.runs import RunHistory
from planar_tui.app.workbench import Workbench
from planar_tui.batch import run_job

DATA = Path(__file__).parent / "data" / "app"


def test_two_real_workspace_runs_overlay_their_maps(tmp_path):
    # tiny.toml's coarse 3-RRR, then the same with the first leg's limits narrowed: run B
    # holds less, so the overlay shows cells inside both ('#') and inside A only ('A'),
    # none inside B only (B's workspace is a subset of A's).
    shutil.copy(DATA / "tiny.toml", tmp_path / "tiny.toml")
    bench = Workbench.open(tmp_path / "tiny.toml")
    history = RunHistory()
    job = bench.job("workspace")
    history.add_result(job, run_job(job))
    bench.document["workspace"]["joint_limits_deg"] = [[30, 60], [110, 160], [245, 295]]
    job = bench.job("workspace")
    history.add_result(job, run_job(job))
    a, b = history.runs
    assert {row[-1] for row in a.extra_tables["boxes"].rows} == {"inside", "boundary"}
    grid = compare_runs(a, b).overlay.splitlines()[:-1]
    glyphs = set("".join(grid))
    assert "#" in glyphs and "A" in glyphs and "B" not in glyphs, "\n".join(grid)

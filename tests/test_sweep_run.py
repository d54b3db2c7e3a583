"""Sweeps run in-process: every point's figures equal a separate run of the same job (its
preset written out by hand), failing points are rows, and an interrupted sweep resumes
from its checkpoint without recomputing its finished points."""

from __future__ import annotations

import csv
import json

import numpy as np
import pytest

from planar_tui import batch
from planar_tui.errors import Cancelled
from planar_tui.presets import load_preset
from planar_tui.progress import Progress
from planar_tui.sweep.points import design
from planar_tui.sweep.service import run_sweep
from planar_tui.sweep.spec import parse_sweeps
from tests.sweep_presets import TORQUES, TORQUES_BASE, WORKSPACE, WORKSPACE_BASE, write


def read_rows(path):
    with open(path, newline="") as stream:
        return list(csv.DictReader(stream))


def separate(tmp_path, template, **values):
    """One job run on its own from a preset written by text substitution."""
    path = write(tmp_path, "separate.toml", template, **values)
    (job,) = load_preset(path).jobs
    return batch.run_job(job)


def the_sweep(tmp_path, template, base, body):
    path = write(tmp_path, "p.toml", template, "[[sweep]]\n" + body, **base)
    (sweep,) = parse_sweeps(load_preset(path))
    return sweep


def test_grid_workspace_sweep_equals_separate_runs(tmp_path):
    sweep = the_sweep(
        tmp_path,
        WORKSPACE,
        WORKSPACE_BASE,
        """job = "workspace"
values.orientation_deg = [-10, 10]
values."robot3rrr.distal_cm" = { from = 28.0, to = 32.0, count = 2 }
output = "grid.csv"
point_outputs = "grid-points"
""",
    )
    out = tmp_path / "out"
    run = run_sweep(sweep, out_dir=out)
    rows = read_rows(out / "grid.csv")
    assert [r["point"] for r in rows] == ["1", "2", "3", "4"]
    assert list(rows[0])[:3] == ["point", "orientation_deg", "robot3rrr.distal_cm"]
    assert list(rows[0])[-3:] == ["status", "message", "seconds"]
    for row, (orientation, distal) in zip(
        rows, [(-10, 28.0), (-10, 32.0), (10, 28.0), (10, 32.0)], strict=True
    ):
        assert (row["orientation_deg"], row["robot3rrr.distal_cm"]) == (
            str(orientation),
            str(distal),
        )
        values = {**WORKSPACE_BASE, "orientation_deg": orientation, "distal_cm": distal}
        alone = separate(tmp_path, WORKSPACE, **values).table
        assert row["status"] == "ok" and row["message"] == ""
        for name, cell in zip(alone.header, alone.rows[0], strict=True):
            if name != "seconds":
                assert row[name] == str(cell), name
        # the point's own CSV, as a run of the job writes it
        point_csv = out / "grid-points" / f"point-{row['point']}.csv"
        lines = point_csv.read_text().splitlines()
        assert lines[0] == ",".join(alone.header)
        assert lines[1].split(",")[:-1] == [str(c) for c in alone.rows[0]][:-1]
    assert run.failed == 0 and not (out / "grid.csv.checkpoint.jsonl").exists()


def max_abs_torques(result) -> list[float]:
    """Per joint the largest |tau| of a torques CSV (read back from its table)."""
    header = list(result.table.header)
    rows = np.asarray(result.table.rows)
    return [float(np.abs(rows[:, header.index(f"tau{i}_Nm")]).max()) for i in (1, 2)]


def test_zip_torques_sweep_equals_separate_runs(tmp_path):
    sweep = the_sweep(
        tmp_path,
        TORQUES,
        TORQUES_BASE,
        """job = "torques"
combine = "zip"
values."robot.lengths_m[2]" = [0.3, 0.4, 0.5]
values."theta_deg[1][2]" = [10, 20, 30]
""",
    )
    run = run_sweep(sweep)
    rows = list(run.table.rows)
    assert run.table.header[:3] == ("point", "robot.lengths_m[2]", "theta_deg[1][2]")
    for row, (l2, theta) in zip(rows, [(0.3, 10), (0.4, 20), (0.5, 30)], strict=True):
        alone = separate(tmp_path, TORQUES, **{**TORQUES_BASE, "l2": l2, "theta12": theta})
        figures = dict(zip(run.table.header, row, strict=True))
        assert [figures["tau1_abs_max_Nm"], figures["tau2_abs_max_Nm"]] == max_abs_torques(alone)


def test_sampled_sweep_equals_separate_runs(tmp_path):
    sweep = the_sweep(
        tmp_path,
        TORQUES,
        TORQUES_BASE,
        """job = "torques"
ranges."robot.lengths_m[1]" = [0.2, 0.3]
ranges."robot.masses_kg[2]" = [1.0, 2.0]
sample = { method = "sobol", count = 4, seed = 7 }
""",
    )
    run = run_sweep(sweep)
    for row, (l1, m2) in zip(run.table.rows, design(sweep), strict=True):
        assert list(row[1:3]) == [l1, m2]
        alone = separate(tmp_path, TORQUES, **{**TORQUES_BASE, "l1": repr(l1), "m2": repr(m2)})
        assert list(row[3:5]) == max_abs_torques(alone)


def test_a_failing_point_is_a_row_and_the_others_go_on(tmp_path, cli):
    # 0.25 cm: about 37,000 boxes estimated, within 4 × the budget, past it when run
    base = {**WORKSPACE_BASE, "box_budget": 9500}
    path = write(
        tmp_path,
        "p.toml",
        WORKSPACE,
        """[[sweep]]
job = "workspace"
values.precision_cm = [2.0, 0.25, 1.5]
output = "budget.csv"
""",
        **base,
    )
    result = cli("sweep", path, "--out-dir", tmp_path / "out", "--workers", "1")
    assert result.exit_code == 1, result.output
    assert "1 sweep point(s) failed" in result.stderr
    rows = read_rows(tmp_path / "out" / "budget.csv")
    assert [r["status"] for r in rows] == ["ok", "failed", "ok"]
    assert "box_budget" in rows[1]["message"] and "\n" not in rows[1]["message"]
    assert rows[1]["area_kept_cm2"] == "" and rows[2]["area_kept_cm2"] != ""


def test_cancel_keeps_the_checkpoint_and_resume_recomputes_nothing_finished(tmp_path, monkeypatch):
    sweep = the_sweep(
        tmp_path,
        TORQUES,
        TORQUES_BASE,
        """job = "torques"
values."robot.masses_kg[2]" = [1.0, 1.5, 2.0, 2.5, 3.0]
output = "resume.csv"
""",
    )
    out = tmp_path / "out"
    progress = Progress()
    seen = []

    def cancel_after_two(outcome):
        seen.append(outcome.number)
        if len(seen) == 2:
            progress.request_cancel()

    with pytest.raises(Cancelled):
        run_sweep(sweep, progress, out_dir=out, on_outcome=cancel_after_two)
    assert not (out / "resume.csv").exists()
    lines = (out / "resume.csv.checkpoint.jsonl").read_text().splitlines()
    assert json.loads(lines[0])["fingerprint"] == sweep.fingerprint()
    assert [json.loads(line)["number"] for line in lines[1:]] == [1, 2]

    from planar_tui.sweep import execute

    computed = []
    real = execute.run_point
    monkeypatch.setattr(
        execute, "run_point", lambda task, p=None: computed.append(task.number) or real(task, p)
    )
    run = run_sweep(sweep, out_dir=out, resume=True)
    assert computed == [3, 4, 5] and run.resumed == 2
    assert not (out / "resume.csv.checkpoint.jsonl").exists()
    whole = run_sweep(sweep)  # uninterrupted, nothing written
    resumed_rows = read_rows(out / "resume.csv")
    assert [list(r.values())[:-1] for r in resumed_rows] == [
        [str(c) for c in row[:-1]] for row in whole.table.rows
    ]


def test_a_changed_preset_does_not_resume_stale_points(tmp_path):
    body = (
        '[[sweep]]\njob = "torques"\nvalues."robot.masses_kg[2]" = [1.0, 2.0]\noutput = "s.csv"\n'
    )
    out = tmp_path / "out"
    first = write(tmp_path, "p.toml", TORQUES, body, **TORQUES_BASE)
    (sweep,) = parse_sweeps(load_preset(first))
    progress = Progress()
    with pytest.raises(Cancelled):
        run_sweep(sweep, progress, out_dir=out, on_outcome=lambda o: progress.request_cancel())
    changed = write(tmp_path, "p.toml", TORQUES, body, **{**TORQUES_BASE, "l1": 0.5})
    (sweep,) = parse_sweeps(load_preset(changed))
    run = run_sweep(sweep, out_dir=out, resume=True)
    assert run.resumed == 0
    assert [row[2] for row in run.table.rows] == [
        max_abs_torques(separate(tmp_path, TORQUES, **{**TORQUES_BASE, "l1": 0.5, "m2": m}))[0]
        for m in (1.0, 2.0)
    ]


def _interrupted_after(sweep, out, count):
    """Run ``sweep`` into ``out`` and cancel it once ``count`` points have finished."""
    progress = Progress()
    seen = []

    def cancel(outcome):
        seen.append(outcome.number)
        if len(seen) == count:
            progress.request_cancel()

    with pytest.raises(Cancelled):
        run_sweep(sweep, progress, out_dir=out, on_outcome=cancel)


def test_a_sweep_started_afresh_removes_the_earlier_point_files(tmp_path):
    masses = ", ".join(str(1.0 + k / 10) for k in range(10))
    ten = the_sweep(
        tmp_path,
        TORQUES,
        TORQUES_BASE,
        f"""job = "torques"
values."robot.masses_kg[2]" = [{masses}]
output = "s.csv"
point_outputs = "pts"
""",
    )
    out = tmp_path / "out"
    _interrupted_after(ten, out, 2)
    assert sorted(p.name for p in (out / "pts").iterdir()) == [
        "point-01.csv",
        "point-01.csv.json",
        "point-02.csv",
        "point-02.csv.json",
    ]
    (out / "pts" / "notes.txt").write_text("mine")  # not a point file: kept
    three = the_sweep(
        tmp_path,
        TORQUES,
        TORQUES_BASE,
        """job = "torques"
values."robot.masses_kg[2]" = [1.0, 1.5, 2.0]
output = "s.csv"
point_outputs = "pts"
""",
    )
    run_sweep(three, out_dir=out, resume=True)  # another sweep's checkpoint: afresh
    names = sorted(p.name for p in (out / "pts").iterdir())
    assert names == ["notes.txt", *(f"point-{n}.csv{s}" for n in (1, 2, 3) for s in ("", ".json"))]


def test_resume_rewrites_the_missing_point_files_of_finished_points(tmp_path, monkeypatch):
    from planar_tui.sweep import execute

    sweep = the_sweep(
        tmp_path,
        TORQUES,
        TORQUES_BASE,
        """job = "torques"
values."robot.masses_kg[2]" = [1.0, 1.5, 2.0, 2.5, 3.0]
output = "s.csv"
point_outputs = "pts"
""",
    )
    out = tmp_path / "out"
    _interrupted_after(sweep, out, 3)
    for number in (1, 3):
        (out / "pts" / f"point-{number}.csv").unlink()
    computed = []
    real = execute.run_point
    monkeypatch.setattr(
        execute, "run_point", lambda task, p=None: computed.append(task.number) or real(task, p)
    )
    run = run_sweep(sweep, out_dir=out, resume=True)
    assert sorted(computed) == [1, 3, 4, 5]
    assert (run.resumed, run.recomputed) == (1, 2)
    from planar_tui.sweep.service import resume_note

    assert resume_note(run) == ", 1 from the checkpoint, 2 run again (point files missing)"
    whole = tmp_path / "whole"
    run_sweep(sweep, out_dir=whole)  # uninterrupted
    for number in range(1, 6):
        name = f"point-{number}.csv"
        assert (out / "pts" / name).read_text() == (whole / "pts" / name).read_text()


def test_the_sweep_service_imports_without_dask():
    """docs/sweeps.md: every ``planar_tui.sweep`` module imports without Dask."""
    import subprocess
    import sys

    from tests.conftest import REPO

    code = (
        "import sys, planar_tui.sweep.service, planar_tui.sweep.execute; "
        "print(sorted({'dask', 'distributed'} & set(sys.modules)))"
    )
    probe = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, cwd=REPO, check=True
    )
    assert probe.stdout.strip() == "[]", probe.stderr

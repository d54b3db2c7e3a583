"""Sweep runs refused before anything runs, in one line with exit code 2 and nothing
written: the run's planned files colliding (CSVs, checkpoints, figures, point folders of
jobs and sweeps together), a figure that cannot be drawn, a checkpoint of the same sweep
without ``--resume``, ``--workers 0``, a ``count`` beyond ``max_points`` (never built), a
motion point on an unusable ``cuda`` device. A checkpoint of another version of the sweep
is replaced, said in one line; a sweep CSV that cannot be written is one ``error:`` line."""

from __future__ import annotations

import json
import os

import pytest

from planar_tui.presets import load_preset
from planar_tui.sweep.checkpoint import record_digest
from planar_tui.sweep.spec import parse_sweeps
from tests.sweep_presets import TORQUES, TORQUES_BASE, WORKSPACE, WORKSPACE_BASE, write

SWEEP = '[[sweep]]\njob = "torques"\nvalues."robot.masses_kg[2]" = [1.0, 2.0]\n'


def refused(result, *parts):
    assert result.exit_code == 2, result.output
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in result.output, result.stderr
    for part in parts:
        assert part in lines[0], lines[0]
    return lines[0]


def listing(folder):
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*"))


@pytest.mark.parametrize(
    ("keys", "command", "parts"),
    [
        ('output = "a.csv"\npoint_outputs = "a.csv"\n', ("sweep",), ("a.csv", "written by both")),
        ('output = "a.svg"\nplot = "a.svg"\n', ("sweep",), ("a.svg", "written by both")),
        (
            'output = "pts/point-1.csv"\npoint_outputs = "pts"\n',
            ("sweep",),
            ("pts", "folder of point files", "point-1.csv"),
        ),
        (
            'output = "a.csv"\npoint_outputs = "pts"\n'
            + SWEEP
            + 'output = "b.csv"\npoint_outputs = "pts"\n',
            ("sweep",),
            ("pts", "written by both"),
        ),
        (
            'output = "s.csv"\nplot = "same.svg"\n',
            ("run",),
            ("same.svg", "p:torques[1] (plot)", "p:sweep[1] (plot)"),
        ),
        (
            'output = "s.csv"\nplot = "grid.png"\n',
            ("run", "--plot", "{out}/grid.png"),
            ("grid.png", "written by both"),
        ),
        ('output = "s.csv"\n', ("run",), ("tq.csv", "written by both")),
        (
            'output = "a.csv"\n' + SWEEP + 'output = "a.csv/b.csv"\n',
            ("sweep",),
            ("a.csv/b.csv", "lies inside", "a.csv, which p:sweep[1] (output) writes as a file"),
        ),
        (
            'output = "a.csv"\npoint_outputs = "a.csv/pts"\n',
            ("sweep",),
            ("a.csv/pts", "lies inside", "p:sweep[1] (output) writes as a file"),
        ),
    ],
)
def test_colliding_planned_files_are_refused_before_anything_runs(
    tmp_path, cli, keys, command, parts
):
    out = tmp_path / "out"
    out.mkdir()
    body = TORQUES.format(**TORQUES_BASE)
    if "same.svg" in keys:
        body = body.replace('output = "tq.csv"', 'output = "tq.csv"\nplot = "same.svg"')
    if keys.startswith('output = "s.csv"\n') and "plot" not in keys:
        keys = 'output = "tq.csv"\n'
    preset = tmp_path / "p.toml"
    preset.write_text(body + "\n" + SWEEP + keys)
    args = [part.format(out=out) for part in command]
    refused(cli(args[0], preset, "--out-dir", out, "--workers", "1", *args[1:]), *parts)
    assert listing(out) == []


def test_a_job_table_inside_its_own_csv_is_refused_before_anything_runs(tmp_path, cli):
    """``boxes_output = "ws.csv/boxes.csv"`` beside ``output = "ws.csv"``: once half-written
    (the CSV, then the boxes could not be)."""
    body = WORKSPACE.format(**WORKSPACE_BASE).replace(
        'output = "ws.csv"', 'output = "ws.csv"\nboxes_output = "ws.csv/boxes.csv"'
    )
    preset = tmp_path / "p.toml"
    preset.write_text(body)
    out = tmp_path / "out"
    out.mkdir()
    refused(
        cli("run", preset, "--out-dir", out),
        "ws.csv/boxes.csv",
        "lies inside",
        "p:workspace[1] (output) writes as a file",
    )
    assert listing(out) == []


def test_a_figure_that_cannot_be_drawn_is_refused_before_anything_runs(tmp_path, cli):
    preset = write(
        tmp_path,
        "p.toml",
        TORQUES,
        '[[sweep]]\njob = "torques"\n'
        'values."robot.masses_kg[2]" = [1.0]\noutput = "one.csv"\nplot = "one.svg"\n'
        + SWEEP
        + 'output = "two.csv"\n',
        **TORQUES_BASE,
    )
    out = tmp_path / "out"
    refused(cli("sweep", preset, "--out-dir", out, "--workers", "1"), "sweep[1].plot", "1 point")
    assert not out.exists() or listing(out) == []


def test_a_checkpoint_of_the_same_sweep_is_kept_without_resume(tmp_path, cli):
    preset = write(tmp_path, "p.toml", TORQUES, SWEEP + 'output = "m.csv"\n', **TORQUES_BASE)
    (sweep,) = parse_sweeps(load_preset(preset))
    checkpoint = tmp_path / "m.csv.checkpoint.jsonl"
    figures = {"tau1_abs_max_Nm": 1.5, "tau2_abs_max_Nm": 2.5}  # the kind's own columns
    point = {
        "number": 1,
        "status": "ok",
        "message": "",
        "figures": figures,
        "seconds": 12.5,
        "tables": {},
    }
    point["digest"] = record_digest(sweep.fingerprint(), point)  # as the run writes it
    text = json.dumps({"fingerprint": sweep.fingerprint(), "points": 2}) + "\n"
    text += json.dumps(point) + "\n"
    checkpoint.write_text(text)
    line = refused(
        cli("sweep", preset, "--out-dir", tmp_path, "--workers", "1"),
        str(checkpoint),
        "--resume",
        "delete the file",
    )
    assert "interrupted" in line
    assert checkpoint.read_text() == text and not (tmp_path / "m.csv").exists()
    # --resume finishes it: point 1 is not run again (its recorded seconds are kept)
    result = cli("sweep", preset, "--out-dir", tmp_path, "--workers", "1", "--resume")
    assert result.exit_code == 0, result.output
    assert "2 points, 0 failed, 1 from the checkpoint" in result.stdout
    assert "12.5" in (tmp_path / "m.csv").read_text().splitlines()[1]
    assert not checkpoint.exists()


def test_a_checkpoint_of_another_version_of_the_sweep_is_replaced_saying_so(tmp_path, cli):
    preset = write(tmp_path, "p.toml", TORQUES, SWEEP + 'output = "m.csv"\n', **TORQUES_BASE)
    checkpoint = tmp_path / "m.csv.checkpoint.jsonl"
    checkpoint.write_text(json.dumps({"fingerprint": "0" * 64, "points": 2}) + "\n")
    result = cli("sweep", preset, "--out-dir", tmp_path, "--workers", "1")
    assert result.exit_code == 0, result.output
    notes = [line for line in result.stderr.splitlines() if "replaced" in line]
    assert len(notes) == 1 and str(checkpoint) in notes[0] and "p:sweep[1]" in notes[0]
    assert (tmp_path / "m.csv").exists() and not checkpoint.exists()


def test_workers_below_one_is_one_line(tmp_path, cli):
    preset = write(tmp_path, "p.toml", TORQUES, SWEEP, **TORQUES_BASE)
    for command in ("sweep", "run"):
        line = refused(
            cli(command, preset, "--out-dir", tmp_path, "--workers", "0"),
            "--workers",
            "is 0",
            "an integer from 1 to",
        )
        assert line.startswith("error: command line: --workers")
    assert listing(tmp_path) == ["p.toml"]


def test_a_count_beyond_max_points_is_refused_without_making_the_values(tmp_path, cli, monkeypatch):
    from planar_tui.sweep import spec

    made = []
    real = spec._read_values
    monkeypatch.setattr(spec, "_read_values", lambda *a: made.append(a) or real(*a))
    preset = write(
        tmp_path,
        "p.toml",
        TORQUES,
        '[[sweep]]\njob = "torques"\n'
        'values."robot.masses_kg[2]" = { from = 1, to = 2, count = 1000000000 }\n',
        **TORQUES_BASE,
    )
    refused(
        cli("sweep", preset, "--out-dir", tmp_path, "--workers", "1"),
        "1,000,000,000 points",
        "max_points = 100,000",
    )
    grid = write(
        tmp_path,
        "g.toml",
        TORQUES,
        '[[sweep]]\njob = "torques"\nmax_points = 10\n'
        'values."robot.masses_kg[2]" = { from = 1, to = 2, count = 5 }\n'
        'values."robot.masses_kg[1]" = { from = 1, to = 2, count = 3 }\n',
        **TORQUES_BASE,
    )
    refused(
        cli("sweep", grid, "--out-dir", tmp_path, "--workers", "1"),
        "sweep[1].max_points",
        "15 points",
    )
    assert made == []
    assert listing(tmp_path) == ["g.toml", "p.toml"]


def test_a_sweep_csv_that_cannot_be_written_is_one_error_line(tmp_path, cli, monkeypatch):
    from planar_tui.sweep import service

    def full(path, table):
        raise OSError(28, os.strerror(28), str(path))

    monkeypatch.setattr(service, "write_csv_atomic", full)
    preset = write(tmp_path, "p.toml", TORQUES, SWEEP + 'output = "m.csv"\n', **TORQUES_BASE)
    result = cli("sweep", preset, "--out-dir", tmp_path, "--workers", "1")
    assert result.exit_code == 1, result.output
    assert "Traceback" not in result.output
    errors = [line for line in result.stderr.splitlines() if line.startswith("error:")]
    assert len(errors) == 2 and "m.csv: cannot write: No space left on device" in errors[0]
    assert (tmp_path / "m.csv.checkpoint.jsonl").exists()  # the finished points are kept


MOTION = """[robot]
lengths_m = [0.3, 0.25]
masses_kg = [2.0, 1.5]

[motion_uncertainty]
duration_s = 0.05
step_s = 0.01
samples = 8
device = "cpu"
tolerance_length_mm = 1
output = "motion.csv"

[[sweep]]
job = "motion_uncertainty"
values.device = ["cpu", "cuda"]
output = "devices.csv"
"""


def test_a_motion_point_on_an_unusable_cuda_device_is_refused_up_front(tmp_path, cli, monkeypatch):
    monkeypatch.delenv("NUMBA_ENABLE_CUDASIM", raising=False)
    from planar_tui.motion.device import cuda_problem

    assert cuda_problem() is not None, "this test needs a machine without a usable GPU"
    preset = tmp_path / "m.toml"
    preset.write_text(MOTION)
    refused(
        cli("sweep", preset, "--out-dir", tmp_path, "--workers", "1"),
        "sweep[1]: point 2",
        "cuda",
        "motion_uncertainty.device",
    )
    assert listing(tmp_path) == ["m.toml"]


@pytest.mark.parametrize("where", ["create", "add"])
def test_a_checkpoint_that_cannot_be_written_is_one_error_line(tmp_path, cli, monkeypatch, where):
    from planar_tui.sweep import checkpoint

    def full(*args, **kwargs):
        raise OSError(28, os.strerror(28))

    monkeypatch.setattr(checkpoint, "write_text_atomic" if where == "create" else "_record", full)
    preset = write(tmp_path, "p.toml", TORQUES, SWEEP + 'output = "m.csv"\n', **TORQUES_BASE)
    result = cli("sweep", preset, "--out-dir", tmp_path, "--workers", "1")
    assert result.exit_code == 1, result.output
    assert "Traceback" not in result.output
    errors = [line for line in result.stderr.splitlines() if line.startswith("error:")]
    assert len(errors) == 2, result.stderr
    assert "m.csv.checkpoint.jsonl: cannot write: No space left on device" in errors[0]
    assert not (tmp_path / "m.csv").exists()

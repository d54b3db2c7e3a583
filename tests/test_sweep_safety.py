"""Sweeps never touch files they did not write, and a damaged checkpoint cannot crash a
resume (issue 19, items 1-2), through the public CLI."""

from __future__ import annotations

import csv
import json

import pytest

from planar_tui.errors import ExitCode
from tests.sweep_presets import SENSITIVITY, TORQUES, TORQUES_BASE, one_line, write

POINTS = """[[sweep]]
job = "torques"
values."robot.masses_kg[2]" = [1.0, 2.0]
output = "s.csv"
point_outputs = "pts"
"""


@pytest.mark.parametrize("name", ["point-99.csv", "point-1.csv.json"])
def test_a_users_point_file_in_the_folder_is_refused_by_name_and_kept(tmp_path, cli, name):
    """A CSV or a provenance sidecar (``point-1.csv.json`` would be overwritten)."""
    preset = write(tmp_path, "p.toml", TORQUES, POINTS, **TORQUES_BASE)
    out = tmp_path / "out"
    (out / "pts").mkdir(parents=True)
    (out / "pts" / name).write_text("mine\n")
    result = cli("sweep", preset, "--out-dir", out, "--workers", "1")
    assert result.exit_code == ExitCode.BAD_INPUT
    line = one_line(result)
    assert name in line and "did not write" in line
    assert (out / "pts" / name).read_text() == "mine\n"
    assert sorted(p.name for p in (out / "pts").iterdir()) == [name]
    assert not (out / "s.csv").exists()


def test_a_symlinked_point_folder_is_refused_and_the_files_it_points_to_kept(tmp_path, cli):
    preset = write(tmp_path, "p.toml", TORQUES, POINTS, **TORQUES_BASE)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (elsewhere / "point-1.csv").write_text("precious\n")
    out = tmp_path / "out"
    out.mkdir()
    (out / "pts").symlink_to(elsewhere)
    result = cli("sweep", preset, "--out-dir", out, "--workers", "1")
    assert result.exit_code == ExitCode.BAD_INPUT
    assert "symbolic link" in one_line(result)
    assert (elsewhere / "point-1.csv").read_text() == "precious\n"


def test_a_fresh_run_deletes_only_the_point_files_its_record_names(tmp_path, cli):
    preset = write(tmp_path, "p.toml", TORQUES, POINTS, **TORQUES_BASE)
    out = tmp_path / "out"
    assert cli("sweep", preset, "--out-dir", out, "--workers", "1").exit_code == 0
    both = ["point-1.csv", "point-1.csv.json", "point-2.csv", "point-2.csv.json"]
    assert sorted(p.name for p in (out / "pts").iterdir()) == both
    record = out / "s.csv.point-files.txt"
    assert record.read_text().split() == both  # each name recorded before its file
    (out / "pts" / "notes.txt").write_text("kept")  # no point file: not the sweep's business
    (out / "s.csv").unlink()
    one = write(tmp_path, "p.toml", TORQUES, POINTS.replace("[1.0, 2.0]", "[3.0]"), **TORQUES_BASE)
    assert cli("sweep", one, "--out-dir", out, "--workers", "1").exit_code == 0
    assert sorted(p.name for p in (out / "pts").iterdir()) == [
        "notes.txt",
        "point-1.csv",
        "point-1.csv.json",
    ]
    assert record.read_text().split() == ["point-1.csv", "point-1.csv.json"]


def _interrupted_checkpoint(tmp_path, cli, sweep_text=POINTS):
    """A preset and an output folder holding a checkpoint of its sweep with both points
    finished (the CSV removed, as after an interrupt)."""
    preset = write(tmp_path, "p.toml", TORQUES, sweep_text, **TORQUES_BASE)
    out = tmp_path / "out"
    checkpoint = out / "s.csv.checkpoint.jsonl"
    from planar_tui.presets import load_preset
    from planar_tui.sweep.service import run_sweep
    from planar_tui.sweep.spec import parse_sweeps

    (sweep,) = parse_sweeps(load_preset(preset))
    run = run_sweep(sweep, out_dir=out, keep_checkpoint=True)
    (out / "s.csv").unlink()
    assert checkpoint.exists()
    return preset, out, checkpoint, run


def _rows(path):
    with open(path, newline="") as stream:
        return list(csv.DictReader(stream))


@pytest.mark.parametrize(
    ("change", "problem"),
    [
        (lambda r: r.update(number="x"), "number"),
        (lambda r: r.update(number=7), "number"),
        (lambda r: r.update(figures="abc"), "figures"),
        (lambda r: r.update(status="done"), "status"),
        (lambda r: r.update(seconds=float("nan")), "seconds"),
        (lambda r: r["figures"].update(FORGED=1), "FORGED"),
        (lambda r: r["figures"].update(tau1_abs_max_Nm=float("inf")), "tau1_abs_max_Nm"),
        (lambda r: r.pop("message"), "message"),
    ],
)
def test_a_bad_checkpoint_record_is_dropped_with_one_line_and_its_point_runs_again(
    tmp_path, cli, change, problem
):
    preset, out, checkpoint, run = _interrupted_checkpoint(tmp_path, cli)
    lines = checkpoint.read_text().splitlines()
    record = json.loads(lines[1])
    change(record)
    lines[1] = json.dumps(record)
    checkpoint.write_text("\n".join(lines) + "\n")
    result = cli("sweep", preset, "--out-dir", out, "--workers", "1", "--resume")
    assert result.exit_code == 0, result.output
    assert "Traceback" not in result.output
    warnings = [line for line in result.stderr.splitlines() if line.startswith("warning:")]
    assert len(warnings) == 1, result.stderr
    assert f"{checkpoint}:2: record dropped" in warnings[0] and problem in warnings[0]
    assert "2 points, 0 failed, 1 from the checkpoint" in result.stdout
    rows = _rows(out / "s.csv")
    assert list(rows[0]) == [
        "point",
        "robot.masses_kg[2]",
        "tau1_abs_max_Nm",
        "tau2_abs_max_Nm",
        "status",
        "message",
        "seconds",
    ]
    expected = run.table.rows
    for row, want in zip(rows, expected, strict=True):
        assert [row["tau1_abs_max_Nm"], row["tau2_abs_max_Nm"]] == [str(want[2]), str(want[3])]


def test_a_checkpoint_whose_first_line_is_no_header_starts_afresh(tmp_path, cli):
    preset, out, checkpoint, _ = _interrupted_checkpoint(tmp_path, cli)
    lines = checkpoint.read_text().splitlines()
    checkpoint.write_text("\n".join(["[]", *lines[1:]]) + "\n")
    result = cli("sweep", preset, "--out-dir", out, "--workers", "1", "--resume")
    assert result.exit_code == 0, result.output
    assert "Traceback" not in result.output
    assert "2 points, 0 failed ->" in result.stdout
    assert len(_rows(out / "s.csv")) == 2


SIMULATE = """[robot]
lengths_m = [0.3, 0.25, 0.2]
masses_kg = [2.0, 1.5, 1.0]

[simulate]
duration_s = 0.01
step_s = 0.001
output = "sim.csv"
"""


@pytest.mark.parametrize(
    ("text", "kind"),
    [
        (SIMULATE, "simulate"),
        (TORQUES.format(**TORQUES_BASE), "torques"),
        (
            SENSITIVITY.format(mass_g=10).replace(
                "samples = 64", "samples = 64\nspeed_rad_s = [1.0, 2.0]"
            ),
            "sensitivity",
        ),
    ],
)
def test_the_declared_figure_names_are_those_a_run_reports(tmp_path, text, kind):
    """The columns a checkpoint record is checked against are those a real run gives."""
    from planar_tui.batch import prepare_jobs, run_job
    from planar_tui.presets import load_preset
    from planar_tui.registry import JOB_KINDS

    path = tmp_path / "p.toml"
    path.write_text(text)
    (job,) = prepare_jobs(load_preset(path).jobs_of(kind))
    figures = JOB_KINDS[kind].point_figures(job, run_job(job))
    assert JOB_KINDS[kind].figure_names(job) == tuple(figures)

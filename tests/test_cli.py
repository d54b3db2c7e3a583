"""The batch CLI end to end on the bundled Table 1 preset."""

from __future__ import annotations

import csv
import math
import os
import signal
import subprocess
import sys
import time

import pytest

from planar_tui.errors import ExitCode
from tests.conftest import PRESETS, REPO

TABLE1 = PRESETS / "paper-a-table1.toml"


def read_csv(path):
    with open(path, newline="") as stream:
        rows = list(csv.reader(stream))
    return rows[0], [[float(x) if x else math.inf for x in row] for row in rows[1:]]


def test_version_and_presets_list(cli):
    from planar_tui import __version__

    assert cli("--version").stdout.strip() == f"planar-tui {__version__}"
    listing = cli("presets").stdout.splitlines()
    assert any(line.startswith("paper-a-table1 ") and "Table 1" in line for line in listing)


def test_simulate_writes_both_runs_with_exact_header(tmp_path, cli):
    result = cli("simulate", TABLE1, "--out-dir", tmp_path)
    assert result.exit_code == 0, result.output
    header, rows = read_csv(tmp_path / "table1-6r-simulate.csv")
    assert header == (
        ["t_s"]
        + [f"theta{i}_rad" for i in range(1, 7)]
        + [f"omega{i}_rad_s" for i in range(1, 7)]
        + ["kinetic_J", "potential_J", "energy_J", "kappa"]
    )
    assert len(rows) == 10_000 // 10 + 1
    assert rows[0][0] == 0.0 and math.isclose(rows[-1][0], 1.0)
    assert rows[1][0] == pytest.approx(10 * 1e-4)
    # energy column is the sum of the other two
    assert all(abs(r[-2] - r[-3] - r[-4]) <= 1e-12 for r in rows)
    # free fall from the horizontal: starts at rest at zero energy and keeps it
    _, fall = read_csv(tmp_path / "table1-6r-free-fall.csv")
    assert fall[0][1:13] == [0.0] * 12
    assert max(abs(r[-2]) for r in fall) <= 1e-9
    assert fall[-1][1] < -0.5  # the arm has fallen (the first joint turned well below horizontal)
    assert "simulate paper-a-table1: 2 jobs" in result.stdout


def test_simulate_out_option_numbers_several_jobs(tmp_path, cli):
    result = cli("simulate", "paper-a-table1", "--out", tmp_path / "sim.csv")
    assert result.exit_code == 0, result.output
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "sim-1.csv",
        "sim-1.csv.json",
        "sim-2.csv",
        "sim-2.csv.json",
    ]


def test_torques_rows_match_listed_states_in_si_units(tmp_path, cli):
    result = cli("torques", TABLE1, "--out", tmp_path / "tau.csv")
    assert result.exit_code == 0, result.output
    header, rows = read_csv(tmp_path / "tau.csv")
    joints = range(1, 7)
    assert header == (
        [f"theta{i}_rad" for i in joints]
        + [f"omega{i}_rad_s" for i in joints]
        + [f"alpha{i}_rad_s2" for i in joints]
        + [f"tau{i}_Nm" for i in joints]
    )
    assert len(rows) == 2
    assert rows[1][:6] == pytest.approx([math.radians(d) for d in (10, 20, 30, 40, 50, 60)])
    # static, stretched: tau_i = g * sum_{k>=i} m_k (x_ck - x_joint_i), a closed form
    lengths = [0.25, 0.25, 0.20, 0.20, 0.15, 0.15]
    masses = [0.484, 0.484, 0.387, 0.387, 0.290, 0.290]
    joints_x = [sum(lengths[:i]) for i in range(6)]
    for i in range(6):
        expected = 9.81 * sum(
            masses[k] * (joints_x[k] + lengths[k] / 2 - joints_x[i]) for k in range(i, 6)
        )
        assert rows[0][18 + i] == pytest.approx(expected, rel=1e-12)


def test_run_is_deterministic_byte_for_byte(tmp_path, cli):
    """Every CSV is the same bytes run after run; a provenance sidecar differs only in
    what records the run itself (its command line, start time and duration)."""
    import json

    for name in ("a", "b"):
        assert cli("run", TABLE1, "--out-dir", tmp_path / name).exit_code == 0
    paths = sorted((tmp_path / "a").iterdir())
    assert any(p.name.endswith(".csv.json") for p in paths)
    for path in paths:
        other = tmp_path / "b" / path.name
        if not path.name.endswith(".json"):
            assert path.read_bytes() == other.read_bytes()
            continue
        first, second = json.loads(path.read_text()), json.loads(other.read_text())
        differ = {key for key in first.keys() | second.keys() if first.get(key) != second.get(key)}
        assert differ <= {"command", "started_utc", "duration_s"}, differ


def test_interrupt_mid_run_exits_130_and_writes_nothing(tmp_path, cli, monkeypatch):
    import planar_tui.dynamics.simulate as runner
    from planar_tui.progress import Progress

    calls = []

    def interrupting_advance(self, amount=1.0, detail=None, **figures):
        calls.append(amount)
        if len(calls) == 3:
            raise KeyboardInterrupt
        self.completed += amount

    monkeypatch.setattr(runner, "STEPS_PER_CHUNK", 1000)
    monkeypatch.setattr(Progress, "advance", interrupting_advance)
    result = cli("simulate", TABLE1, "--out-dir", tmp_path)
    assert result.exit_code == ExitCode.INTERRUPTED
    assert "interrupted" in result.stderr
    assert list(tmp_path.iterdir()) == []


@pytest.mark.slow
def test_sigint_to_a_real_process_leaves_no_partial_csv(tmp_path):
    long_run = tmp_path / "long.toml"
    text = TABLE1.read_text().replace("duration_s = 1.0", "duration_s = 600.0", 1)
    long_run.write_text(text)
    env = dict(os.environ, PYTHONPATH=str(REPO))
    process = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "planar_tui",
            "simulate",
            str(long_run),
            "--out-dir",
            str(tmp_path / "out"),
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        env=env,
        text=True,
    )
    time.sleep(4.0)
    process.send_signal(signal.SIGINT)
    _, err = process.communicate(timeout=600)
    assert process.returncode == ExitCode.INTERRUPTED, err
    assert "Traceback" not in err
    assert not (tmp_path / "out").exists() or list((tmp_path / "out").iterdir()) == []


WORKSPACE_SMALL = REPO / "tests" / "data" / "app" / "workspace-small.toml"


def test_run_writes_the_extra_tables_a_preset_names(tmp_path, cli):
    preset = tmp_path / "ws.toml"
    preset.write_text(WORKSPACE_SMALL.read_text() + 'boxes_output = "boxes/small.csv"\n')
    result = cli("run", preset, "--out-dir", tmp_path / "out")
    assert result.exit_code == 0, result.output
    header = (tmp_path / "out" / "boxes" / "small.csv").read_text().splitlines()[0]
    assert header == "x_lo_cm,x_hi_cm,y_lo_cm,y_hi_cm,status"
    assert (tmp_path / "out" / "small-workspace.csv").is_file()


def test_extra_output_outside_the_output_folder_is_refused(tmp_path, cli):
    preset = tmp_path / "ws.toml"
    preset.write_text(WORKSPACE_SMALL.read_text() + 'boxes_output = "../escape.csv"\n')
    result = cli("run", preset, "--out-dir", tmp_path / "out")
    assert result.exit_code == 2
    assert f"error: {preset}: workspace.boxes_output: is '../escape.csv'" in result.stderr
    assert not (tmp_path / "out").exists() and not (tmp_path / "escape.csv").exists()


def test_unwritable_outputs_are_refused_before_any_job_runs(tmp_path, cli):
    blocker = tmp_path / "a-file"
    blocker.write_text("")
    for out, problem in (
        (tmp_path, "is a folder"),
        (blocker / "x.csv", f"cannot be created: {blocker} is not a writable folder"),
    ):
        result = cli("torques", TABLE1, "--out", out)
        assert result.exit_code == 2
        assert result.stderr.strip() == (
            f"error: {out}: (output): {problem} (expected "
            + ("a CSV file path)" if out == tmp_path else "a path inside a writable folder)")
        )
        assert "done" not in result.stderr  # checked before the job ran


def test_a_failing_job_is_one_line_exit_1_and_no_file(tmp_path, cli, monkeypatch):
    def broken(*args):
        raise FloatingPointError("the kernel diverged")

    # the runner imports the kernel when it runs, so patching the kernel module reaches it
    monkeypatch.setattr("planar_tui.kernels.dynamics_batch.inverse_dynamics_batch_states", broken)
    result = cli("torques", TABLE1, "--out-dir", tmp_path)
    assert result.exit_code == ExitCode.RUN_FAILED
    assert result.stderr.strip().splitlines()[-1] == (
        "error: paper-a-table1:torques failed: FloatingPointError: the kernel diverged"
    )
    assert "Traceback" not in result.stderr
    assert list(tmp_path.iterdir()) == []


def test_presets_name_prints_a_bundled_preset_and_copy_writes_it_never_over_a_file(cli, tmp_path):
    from tests.conftest import PRESETS

    text = (PRESETS / "paper-a-table1.toml").read_text(encoding="utf-8")
    result = cli("presets", "paper-a-table1")
    assert result.exit_code == 0 and result.stdout == text
    target = tmp_path / "mine.toml"
    result = cli("presets", "paper-a-table1.toml", "--copy", target)
    assert result.exit_code == 0, result.output
    assert target.read_text(encoding="utf-8") == text
    target.write_text("# my edits\n")
    result = cli("presets", "paper-a-table4", "--copy", target)
    assert result.exit_code == 2
    assert result.stderr.strip() == (
        f"error: command line: --copy: {target} exists (it is "
        "never overwritten) (expected a new file name)"
    )
    assert target.read_text() == "# my edits\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["mine.toml"]
    unknown = cli("presets", "nope")
    assert unknown.exit_code == 2 and unknown.stderr.count("\n") == 1
    assert "NAME: is 'nope', no bundled preset (expected one of " in unknown.stderr
    assert "paper-a-fig5-6" in unknown.stderr

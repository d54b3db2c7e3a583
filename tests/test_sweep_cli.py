"""``planar-tui sweep`` and ``run`` on real processes: Ctrl-C on a 2-process local cluster
exits 130 with the finished points checkpointed and no CSV, ``--resume`` finishes the
sweep without recomputing them and gives the uninterrupted result; ``run`` runs the
sweeps after the jobs."""

from __future__ import annotations

import csv
import json
import os
import signal
import subprocess
import sys
import time

import pytest

from planar_tui.errors import ExitCode
from planar_tui.presets import load_preset
from planar_tui.sweep.service import run_sweep
from planar_tui.sweep.spec import parse_sweeps
from tests.conftest import REPO
from tests.sweep_presets import TORQUES, TORQUES_BASE, WORKSPACE, WORKSPACE_BASE, write

pytestmark = pytest.mark.slow  # end to end (see pyproject.toml's markers)

CONSOLE_SCRIPT = "from planar_tui.entry import main; main()"


def read_rows(path):
    with open(path, newline="") as stream:
        return list(csv.DictReader(stream))


def test_ctrl_c_then_resume_gives_the_whole_result_without_recomputing(tmp_path, cli):
    preset = write(
        tmp_path,
        "p.toml",
        WORKSPACE,
        """[[sweep]]
job = "workspace"
values.orientation_deg = { from = -30, to = 30, count = 10 }
values.precision_cm = [0.2]
output = "interrupted.csv"
""",
        **WORKSPACE_BASE,
    )
    out = tmp_path / "out"
    checkpoint = out / "interrupted.csv.checkpoint.jsonl"
    process = subprocess.Popen(
        [
            sys.executable,
            "-c",
            CONSOLE_SCRIPT,
            "sweep",
            str(preset),
            "--workers",
            "2",
            "--out-dir",
            str(out),
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
        env=dict(os.environ, PYTHONPATH=str(REPO)),
    )
    deadline = time.monotonic() + 90
    while not (checkpoint.exists() and len(checkpoint.read_text().splitlines()) >= 3):
        assert process.poll() is None, process.communicate()
        assert time.monotonic() < deadline, "no point finished"
        time.sleep(0.02)
    os.killpg(process.pid, signal.SIGINT)  # as a terminal's Ctrl-C: the whole group
    _, err = process.communicate(timeout=600)
    assert process.returncode == ExitCode.INTERRUPTED, err
    assert "dask: local cluster of 2 worker processes, dashboard http" in err
    assert err.strip().splitlines()[-1].startswith("interrupted: finished points are in the")
    assert "Traceback" not in err
    assert not (out / "interrupted.csv").exists()
    records = [json.loads(line) for line in checkpoint.read_text().splitlines()[1:]]
    finished = {r["number"]: r["seconds"] for r in records}
    assert 2 <= len(finished) < 10

    result = cli("sweep", preset, "--out-dir", out, "--resume", "--workers", "1")
    assert result.exit_code == 0, result.output
    assert f"10 points, 0 failed, {len(finished)} from the checkpoint" in result.stdout
    rows = read_rows(out / "interrupted.csv")
    for row in rows:  # a resumed point keeps the timing of its first run: not run again
        if int(row["point"]) in finished:
            assert float(row["seconds"]) == round(finished[int(row["point"])], 6)
    assert not checkpoint.exists()
    (sweep,) = parse_sweeps(load_preset(preset))
    whole = run_sweep(sweep)
    assert [list(r.values())[:-1] for r in rows] == [
        [str(c) for c in row[:-1]] for row in whole.table.rows
    ]


def test_run_runs_the_sweeps_after_the_jobs(tmp_path, cli):
    preset = write(
        tmp_path,
        "p.toml",
        TORQUES,
        """[[sweep]]
job = "torques"
values."robot.masses_kg[2]" = [1.0, 2.0]
output = "masses.csv"
""",
        **TORQUES_BASE,
    )
    result = cli("run", preset, "--out-dir", tmp_path, "--workers", "1")
    assert result.exit_code == 0, result.output
    assert (tmp_path / "tq.csv").exists()
    assert "p:sweep[1]: 2 points, 0 failed" in result.stdout
    assert [r["robot.masses_kg[2]"] for r in read_rows(tmp_path / "masses.csv")] == ["1.0", "2.0"]
    # with --job only the named jobs run, no sweep
    (tmp_path / "masses.csv").unlink()
    result = cli("run", preset, "--out-dir", tmp_path, "--job", "torques[1]")
    assert result.exit_code == 0 and not (tmp_path / "masses.csv").exists()


def test_sweep_without_sweeps_and_an_unreachable_scheduler(tmp_path, cli, monkeypatch):
    plain = write(tmp_path, "plain.toml", TORQUES, **TORQUES_BASE)
    result = cli("sweep", plain, "--out-dir", tmp_path / "out")
    assert result.exit_code == 2
    assert (
        result.stderr.strip() == f"error: {plain}: sweep: no [[sweep]] table in this "
        "preset (expected a [[sweep]] table)"
    )
    preset = write(
        tmp_path,
        "p.toml",
        TORQUES,
        '[[sweep]]\njob = "torques"\nvalues."robot.masses_kg[2]" = [1.0]\n',
        **TORQUES_BASE,
    )
    monkeypatch.setenv("PLANAR_TUI_SCHEDULER_TIMEOUT_S", "1")
    result = cli("sweep", preset, "--out-dir", tmp_path / "out", "--scheduler", "tcp://127.0.0.1:9")
    assert result.exit_code == 2
    last = result.stderr.strip().splitlines()[-1]
    assert last.startswith("error: command line: --scheduler: cannot reach tcp://127.0.0.1:9")
    monkeypatch.setenv("PLANAR_TUI_SCHEDULER", "tcp://127.0.0.1:7")  # the same, by name
    result = cli("sweep", preset, "--out-dir", tmp_path / "out")
    assert result.exit_code == 2
    last = result.stderr.strip().splitlines()[-1]
    assert last.startswith("error: command line: --scheduler: cannot reach tcp://127.0.0.1:7")
    assert not (tmp_path / "out" / "p-sweep-1.csv").exists()


def test_resume_after_ctrl_c_in_the_second_sweep_recomputes_none_of_the_first(tmp_path, cli):
    """Ctrl-C during the second sweep keeps the first one's checkpoint (its CSV is
    written); ``--resume`` rebuilds the first from it (every point from the checkpoint,
    its timings kept) and runs only the second's unfinished points."""
    preset = tmp_path / "two.toml"
    preset.write_text(
        TORQUES.format(**TORQUES_BASE)
        + WORKSPACE.split("\n", 1)[1].format(**WORKSPACE_BASE)
        + """
[[sweep]]
job = "torques"
values."robot.masses_kg[2]" = [1.0, 2.0, 3.0]
output = "first.csv"

[[sweep]]
job = "workspace"
values.orientation_deg = { from = -30, to = 30, count = 10 }
values.precision_cm = [0.2]
output = "second.csv"
"""
    )
    out = tmp_path / "out"
    first, second = (out / f"{name}.csv.checkpoint.jsonl" for name in ("first", "second"))
    process = subprocess.Popen(
        [
            sys.executable,
            "-c",
            CONSOLE_SCRIPT,
            "sweep",
            str(preset),
            "--workers",
            "1",
            "--out-dir",
            str(out),
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
        env=dict(os.environ, PYTHONPATH=str(REPO)),
    )
    deadline = time.monotonic() + 90
    while not (second.exists() and len(second.read_text().splitlines()) >= 3):
        assert process.poll() is None, process.communicate()
        assert time.monotonic() < deadline, "no point of the second sweep finished"
        time.sleep(0.02)
    os.killpg(process.pid, signal.SIGINT)
    _, err = process.communicate(timeout=600)
    assert process.returncode == ExitCode.INTERRUPTED, err
    assert (out / "first.csv").exists() and not (out / "second.csv").exists()
    kept = {
        json.loads(line)["number"]: json.loads(line)["seconds"]
        for line in first.read_text().splitlines()[1:]
    }
    assert sorted(kept) == [1, 2, 3]
    done = len(second.read_text().splitlines()) - 1
    assert 2 <= done < 10

    result = cli("sweep", preset, "--out-dir", out, "--resume", "--workers", "1")
    assert result.exit_code == 0, result.output
    assert "two:sweep[1]: 3 points, 0 failed, 3 from the checkpoint" in result.stdout
    assert f"two:sweep[2]: 10 points, 0 failed, {done} from the checkpoint" in result.stdout
    for row in read_rows(out / "first.csv"):  # not run again: the first run's timings
        assert float(row["seconds"]) == round(kept[int(row["point"])], 6)
    assert not first.exists() and not second.exists()


def test_a_scheduler_that_never_answers_is_one_line_within_the_timeout(tmp_path, cli, monkeypatch):
    """A plain socket server on the loopback that accepts and never answers: refused
    after PLANAR_TUI_SCHEDULER_TIMEOUT_S (1 s here; bounded at 60 s, not hung)."""
    import socket
    import threading

    preset = write(
        tmp_path,
        "p.toml",
        TORQUES,
        '[[sweep]]\njob = "torques"\nvalues."robot.masses_kg[2]" = [1.0]\n',
        **TORQUES_BASE,
    )
    server = socket.create_server(("127.0.0.1", 0))
    accepted = []

    def accept() -> None:
        while True:
            try:
                accepted.append(server.accept()[0])
            except OSError:
                return

    threading.Thread(target=accept, daemon=True).start()
    address = f"tcp://127.0.0.1:{server.getsockname()[1]}"
    monkeypatch.setenv("PLANAR_TUI_SCHEDULER_TIMEOUT_S", "1")
    started = time.monotonic()
    try:
        result = cli("sweep", preset, "--out-dir", tmp_path / "out", "--scheduler", address)
    finally:
        server.close()
        for connection in accepted:
            connection.close()
    assert time.monotonic() - started < 60
    assert accepted, "the client never connected"
    assert result.exit_code == ExitCode.BAD_INPUT
    (line,) = result.stderr.strip().splitlines()
    assert line.startswith(f"error: command line: --scheduler: cannot reach {address}: ")
    assert "PLANAR_TUI_SCHEDULER_TIMEOUT_S" in line
    assert not (tmp_path / "out" / "p-sweep-1.csv").exists()


@pytest.mark.parametrize("value", ["0", "soon", "nan", "1e400"])
def test_a_bad_scheduler_timeout_is_one_line(tmp_path, cli, monkeypatch, value):
    preset = write(
        tmp_path,
        "p.toml",
        TORQUES,
        '[[sweep]]\njob = "torques"\nvalues."robot.masses_kg[2]" = [1.0]\n',
        **TORQUES_BASE,
    )
    monkeypatch.setenv("PLANAR_TUI_SCHEDULER_TIMEOUT_S", value)
    result = cli("sweep", preset, "--out-dir", tmp_path / "out", "--scheduler", "tcp://127.0.0.1:9")
    assert result.exit_code == ExitCode.BAD_INPUT
    (line,) = result.stderr.strip().splitlines()
    assert line.startswith("error: environment: PLANAR_TUI_SCHEDULER_TIMEOUT_S: is ")


def test_the_scheduler_variable_does_not_override_workers_1(tmp_path, cli, monkeypatch):
    preset = write(
        tmp_path,
        "p.toml",
        TORQUES,
        '[[sweep]]\njob = "torques"\nvalues."robot.masses_kg[2]" = [1.0]\n',
        **TORQUES_BASE,
    )
    monkeypatch.setenv("PLANAR_TUI_SCHEDULER", "tcp://127.0.0.1:9")  # nothing listens
    result = cli("sweep", preset, "--out-dir", tmp_path / "out", "--workers", "1")
    assert result.exit_code == 0, result.output
    assert "dask" not in result.stderr
    assert (tmp_path / "out" / "p-sweep-1.csv").exists()

"""Signals on real processes: SIGTERM (``kill``, ``timeout``, systemd, SLURM) is handled
like Ctrl-C (exit 143, one ``terminated:`` line, no hidden temporary file left), and
Ctrl-C while the CLI is still importing its modules prints no traceback (exit 130)."""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import time
import tomllib
from pathlib import Path

import pytest

from planar_tui.errors import ExitCode
from tests.conftest import PRESETS, REPO

pytestmark = pytest.mark.slow  # end to end (see pyproject.toml's markers)

#: What the ``planar-tui`` console script runs (pyproject's [project.scripts]).
CONSOLE_SCRIPT = "from planar_tui.entry import main; main()"


def start(*args: str, own_group: bool = False) -> subprocess.Popen:
    """The console script with ``args``; ``own_group``: in a process group of its own,
    as a terminal's foreground job is (``os.killpg`` then signals every process of the
    run, as Ctrl-C in a terminal does)."""
    env = dict(os.environ, PYTHONPATH=str(REPO))
    return subprocess.Popen(
        [sys.executable, "-c", CONSOLE_SCRIPT, *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        env=env,
        text=True,
        process_group=0 if own_group else None,
    )


def test_the_console_script_is_the_entry_module():
    project = tomllib.loads((REPO / "pyproject.toml").read_text())["project"]
    assert project["scripts"]["planar-tui"] == "planar_tui.entry:main"


def test_sigterm_while_a_csv_is_written_leaves_no_temporary_file(tmp_path):
    # a quick 2R run with many rows: most of its time is writing the CSV
    preset = tmp_path / "rows.toml"
    preset.write_text(
        (PRESETS / "paper-a-table1.toml")
        .read_text()
        .replace("duration_s = 1.0", "duration_s = 40.0", 1)
        .replace("every = 10", "every = 1", 1)
    )
    out = tmp_path / "out"
    process = start("simulate", str(preset), "--out-dir", str(out))
    deadline = time.monotonic() + 600
    while not (out.exists() and any(p.suffix == ".tmp" for p in out.iterdir())):
        assert process.poll() is None, process.communicate()
        assert time.monotonic() < deadline, "no temporary file appeared"
        time.sleep(0.002)
    process.send_signal(signal.SIGTERM)
    _, err = process.communicate(timeout=600)
    assert process.returncode == ExitCode.TERMINATED == 143, err
    assert err.strip().splitlines()[-1] == ("terminated: the running job's output was not written")
    assert "Traceback" not in err
    assert list(out.iterdir()) == []


def wait_until_caught(process: subprocess.Popen, signum: int, timeout_s: float = 10.0) -> None:
    """Wait until the process has a handler for ``signum`` (Linux: /proc/PID/status)."""
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        status = Path(f"/proc/{process.pid}/status").read_text()
        found = re.search(r"^SigCgt:\s*([0-9a-f]+)", status, re.MULTILINE)
        if found and int(found.group(1), 16) >> (signum - 1) & 1:
            return
        time.sleep(0.0005)
    raise AssertionError(f"the process never caught signal {signum}")


def test_ctrl_c_while_the_cli_is_importing_prints_no_traceback(tmp_path):
    long_run = tmp_path / "long.toml"
    text = (PRESETS / "paper-a-table1.toml").read_text()
    long_run.write_text(text.replace("duration_s = 1.0", "duration_s = 600.0", 1))
    # every 10 ms of the first 0.3 s: the imports (about 0.1 s), Typer building the Click
    # command from the signatures (a KeyboardInterrupt there escaped Typer once), the
    # preset loading and the job's start, on a quick or a loaded machine
    for delay_s in [0.0, 0.005] + [k / 100 for k in range(1, 31)]:
        process = start("simulate", str(long_run), "--out-dir", str(tmp_path / "out"))
        # the entry point's first act is to catch SIGTERM (Python alone never does); from
        # then on typer, rich and the CLI are being imported
        wait_until_caught(process, signal.SIGTERM)
        time.sleep(delay_s)
        process.send_signal(signal.SIGINT)
        _, err = process.communicate(timeout=600)
        assert "Traceback" not in err, (delay_s, err)
        assert process.returncode == ExitCode.INTERRUPTED, (delay_s, err)
        assert err.strip().splitlines()[-1].startswith("interrupted"), err
        if delay_s == 0.0:  # still importing: the entry point's own line
            assert err.strip() == "interrupted: nothing was run"
    assert not (tmp_path / "out").exists()


#: The console script, with a Ctrl-C that lands where Python can only report it: the job
#: runner drops a weakref whose callback raises KeyboardInterrupt ("Exception ignored in
#: ..."), as a SIGINT arriving during an import's module-lock callback does.
UNRAISABLE_CTRL_C = """
import sys, weakref
from planar_tui import batch
from planar_tui.entry import main

run_job = batch.run_job

class Dropped:
    pass

def interrupt(_):
    raise KeyboardInterrupt

def run_job_after_a_lost_ctrl_c(job, progress=None):
    dropped = Dropped()
    ref = weakref.ref(dropped, interrupt)
    del dropped  # the callback raises where Python can only report it
    return run_job(job, progress)

batch.run_job = run_job_after_a_lost_ctrl_c
sys.argv[0] = "planar-tui"
main()
"""


def test_a_ctrl_c_python_could_only_report_still_stops_the_run(tmp_path):
    out = tmp_path / "out"
    env = dict(os.environ, PYTHONPATH=str(REPO))
    done = subprocess.run(
        [
            sys.executable,
            "-c",
            UNRAISABLE_CTRL_C,
            "simulate",
            str(PRESETS / "paper-a-table1.toml"),
            "--out-dir",
            str(out),
        ],
        capture_output=True,
        text=True,
        env=env,
        timeout=120,
    )
    assert done.returncode == ExitCode.INTERRUPTED, done.stderr
    assert "Traceback" not in done.stderr and "Exception ignored" not in done.stderr
    assert done.stderr.strip().splitlines()[-1].startswith("interrupted"), done.stderr
    assert not out.exists() or list(out.iterdir()) == []


#: A Ctrl-C that Python hands on wrapped: raised inside a class body's ``__set_name__`` (as
#: a SIGINT landing while a job kind's dataclass fields are made), Python 3.11 reports it
#: as a RuntimeError caused by the KeyboardInterrupt. The CI met it once, a Ctrl-C 0.24 s
#: into `planar-tui simulate` on a loaded machine, while the kinds' modules loaded for the
#: kinds' commands.
WRAPPED_CTRL_C_KIND = """
class Field:
    def __set_name__(self, owner, name):
        raise KeyboardInterrupt  # what the SIGINT handler raises when it lands here

class Spec:
    orientation_deg = Field()
"""

WRAPPED_CTRL_C_WHILE_BUILDING = """
import sys
from planar_tui import registry
from planar_tui.entry import main

registry.JOB_KINDS = registry.Registry("JOB_KIND", {"wrapped": "wrapped_ctrl_c_kind"})
sys.argv[0] = "planar-tui"
main()
"""

WRAPPED_CTRL_C_WHILE_RUNNING = """
import sys
from planar_tui import batch
from planar_tui.entry import main

def run_job_importing_a_kind(job, progress=None):
    import wrapped_ctrl_c_kind  # noqa: F401

batch.run_job = run_job_importing_a_kind
sys.argv[0] = "planar-tui"
main()
"""


def test_a_ctrl_c_python_wrapped_in_another_error_is_still_an_interrupt(tmp_path):
    (tmp_path / "wrapped_ctrl_c_kind.py").write_text(WRAPPED_CTRL_C_KIND)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(REPO), str(tmp_path)]))
    out = tmp_path / "out"
    for script, last_line in [
        (WRAPPED_CTRL_C_WHILE_BUILDING, "interrupted: nothing was written"),
        (WRAPPED_CTRL_C_WHILE_RUNNING, "interrupted: the running job's output was not written"),
    ]:
        done = subprocess.run(
            [
                sys.executable,
                "-c",
                script,
                "simulate",
                str(PRESETS / "paper-a-table1.toml"),
                "--out-dir",
                str(out),
            ],
            capture_output=True,
            text=True,
            env=env,
            timeout=120,
        )
        assert "Traceback" not in done.stderr, done.stderr
        assert done.returncode == ExitCode.INTERRUPTED, done.stderr
        assert done.stderr.strip().splitlines()[-1] == last_line, done.stderr
        assert not out.exists() or list(out.iterdir()) == []

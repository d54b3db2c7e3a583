"""The CLI as a new user meets it: progress in batch logs, the compile stage
said, the summary's run and compile seconds, the help's and the summary's words, and an
optimisation that tells infeasible designs from failed evaluations."""

from __future__ import annotations

import csv
import io
import os
import re
import subprocess
import sys
import time

import pytest
import typer

from planar_tui import batch, warmup
from planar_tui.cli import app
from planar_tui.cli.loglines import ProgressLog
from planar_tui.errors import PresetError
from planar_tui.progress import Progress, ProgressState
from tests.conftest import PRESETS, REPO

TINY = REPO / "tests" / "data" / "app" / "tiny.toml"


class Clock:
    """A :func:`time.monotonic` stand-in the test moves by hand."""

    def __init__(self) -> None:
        self.now_s = 1000.0

    def __call__(self) -> float:
        return self.now_s


def state(completed: float, total: float, stage: str, started_s: float, detail: str = ""):
    return ProgressState(completed, total, stage, detail, stage_started_s=started_s)


def test_log_lines_come_at_each_stage_and_every_10_s_with_percent_rate_and_eta():
    clock, lines = Clock(), []
    log = ProgressLog("p:sweep[1]", lines.append, "pt", clock=clock)
    log.update(state(0, 50, "compiling", clock.now_s, "sweep: compiling k, 0 s"))
    clock.now_s += 4.0
    log.update(state(0, 50, "compiling", clock.now_s - 4.0))
    assert len(lines) == 1  # the same stage within 10 s: no line
    clock.now_s += 7.0
    log.heartbeat()  # 11 s without a report (a kernel compiling): the latest state again
    assert len(lines) == 2 and "elapsed 0:00:11" in lines[1]
    started_s = clock.now_s
    log.update(state(0, 50, "p:sweep[1]", started_s))  # a new stage: at once
    clock.now_s += 60.0
    log.update(state(20, 50, "p:sweep[1]", started_s, "20/50 points, 0 failed"))
    assert len(lines) == 4
    # 20 points in 60 s: 0.333 pt/s, 30 left: 90 s
    assert lines[3] == (
        "p:sweep[1]: 40% 20/50 0.333 pt/s ETA 0:01:30 elapsed 0:01:00\n  20/50 points, 0 failed"
    )
    clock.now_s += 9.9
    log.heartbeat()
    assert len(lines) == 4
    clock.now_s += 0.1
    log.heartbeat()
    assert len(lines) == 5
    log.done(85.0)
    assert lines[-1] == "p:sweep[1] done in 0:01:25\n  20/50 points, 0 failed"


def test_a_run_that_reports_nothing_yet_still_gets_a_line_every_10_s():
    clock, lines = Clock(), []
    log = ProgressLog("job", lines.append, clock=clock)
    clock.now_s += 9.0
    log.heartbeat()
    assert lines == []
    clock.now_s += 1.0
    log.heartbeat()
    assert lines == ["job: starting (elapsed 0:00:10)"]


def test_a_stage_not_started_shows_no_rate_and_no_eta():
    clock, lines = Clock(), []
    log = ProgressLog("job", lines.append, clock=clock)
    log.update(state(0, 200, "integrating", clock.now_s))
    assert lines == ["job integrating: 0% 0/200 -- units/s ETA -- elapsed 0:00:00"]


def test_a_warning_is_logged_once():
    clock, lines = Clock(), []
    log = ProgressLog("job", lines.append, clock=clock)
    for _ in range(2):
        log.update(ProgressState(0, 4, "bisection", "", warning="over budget"))
    assert lines[0] == "warning: job: over budget" and lines.count(lines[0]) == 1


def test_the_heartbeat_thread_writes_while_nothing_reports():
    clock, lines = Clock(), []
    with ProgressLog("job", lines.append, clock=clock, interval_s=0.0) as log:
        log.update(state(0, 1, "compiling", clock.now_s))
        for _ in range(300):  # the thread beats every second: wait up to 3 s
            if len(lines) > 1:
                break
            time.sleep(0.01)
    assert len(lines) > 1


def test_a_job_whose_stderr_is_a_pipe_logs_plain_progress_lines(tmp_path):
    done = subprocess.run(
        [sys.executable, "-m", "planar_tui", "simulate", str(TINY), "--out-dir", str(tmp_path)],
        capture_output=True,
        text=True,
        timeout=600,
        env=dict(os.environ, COLUMNS="80"),
    )
    assert done.returncode == 0, done.stderr
    assert "\x1b" not in done.stderr and "━" not in done.stderr
    lines = done.stderr.splitlines()
    (first,) = [line for line in lines if line.startswith("tiny:simulate integrating: ")]
    assert re.fullmatch(
        r"tiny:simulate integrating: 0% 0/200 -- units/s ETA -- elapsed 0:00:\d\d", first
    ), first
    assert any(re.fullmatch(r"tiny:simulate done in 0:\d\d:\d\d", line) for line in lines)


def test_the_compile_stage_names_the_kernel_and_its_seconds(monkeypatch):
    import numba

    def compile_a_kernel(unit: str) -> None:
        @numba.njit(cache=False)
        def tiny_kernel(x):
            return x + 1

        tiny_kernel(1)
        time.sleep(0.2)  # the watcher's next poll sees the kernel's name

    monkeypatch.setattr(warmup, "missing", lambda units: ["toy"])
    monkeypatch.setattr(warmup, "_run_example", compile_a_kernel)
    states: list[ProgressState] = []
    progress = Progress(on_update=states.append)
    assert warmup.warm_kernels(["toy"], progress) == ["toy"]
    assert {s.stage for s in states} == {warmup.STAGE}
    details = [s.detail for s in states]
    assert any(re.fullmatch(r"toy: compiling tiny_kernel, \d+ s", d) for d in details), details
    assert progress.figures["compile_s"] > 0
    lines: list[str] = []
    log = ProgressLog("j", lines.append)
    for each in states:
        log.update(each)
    assert lines[0].startswith("j compiling kernels (first run only): 0% ")


def test_the_summary_is_titled_by_the_command_and_splits_run_and_compile_seconds(cli, tmp_path):
    result = cli("simulate", TINY, "--out-dir", tmp_path)
    assert result.exit_code == 0, result.output
    lines = result.stdout.splitlines()
    assert "planar-tui run summary" not in result.stdout
    assert lines[0].strip() == "simulate tiny: 1 job"
    assert re.search(r"job and file +┃ +run s ┃ compile s ┃ result", result.stdout)
    (row,) = [line for line in lines if "tiny:simulate" in line]
    run_s, compile_s = (float(x) for x in re.findall(r"\d+\.\d{3}", row))
    assert run_s >= 0 and compile_s >= 0
    # the file's name whole on one line, its folder once below the table
    assert any(re.match(r"│ tiny-simulate\.csv +│", line) for line in lines)
    assert f"files in {tmp_path}" in lines


def test_the_summary_compile_seconds_are_the_compile_stage(monkeypatch, tmp_path):
    """run_plans gives the compile stage's seconds apart (the CSVs' ``seconds`` never
    held them)."""
    from contextlib import contextmanager

    from planar_tui.plan import plan_run
    from planar_tui.presets import load_preset

    def slow_compile(units, progress):
        progress.start(1, warmup.STAGE)
        time.sleep(0.3)
        progress.advance(1.0, compile_s=0.25)
        return list(units)

    monkeypatch.setattr(warmup, "warm_kernels", slow_compile)
    plan = plan_run(load_preset(TINY).jobs_of("simulate"), tmp_path)

    @contextmanager
    def progress_for(job):
        yield Progress()

    (row,) = batch.run_plans(plan.jobs, progress_for)
    assert row.compile_seconds == 0.25 and row.seconds > 0.25


def help_text(*args: str) -> str:
    from typer.testing import CliRunner

    result = CliRunner().invoke(app, list(args), env={"COLUMNS": "80"})
    return result.stdout


def test_help_paragraphs_are_not_broken_mid_sentence():
    group = typer.main.get_command(app)
    for name, command in group.commands.items():
        for paragraph in (command.help or "").split("\n\n"):
            assert "\n" not in paragraph, (name, paragraph)
    text = help_text("--help")
    # `run`'s help: "... files named as the presets say, then ..." broke after "presets"
    assert "files named as the presets" in " ".join(text.replace("│", " ").split())
    assert not re.search(r"presets\s*│\n│\s+say", text)


@pytest.mark.parametrize(
    ("command", "usage"),
    [
        ("simulate", "planar-tui simulate [OPTIONS] PRESET"),
        ("run", "planar-tui run [OPTIONS] PRESETS..."),
        ("presets", "planar-tui presets [OPTIONS] [NAME]"),
    ],
)
def test_usage_lines_name_arguments_in_capitals(command, usage):
    text = help_text(command, "--help")
    assert usage in text and "{" not in text.splitlines()[1]


def test_preset_descriptions_are_whole_sentences(cli):
    listed = cli("presets").stdout.splitlines()
    (line,) = [line for line in listed if line.startswith("paper-b-tolerance ")]
    assert line.endswith('and which does at least one reach ("some")?')
    (line,) = [line for line in listed if line.startswith("fivebar-tolerance ")]
    assert line.endswith('working mode "+-"')
    starts = {len(line) - len(line[len(line.split()[0]) :].lstrip()) for line in listed}
    assert len(starts) == 1  # the descriptions line up, the longest name included


def rows(path):
    with open(path, newline="", encoding="utf-8") as stream:
        return list(csv.DictReader(stream))


ARM_OPTIMISATION = """[robot]
gravity_m_s2 = 9.81
lengths_m = [0.5, 0.4]
masses_kg = [2.0, 1.0]
inertias_kgm2 = [0.04, 0.01]

[torques]
theta_deg = [[0, 0]]
omega_deg_s = [[0, 0]]
alpha_deg_s2 = [[0, 0]]
output = "t.csv"

[[optimise]]
job = "torques"
variables."theta_deg[1][1]" = { from = -60, to = 30 }
maximise = "tau1_abs_max_Nm"
budget = 24
population = 12
output = "opt.csv"
"""


@pytest.mark.parametrize("breaking", [False, True])
def test_an_optimisation_tells_infeasible_designs_from_failed_evaluations(
    cli, tmp_path, monkeypatch, breaking
):
    """A design the job refuses (below -30 deg here, as a centre out of reach) is
    infeasible: counted, exit 0; an evaluation whose job breaks (above 20 deg) failed:
    counted apart, the files written, exit 1."""
    real = batch.run_job

    def run_job(job, progress=None):
        theta_deg = job.spec.theta_deg[0][0]
        if theta_deg < -30:
            raise PresetError(job.preset_path, "theta_deg", "is out of reach", "a reachable one")
        if breaking and theta_deg > 20:
            raise batch.JobFailed(job, RuntimeError("the job broke"))
        return real(job, progress)

    monkeypatch.setattr(batch, "run_job", run_job)
    preset = tmp_path / "p.toml"
    preset.write_text(ARM_OPTIMISATION, encoding="utf-8")
    result = cli("optimise", preset, "--out-dir", tmp_path, "--workers", "1")
    evaluations = rows(tmp_path / "opt.csv")
    thetas = [float(row["theta_deg[1][1]"]) for row in evaluations]
    infeasible = sum(theta < -30 for theta in thetas)
    failed = sum(theta > 20 for theta in thetas) if breaking else 0
    assert infeasible > 0 and (failed > 0 or not breaking)
    statuses = [row["status"] for row in evaluations]
    assert statuses.count("infeasible") == infeasible and statuses.count("failed") == failed
    assert f"24 evaluations in 2 generations, {infeasible} infeasible, {failed} failed;" in (
        result.stdout
    )
    assert result.exit_code == (1 if breaking else 0), result.output
    if breaking:
        assert result.stderr.splitlines()[-1] == (
            f"error: {failed} evaluation(s) failed (status failed in the CSV)"
        )


def test_the_study_display_at_80_columns_shows_rate_and_eta_uncut():
    from rich.console import Console

    from planar_tui.cli import job_progress_display, progress_bar

    console = Console(width=80, record=True, force_terminal=True, file=io.StringIO())
    bars = job_progress_display(console)
    with progress_bar(bars, "optimise-3rrr-circle:optimise[1]", "eval") as progress:
        progress.start(128, "optimise-3rrr-circle:optimise[1]")
        time.sleep(0.05)
        progress.advance(64, "generation 4, 20 infeasible, 0 failed")
        console.print(bars.get_renderable())
        progress.start(1, "optimise-3rrr-circle:optimise[1] (certified)", "re-running")
        progress.advance(1)
    console.print(bars.get_renderable())
    text = console.export_text()
    assert "…" not in text and all(len(line) <= 80 for line in text.splitlines())
    assert re.search(r" 50%  64/128  [\d,.]+ eval/s  ETA \d:\d\d:\d\d$", text, re.M), text
    assert re.search(r"100%  [\d,.]+ eval/s  in \d:\d\d:\d\d$", text, re.M), text


def test_every_bundled_presets_jobs_pass_validation():
    from planar_tui.presets import load_preset

    for path in sorted(PRESETS.glob("*.toml")):
        batch.prepare_jobs(load_preset(path).jobs)


@pytest.mark.slow
def test_the_circle_optimisations_own_starting_job_runs(tmp_path):
    from planar_tui.presets import load_preset

    (job,) = load_preset(PRESETS / "optimise-3rrr-circle.toml").jobs_of("workspace")
    result = batch.run_job(job)
    assert "singularity-free: r ∈" in result.summary

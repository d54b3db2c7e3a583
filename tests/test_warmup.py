"""The warm-up markers follow numba's own cache keys: a kernel cached for sources at one
path (or with other stamps) is not a kernel cached for these, so a fresh clone warms up
again instead of compiling, uncancellable, inside a job's stage."""

from __future__ import annotations

import os
import shutil
import time

import pytest

from planar_tui import runtime, warmup


def test_the_marker_changes_with_the_sources_place_and_stamps(tmp_path, monkeypatch):
    here = warmup.marker("workspace")
    clone = tmp_path / "clone" / "kernels"
    shutil.copytree(runtime.kernels_folder(), clone, ignore=shutil.ignore_patterns("__py*"))
    monkeypatch.setattr(runtime, "kernels_folder", lambda: clone)
    elsewhere = warmup.marker("workspace")
    assert elsewhere != here
    assert elsewhere.parent == here.parent  # same kernel cache folder (same sources' digest)
    source = clone / "workspace3rrr.py"
    stat = source.stat()
    os.utime(source, ns=(stat.st_atime_ns, stat.st_mtime_ns + 10**9))  # a checkout
    assert warmup.marker("workspace") not in (here, elsewhere)
    assert warmup.marker("workspace") == warmup.marker("workspace")


def test_the_warm_up_example_leaves_nothing_in_the_design_cache(tmp_path, monkeypatch):
    """The example sensitivity job draws Sobol'/eFAST designs; while it runs (any thread)
    the design cache is off, so a first run leaves only the user's own jobs' designs."""
    from planar_tui.sensitivity import design_cache

    folder = design_cache.cache_dir()  # the per-test folder of conftest's autouse fixture
    assert folder is not None
    with runtime.design_cache_suspended():
        assert design_cache.cache_dir() is None
    assert design_cache.cache_dir() == folder
    monkeypatch.setattr(warmup, "marker", lambda kind: tmp_path / f"{kind}.marker")
    warmup._run_example("sensitivity")
    assert (tmp_path / "sensitivity.marker").exists()  # the example did run
    assert not folder.exists() or not any(folder.glob("*.npy"))


WORKSPACE_ROBOT = "[robot3rrr]\n"
LIMITS = "joint_limits_deg = [[20, 70], [110, 160], [245, 295]]\nprecision_cm = 8.0\n"


def test_a_workspace_job_warms_only_the_parts_its_run_calls(tmp_path):
    from planar_tui.presets import load_preset

    tables = [
        'form = "arc-distance"',
        'form = "slope"\nstrategy = "joint"',
        'form = "natural"',  # the leg-wise strategy by default
        'form = "geometric"',
        'orientation_deg = [-5, 5]\norientation_mode = "total"',
        'form = "arc-distance"\nsingularities = true\nelbow = [1, -1, 1]',
        'form = "arc-distance"\nkappa_max = 4\nelbow = [1, -1, 1]',
        'form = "arc-distance"\nleg_width_cm = 4\nelbow = [1, -1, 1]',
        'form = "arc-distance"\naccuracy = { actuator_deg = 0.1 }\nelbow = [1, -1, 1]',
    ]
    preset = tmp_path / "p.toml"
    preset.write_text(WORKSPACE_ROBOT + "".join(f"[[workspace]]\n{LIMITS}{t}\n" for t in tables))
    assert [warmup.units_for(job) for job in load_preset(preset).jobs] == [
        ["workspace:arc-distance"],
        ["workspace:joint"],
        ["workspace:legwise"],
        [],
        ["workspace:orientation"],
        ["workspace:arc-distance", "workspace:singularities"],
        ["workspace:arc-distance", "workspace:dexterity"],
        ["workspace:arc-distance", "workspace:interference"],
        ["workspace:arc-distance", "workspace:accuracy"],
    ]
    # a kind with one example is one unit; a bare kind stands for all of its parts
    assert warmup.units("torques") == ["torques"]
    assert set(warmup.units("workspace")) == {
        "workspace:legwise",
        "workspace:joint",
        "workspace:arc-distance",
        "workspace:singularities",
        "workspace:orientation",
        "workspace:dexterity",
        "workspace:interference",
        "workspace:accuracy",
    }
    whole = warmup.example("workspace")
    # one job a part, two for the joint bisection (its serial start and its threads)
    assert whole is not None and whole.count("[[workspace]]") == 9
    assert whole.count("[robot3rrr]") == 1


@pytest.mark.slow  # a fresh process compiling kernels
def test_a_cold_run_compiles_only_the_kernels_of_its_jobs(tmp_path):
    """Issue 21: an empty kernel cache, one arc-distance job: the warm-up runs that part
    alone, and numba's own cache then holds the arc-distance kernels but none of the
    bisection's (joint strategy) nor the leg-wise paving's."""
    import subprocess
    import sys

    from tests.conftest import REPO

    preset = tmp_path / "arc.toml"
    preset.write_text(WORKSPACE_ROBOT + f'[workspace]\n{LIMITS}form = "arc-distance"\n')
    cache = tmp_path / "cache"
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache), PYTHONPATH=str(REPO))
    subprocess.run(
        [
            sys.executable,
            "-m",
            "planar_tui",
            "run",
            str(preset),
            "--out-dir",
            str(tmp_path / "out"),
        ],
        check=True,
        capture_output=True,
        env=env,
        timeout=900,
    )
    (folder,) = cache.iterdir()
    markers = sorted(p.name.rsplit("-", 1)[0] for p in folder.glob("warm-*"))
    assert markers == ["warm-workspace-arc-distance"]
    compiled = " ".join(p.name for p in folder.rglob("*.nbi"))
    assert "arc_level" in compiled  # the probe sees the kernels numba cached
    assert "bisect_chunk" not in compiled and "bisect_blocks" not in compiled
    assert "workspace_legwise" not in compiled


@pytest.mark.slow
def test_ctrl_c_during_a_cold_warmup_stops_in_one_line_and_leaves_no_compiler(tmp_path):
    """SIGINT while ``planar-tui warmup`` compiles into an empty cache: one
    ``interrupted:`` line, exit 130, nothing after it (an interpreter that exits while a
    thread is inside LLVM printed an LLVM assertion there), no compiling process left."""
    import signal
    import subprocess
    import sys
    import time

    from tests.conftest import REPO
    from tests.processes import descendants, wait_until_gone

    env = {**os.environ, "PYTHONPATH": str(REPO), "NUMBA_CACHE_DIR": str(tmp_path / "cache")}
    warming = subprocess.Popen(
        [sys.executable, "-m", "planar_tui", "warmup"],
        env=env,
        cwd=tmp_path,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    time.sleep(15)  # the CLI loaded (a loaded machine: seconds), compiling begun
    assert warming.poll() is None, warming.communicate()
    compiling = descendants(warming.pid)
    warming.send_signal(signal.SIGINT)
    asked = time.monotonic()
    try:
        err = warming.communicate(timeout=60)[1]
    finally:
        warming.kill()
    stopped_s = time.monotonic() - asked
    assert warming.returncode == 130, err
    lines = [line for line in err.splitlines() if line.strip()]
    assert lines[-1].startswith("interrupted:"), err
    assert "Assertion" not in err and "LLVM" not in err and "Traceback" not in err, err
    assert stopped_s < 10  # 0.05 s polls and a SIGTERM to the compilers; a loaded machine
    assert not wait_until_gone(compiling, timeout_s=10)


def fake_children(monkeypatch, code: str) -> None:
    """Warm-up processes that run ``code`` (Python) instead of compiling; every kind's
    units missing."""
    import sys

    monkeypatch.setattr(warmup, "missing", lambda names: list(names))
    monkeypatch.setattr(warmup, "_child_command", lambda units: [sys.executable, "-c", code])


def test_the_warm_up_processes_run_side_by_side_and_report_their_kernels(monkeypatch, tmp_path):
    """Each process says it runs, then waits (at most 60 s) to see the other running: one
    after the other, the first would fail."""
    from planar_tui.progress import Progress

    code = (
        "import os, sys, time; from pathlib import Path; "
        f"folder = Path({str(tmp_path)!r}); (folder / str(os.getpid())).touch(); "
        "print('kernel rk4_step', flush=True); deadline = time.monotonic() + 60\n"
        "while len(list(folder.iterdir())) < 2:\n"
        "    time.sleep(0.05)\n"
        "    if time.monotonic() > deadline: sys.exit('alone')"
    )
    fake_children(monkeypatch, code)
    details: list[str] = []
    progress = Progress(on_update=lambda state: details.append(state.detail))
    done = warmup.warm_kernels_in_processes(["simulate", "torques"], progress, processes=2)
    assert done == ["simulate", "torques"]
    assert "simulate: rk4_step" in details or "torques: rk4_step" in details
    assert details[-1] in ("simulate kernels ready", "torques kernels ready")


def test_a_failed_warm_up_process_is_one_error_naming_its_kernels(monkeypatch):
    from planar_tui.progress import Progress

    fake_children(monkeypatch, "import sys; sys.exit('numba: no such kernel')")
    with pytest.raises(RuntimeError, match="compiling the simulate kernels failed: numba: no"):
        warmup.warm_kernels_in_processes(["simulate"], Progress())


def test_a_cancelled_warm_up_ends_its_processes_at_once(monkeypatch):
    from planar_tui.errors import Cancelled
    from planar_tui.progress import Progress

    fake_children(monkeypatch, "import time; time.sleep(120)")
    progress = Progress()
    spawned: list[warmup._Child] = []
    original = warmup._Child.__init__

    def spawn(self, units):
        original(self, units)
        spawned.append(self)
        progress.request_cancel()

    monkeypatch.setattr(warmup._Child, "__init__", spawn)
    started = time.monotonic()
    with pytest.raises(Cancelled):
        warmup.warm_kernels_in_processes(["simulate", "torques"], progress, processes=1)
    assert time.monotonic() - started < 10  # one poll and a SIGTERM
    assert len(spawned) == 1 and spawned[0].process.returncode is not None


EXIT_WHILE_COMPILING = """
import sys, threading, time
from planar_tui.cli.output import exit_now_if_compiling
from planar_tui.progress import WAIT_FOR_THREAD
if sys.argv[1] == "compiling":
    threading.Thread(target=time.sleep, args=(60,), name=WAIT_FOR_THREAD, daemon=True).start()
print("the outcome", end="")
exit_now_if_compiling(130)
print(" and the usual exit", end="")
"""


@pytest.mark.parametrize(
    ("state", "code", "out"),
    [
        ("compiling", 130, "the outcome"),  # at once, its output flushed
        ("idle", 0, "the outcome and the usual exit"),
    ],
)
def test_a_cli_exit_during_a_compile_leaves_at_once_with_its_output(state, code, out):
    import subprocess
    import sys

    from tests.conftest import REPO

    env = {**os.environ, "PYTHONPATH": str(REPO)}
    result = subprocess.run(
        [sys.executable, "-c", EXIT_WHILE_COMPILING, state],
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert (result.returncode, result.stdout) == (code, out), result.stderr


@pytest.mark.slow
def test_a_real_warm_up_process_compiles_a_kind_and_marks_it(tmp_path, monkeypatch):
    """:func:`warmup.child_main` in a child process, into an empty kernel cache."""
    from planar_tui.progress import Progress

    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))  # the child's cache
    monkeypatch.setattr(warmup, "missing", lambda names: list(names))
    details: list[str] = []
    done = warmup.warm_kernels_in_processes(
        ["torques"], Progress(on_update=lambda state: details.append(state.detail))
    )
    assert done == ["torques"]
    child_cache = tmp_path / f"planar-tui-{runtime.kernel_source_digest()}"
    assert (child_cache / warmup.marker("torques").name).exists()
    assert any(child_cache.rglob("*.nbi"))  # numba's index files: kernels compiled there
    assert details[-1] == "torques kernels ready"


def test_the_schedule_is_longest_first_and_balanced(monkeypatch):
    """Longest processing time first: 7, 5, 4, 3, 1 on two processes is 7 + 3 against
    5 + 4 + 1 (worked by hand); a chain stays whole and in order in one process."""
    from planar_tui import warmup_schedule

    costs = {"a": 7.0, "b": 5.0, "c": 4.0, "d": 3.0, "e": 1.0}
    monkeypatch.setattr(warmup_schedule, "UNIT_COST_S", costs)
    monkeypatch.setattr(warmup_schedule, "SHARES", {})
    assert warmup.schedule(["e", "c", "a", "d", "b"], 2) == [["a", "d"], ["b", "c", "e"]]
    assert warmup.schedule(["e", "c"], 4) == [["c"], ["e"]]  # no idle process
    assert warmup.schedule(["e", "c", "a"], 1) == [["a", "c", "e"]]
    # d shares a's kernels: after a, in a's process, the chain a + d (10) placed first
    monkeypatch.setattr(warmup_schedule, "SHARES", {"d": "a", "e": "d"})
    assert warmup.schedule(["e", "d", "c", "b", "a"], 2) == [["a", "d", "e"], ["b", "c"]]
    # the unit it shares with not to be compiled: d goes alone
    assert warmup.schedule(["d", "b"], 2) == [["b"], ["d"]]


def test_every_unit_is_scheduled_once_balanced_and_shared_kernels_compile_once():
    """The declared costs and shares of the real units, on two processes: every unit once,
    each after the unit it shares kernels with and in the same process, the two processes'
    estimates within the longest chain of each other (list scheduling's bound)."""
    from planar_tui.registry import JOB_KINDS
    from planar_tui.warmup_schedule import SHARES, UNIT_COST_S, chains, cost_s

    every = [unit for kind in JOB_KINDS for unit in warmup.units(kind)]
    assert set(UNIT_COST_S) == set(every)  # every unit has a measured cost, no stale one
    assert set(SHARES) | set(SHARES.values()) <= set(every)
    shares = warmup.schedule(every, 2)
    assert sorted(u for units in shares for u in units) == sorted(every)
    for units in shares:
        for unit in units:
            if unit in SHARES:
                assert SHARES[unit] in units[: units.index(unit)]
    longest = max(cost_s(chain) for chain in chains(every))
    assert abs(cost_s(shares[0]) - cost_s(shares[1])) <= longest
    for units in shares:  # each process's chains longest first
        own = [chain for chain in chains(every) if chain[0] in units]
        order = sorted(own, key=lambda chain: units.index(chain[0]))
        assert [cost_s(c) for c in order] == sorted(map(cost_s, order), reverse=True)


def test_a_process_reports_each_unit_ready_as_it_is_done(monkeypatch):
    """Two units in one process: the first is ready while the second still compiles."""
    from planar_tui.progress import Progress

    code = (
        "import sys, time; print('unit simulate', flush=True); "
        "print('kernel rk4_step', flush=True); print('ready simulate', flush=True); "
        "print('unit torques', flush=True); print('kernel tau_rows', flush=True); time.sleep(2)"
    )
    fake_children(monkeypatch, code)
    details: list[str] = []
    progress = Progress(on_update=lambda state: details.append(state.detail))
    warmup.warm_kernels_in_processes(["simulate", "torques"], progress, processes=1)
    ready = details.index("simulate kernels ready")
    assert "torques: tau_rows" in details[ready:]  # still compiling, the unit named
    assert details[-1] == "torques kernels ready"


#: Runs each warm-up unit's example (the arguments) in this process and prints one line per
#: unit, ``UNIT: KERNEL...``, the kernels numba compiled for it (``numba:compile`` fires on a
#: cache miss only).
RUN_EXAMPLES_COUNTING_COMPILES = """
import sys
from numba.core import event
from planar_tui import warmup
from planar_tui.runtime import prepare_kernels

compiled = []

class Listener(event.Listener):
    def on_start(self, ev):
        compiled.append(getattr(ev.data.get("dispatcher"), "__name__", "?"))

    def on_end(self, ev):
        pass

prepare_kernels()
warmup.marker = lambda unit: prepare_kernels() / f"probe-{unit}"  # each example runs again
with event.install_listener("numba:compile", Listener()):
    for unit in sys.argv[1:]:
        compiled.clear()
        warmup._run_example(unit)
        print(unit + ":", *(name for name in compiled if name != "impl"))
"""


def warm_then_run_examples(
    cache, units: list[str], then: list[str] | None = None
) -> dict[str, list[str]]:
    """``planar-tui warmup``'s processes compile ``units`` into the empty kernel cache
    ``cache``; then a fresh process runs the examples of ``then`` (default ``units``)
    there: the kernels each had to compile."""
    import subprocess
    import sys

    from planar_tui.progress import Progress
    from tests.conftest import REPO

    done = warmup.warm_kernels_in_processes(units, Progress(), processes=2)
    assert sorted(done) == sorted(units)
    env = {**os.environ, "PYTHONPATH": str(REPO), "NUMBA_CACHE_DIR": str(cache)}
    result = subprocess.run(
        [sys.executable, "-c", RUN_EXAMPLES_COUNTING_COMPILES, *(then or units)],
        env=env,
        capture_output=True,
        text=True,
        timeout=1800,
    )
    assert result.returncode == 0, result.stderr
    lines = [line.split() for line in result.stdout.splitlines()]
    return {line[0].removesuffix(":"): line[1:] for line in lines}


@pytest.mark.slow  # every kind's kernels compiled: minutes of CPU
def test_after_a_warmup_every_kinds_example_runs_without_compiling(tmp_path, monkeypatch):
    """Whatever the schedule shares out (and leaves out as compiled by another unit),
    every unit's example then finds all of its kernels in the cache."""
    from planar_tui.registry import JOB_KINDS

    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    monkeypatch.setattr(warmup, "missing", lambda names: list(names))
    every = [unit for kind in JOB_KINDS for unit in warmup.units(kind)]
    assert warm_then_run_examples(tmp_path, every) == {unit: [] for unit in every}


@pytest.mark.slow
def test_a_2_link_motion_job_compiles_no_fused_step(tmp_path, monkeypatch):
    """The motion job's general part (a 2-link chain) leaves the fused 6-link step
    uncompiled; the torques example run after it compiles its own kernels (the probe sees
    a cache miss), the general part's example none (:func:`warm_then_run_examples`)."""
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    monkeypatch.setattr(warmup, "missing", lambda names: list(names))
    general = ["motion_uncertainty:general"]
    compiles = warm_then_run_examples(tmp_path, general, [*general, "torques"])
    assert compiles["motion_uncertainty:general"] == []
    assert compiles["torques"]
    compiled = " ".join(p.name for p in tmp_path.rglob("*.nbi"))
    assert "rk4_lanes_general" in compiled
    assert "rk4_step_6" not in compiled and "rk4_lanes-" not in compiled

"""Sweeps on Dask: a 2-process local cluster (started and shut down here, one thread per
worker) gives the in-process result in every column but the timings, also when a worker
process is killed mid-sweep (Dask reschedules its points on the replacement)."""

from __future__ import annotations

import os
import signal
import time
from pathlib import Path

import pytest

from planar_tui.presets import load_preset
from planar_tui.sweep.service import run_sweep
from planar_tui.sweep.spec import parse_sweeps
from tests.sweep_presets import SENSITIVITY, WORKSPACE, WORKSPACE_BASE, write

pytestmark = pytest.mark.slow  # end to end (see pyproject.toml's markers)


@pytest.fixture(scope="module")
def cluster():
    from distributed import Client

    from planar_tui.sweep.execute import local_cluster

    with local_cluster(2) as local, Client(local) as client:
        client.wait_for_workers(2, timeout=600)
        yield local, client


def without_seconds(table):
    assert table.header[-1] == "seconds"
    return table.header[:-1], [tuple(row[:-1]) for row in table.rows]


def sweep_of(tmp_path, template, body, **values):
    (sweep,) = parse_sweeps(load_preset(write(tmp_path, "p.toml", template, body, **values)))
    return sweep


def test_two_worker_processes_give_the_in_process_result(tmp_path, cluster):
    local, _ = cluster
    workspace = sweep_of(
        tmp_path,
        WORKSPACE,
        """[[sweep]]
job = "workspace"
values.orientation_deg = [-20, 0, 20]
values.precision_cm = [1.0, 0.5]
""",
        **WORKSPACE_BASE,
    )
    sensitivity = sweep_of(
        tmp_path,
        SENSITIVITY,
        """[[sweep]]
job = "sensitivity"
values.tolerance_mass_g = [1, 10, 100]
""",
        mass_g=1,
    )
    for sweep in (workspace, sensitivity):
        alone = run_sweep(sweep, workers=1)
        spread = run_sweep(sweep, scheduler=local.scheduler_address)
        assert without_seconds(spread.table) == without_seconds(alone.table)
        assert spread.failed == 0 and len(spread.table.rows) == sweep.point_count
    # the sensitivity figures are there: per torque a dominant parameter and the shares
    header = list(alone.table.header)
    assert {"tau1_dominant", "tau2_masses_percent", "tau1_sobol_halfwidth_max"} <= set(header)


def test_a_worker_killed_mid_sweep_is_replaced_and_the_result_is_unchanged(tmp_path, cluster):
    local, client = cluster
    sweep = sweep_of(
        tmp_path,
        WORKSPACE,
        """[[sweep]]
job = "workspace"
values.orientation_deg = [-15, -10, -5, 0, 5, 10, 15]
values.precision_cm = [0.3, 0.25]
""",
        **WORKSPACE_BASE,
    )
    alone = run_sweep(sweep, workers=1)
    pids = client.run(os.getpid)  # worker address -> process id
    killed: list[tuple[int, int]] = []  # (pid, tasks it was processing)

    def kill_once(outcome) -> None:
        if killed:
            return
        busy = {address: len(keys) for address, keys in client.processing().items()}
        address = max(busy, key=busy.get)
        killed.append((pids[address], busy[address]))
        os.kill(pids[address], signal.SIGKILL)

    spread = run_sweep(sweep, scheduler=local.scheduler_address, on_outcome=kill_once)
    ((victim, in_flight),) = killed
    assert in_flight >= 1  # it died holding points, which were run again elsewhere
    assert without_seconds(spread.table) == without_seconds(alone.table)
    client.wait_for_workers(2, timeout=600)
    after = set(client.run(os.getpid).values())
    assert victim not in after and len(after) == 2  # the nanny started a new process


def _kernel_threads() -> int:
    import numba

    return numba.get_num_threads()


def test_local_workers_share_the_cores_among_their_kernels(cluster):
    """Each worker process's Numba kernels get the machine's cores divided among the
    workers (2 workers on 2 cores: one thread each), not every core each."""
    from planar_tui.sweep.execute import default_workers

    _, client = cluster
    client.wait_for_workers(2, timeout=600)  # a worker killed by a test before is replaced
    threads = client.run(_kernel_threads)
    assert sorted(threads.values()) == [max(1, default_workers() // 2)] * 2


def _worker_settings(dask_worker) -> tuple:
    import dask

    return (
        dask_worker._tick_interval,
        dask.config.get("distributed.worker.profile.enabled"),
        dask.config.get("distributed.worker.memory.monitor-interval"),
    )


def test_local_cluster_processes_keep_their_housekeeping_to_once_a_second(cluster):
    """Dask's idle housekeeping (event-loop tick every 20 ms, profiler every 10 ms, memory
    check every 0.1 s) is turned down in the scheduler and in every worker, also in one a
    nanny starts again after a crash: ticks once a second, no profiler."""
    _, client = cluster
    assert client.run_on_scheduler(lambda dask_scheduler: dask_scheduler._tick_interval) == 1.0
    address, victim = next(iter(client.run(os.getpid).items()))
    os.kill(victim, signal.SIGKILL)
    deadline = time.monotonic() + 600
    while address in (workers := client.scheduler_info()["workers"]) or len(workers) < 2:
        assert time.monotonic() < deadline, "the nanny did not start a new worker"
        time.sleep(0.05)
    assert victim not in client.run(os.getpid).values()
    settings = client.run(_worker_settings)
    assert len(settings) == 2
    assert set(settings.values()) == {(1.0, False, "1s")}


def test_the_printed_dashboard_address_serves_the_dashboard(cluster):
    """The address the CLI prints (``cluster.dashboard_link``) answers with the dashboard:
    bokeh, a dependency, serves it (without bokeh the scheduler serves no page there)."""
    import urllib.request

    local, _ = cluster
    with urllib.request.urlopen(local.dashboard_link, timeout=300) as response:
        page = response.read().decode()
    assert response.status == 200
    assert "needs bokeh" not in page  # what the scheduler serves when bokeh is missing
    assert "<html" in page.lower() and "Dask" in page


def _descendants(pid: int) -> set[int]:
    """Every live process below ``pid`` (Linux: /proc/PID/task/TID/children)."""
    found, todo = set(), [pid]
    while todo:
        parent = todo.pop()
        for task in Path(f"/proc/{parent}/task").glob("*"):
            try:
                children = {int(c) for c in (task / "children").read_text().split()}
            except OSError:  # gone meanwhile
                continue
            todo += sorted(children - found)
            found |= children
    return found


def _running(pid: int) -> bool:
    """Whether ``pid`` is a process that has not exited (a zombie has)."""
    try:
        status = Path(f"/proc/{pid}/status").read_text()
    except OSError:
        return False
    return "\nState:\tZ" not in status and "\nState:\tX" not in status


@pytest.mark.parametrize(
    ("delay_s", "whole_group"), [(0.0, False), (0.3, False), (0.0, True), (0.5, True)]
)
def test_ctrl_c_while_the_local_cluster_starts_prints_one_line_and_leaves_no_process(
    tmp_path, delay_s, whole_group
):
    """SIGINT from the moment the first worker process of ``--workers 2`` appears (the
    cluster is starting, ~0.5 s before it is up): exit 130, the one ``interrupted:`` line
    (Dask's exit hook once failed on the half-started cluster: 28 more lines), and every
    process the run started has exited. ``whole_group``: to every process of the run, as
    a terminal's Ctrl-C is (the starting workers once printed their KeyboardInterrupt
    tracebacks from Dask's comm)."""
    from planar_tui.errors import ExitCode
    from tests.test_signals import start

    preset = write(
        tmp_path,
        "p.toml",
        WORKSPACE,
        """[[sweep]]
job = "workspace"
values.orientation_deg = { from = -20, to = 20, count = 20 }
output = "a.csv"
""",
        **{**WORKSPACE_BASE, "precision_cm": 0.05},
    )
    process = start(
        "sweep",
        str(preset),
        "--workers",
        "2",
        "--out-dir",
        str(tmp_path / "out"),
        own_group=whole_group,
    )
    deadline = time.monotonic() + 600
    while not (started := _descendants(process.pid)):
        assert process.poll() is None, process.communicate()
        assert time.monotonic() < deadline, "no worker process appeared"
        time.sleep(0.002)
    until = time.monotonic() + delay_s
    while time.monotonic() < until:
        started |= _descendants(process.pid)
        time.sleep(0.005)
    if whole_group:
        os.killpg(process.pid, signal.SIGINT)
    else:
        process.send_signal(signal.SIGINT)
    _, err = process.communicate(timeout=600)
    assert process.returncode == ExitCode.INTERRUPTED == 130, err
    lines = [line for line in err.splitlines() if not line.startswith(("dask:", "p:sweep[1]"))]
    assert lines == [
        "interrupted: finished points are in the sweeps' checkpoints (--resume finishes "
        "them); the running sweep's CSV was not written"
    ], err
    assert "Traceback" not in err and "Exception ignored" not in err
    deadline = time.monotonic() + 10
    while any(_running(pid) for pid in started):
        assert time.monotonic() < deadline, [pid for pid in started if _running(pid)]
        time.sleep(0.05)

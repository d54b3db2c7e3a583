"""Benchmark of the app's live workspace preview: ``python benchmarks/bench_app.py``.

Goal: a coarse map redrawn within a second of each valid edit of a 3-RRR's geometry or
joint limits. The app runs headless (``App.run_test``, as the Pilot tests do) on the
bundled ``presets/paper-b-table3.toml`` with its Workspace tab shown. Each edit puts a new
valid value into a field (what the keystroke that completes the value does: the field's
``Input.Changed``) and times, from there, until the preview map of that value is drawn:
``N`` edits of the joint limits (Workspace tab) and ``N`` of the distal link length
(Robot tab), median and max of each. Baseline in the same process: the preview's paving
called directly (no app), wall and CPU seconds, on every core and on one thread (as the
app paves it). The 1-min load (``os.getloadavg``) is
printed before and after (the machine is shared).

Screen changes (each within 1 s at load 8): ``--screens`` times, headless at
120×40 as the Pilot tests drive the app, from the key's action until the app is idle
again (every message handled, the screen laid out and drawn: ``pilot.pause()``):
opening a preset into the running app (``ctrl+o``'s :meth:`open_preset`, each bundled
preset of :data:`SCREEN_PRESETS` in turn), hiding and showing the form (``ctrl+f``), and
the first and a later visit of every tab; wall and CPU seconds of the process (the CPU
time a loaded machine inflates far less). ``--against COMMIT`` runs the screen changes
in ``--processes N`` fresh processes a side (default 2), this checkout's and COMMIT's
(a ``git worktree`` of it, as ``bench_startup.py --against`` makes) alternating, so both
see the same load, and adds their medians and the CPU ratio. ``--preview`` runs the
preview figures above alone; without either option both run.

Options: ``--edits N`` (default 5), ``--rounds N`` (screen changes, default 3).
"""

from __future__ import annotations

import argparse
import asyncio
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

PRESET = REPO / "presets" / "paper-b-table3.toml"
#: The bound on one wait: it only catches a hang.
HANG_S = 300.0


def limits_text(k: int) -> tuple[str, tuple]:
    """The ``k``-th edit of the joint limits: the preset's widened by ``k`` degrees."""
    limits = ((20 - k, 70 + k), (110 - k, 160 + k), (245 - k, 295 + k))
    return str([list(pair) for pair in limits]), limits


async def drawn(pilot, pane, predicate) -> float:
    """Wait until the pane shows a preview whose job satisfies ``predicate``; the moment."""
    deadline = time.monotonic() + HANG_S
    while True:
        job = pane._shown_job
        if job is not None and "preview" in pane.explorer().note and predicate(job):
            return time.perf_counter()
        if time.monotonic() > deadline:
            raise TimeoutError("no preview drawn")
        await pilot.pause(0.01)


async def app_latencies(edits: int) -> dict[str, list[float]]:
    """Seconds from each valid edit to its preview drawn, per edited field."""
    from planar_tui.app.app import WorkbenchApp
    from planar_tui.app.workbench import Workbench

    seconds: dict[str, list[float]] = {"joint limits": [], "distal_cm": []}
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / PRESET.name
        shutil.copy(PRESET, path)
        app = WorkbenchApp(Workbench.open(path), output_dir=Path(folder))
        async with app.run_test(size=(120, 40)) as pilot:
            app.action_show_tab("workspace")
            await pilot.pause()
            pane = app.query_one("#pane-workspace")
            field: Any = pane.query_one("#field-joint_limits_deg")
            # warm-up: the first edit loads the paving's modules and cached kernels
            for k in range(edits + 1):
                text, limits = limits_text(k + 1)
                start = time.perf_counter()
                field.value = text
                end = await drawn(pilot, pane, lambda job, t=limits: job.spec.joint_limits_deg == t)
                if k:
                    seconds["joint limits"].append(end - start)
            distal: Any = app.query_one("#pane-robot #form-robot3rrr #field-distal_cm")
            for k in range(edits):
                length_cm = 30.0 + 0.25 * (k + 1)
                start = time.perf_counter()
                distal.value = f"{length_cm:g}"
                end = await drawn(pilot, pane, lambda job, d=length_cm: job.robot.distal_cm == d)
                seconds["distal_cm"].append(end - start)
    return seconds


def paving_alone(edits: int, threads: int | None) -> tuple[list[float], list[float], int]:
    """Wall and CPU seconds of the preview's paving called directly (no app) on ``threads``
    threads (``None``: every core), box count."""
    from planar_tui.app.widgets.workspace_pane import pave, preview_job
    from planar_tui.presets import load_preset

    job = next(job for job in load_preset(PRESET).jobs if job.kind == "workspace")
    wall, cpu, boxes = [], [], 0
    for k in range(edits + 1):
        _, limits = limits_text(k + 1)
        edited = preview_job(_with_limits(job, limits))
        start_wall, start_cpu = time.perf_counter(), time.process_time()
        outcome = pave(edited, lambda: False, threads)
        if k:  # the first call loads the modules and kernels
            wall.append(time.perf_counter() - start_wall)
            cpu.append(time.process_time() - start_cpu)
        boxes = len(outcome.boxes)
    return wall, cpu, boxes


def _with_limits(job, limits):
    import dataclasses

    spec = dataclasses.replace(job.spec, joint_limits_deg=limits)
    return dataclasses.replace(job, spec=spec)


def row(name: str, values: list[float]) -> str:
    return f"{name:<40} {statistics.median(values):>9.3f} {max(values):>9.3f}"


#: The presets opened in turn by ``--screens`` (a 3-RRR workspace job, a 6R's three
#: kinds, a sweep preset).
SCREEN_PRESETS = ("paper-b-table3.toml", "paper-a-table1.toml", "sweep-3rrr-design.toml")


async def settled(pilot, action) -> tuple[float, float]:
    """Wall and CPU seconds from calling ``action()`` (awaited when it is a coroutine)
    until the app is idle again (``pilot.pause()``: every pending message handled and the
    screen drawn)."""
    start, start_cpu = time.perf_counter(), time.process_time()
    outcome = action()
    if asyncio.iscoroutine(outcome):
        await outcome
    await pilot.pause()
    return time.perf_counter() - start, time.process_time() - start_cpu


async def screen_changes(rounds: int) -> dict[str, list[tuple[float, float]]]:
    """(wall s, CPU s) of each screen change, by name (see the module's docstring)."""
    from planar_tui.app.app import WorkbenchApp
    from planar_tui.app.workbench import Workbench

    seconds: dict[str, list[tuple[float, float]]] = {}

    def keep(name: str, value: tuple[float, float]) -> None:
        seconds.setdefault(name, []).append(value)

    with tempfile.TemporaryDirectory() as folder:
        app = WorkbenchApp(Workbench.open(PRESET), output_dir=Path(folder))
        async with app.run_test(size=(120, 40)) as pilot:
            await pilot.pause()
            tabs = [name for _, name in app.tabs()]
            for round_ in range(rounds):
                for name in tabs:  # the first visit after (re)opening, then a later one
                    keep(
                        "first visit of a tab" if round_ == 0 else "later visit of a tab",
                        await settled(pilot, lambda n=name: app.action_show_tab(n)),
                    )
                app.action_show_tab("workspace")
                await pilot.pause()
                keep("hide the form (ctrl+f)", await settled(pilot, app.action_toggle_form))
                keep("show the form (ctrl+f)", await settled(pilot, app.action_toggle_form))
                for preset in SCREEN_PRESETS:
                    path = str(REPO / "presets" / preset)
                    keep("open a preset", await settled(pilot, lambda p=path: app.open_preset(p)))
                for name in tabs:
                    keep(
                        "first visit after opening",
                        await settled(pilot, lambda n=name: app.action_show_tab(n)),
                    )
    return seconds


def print_screen_changes(seconds: dict[str, list[tuple[float, float]]]) -> None:
    print("screen changes, headless at 120x40 (goal: each within 1 s at load 8)")
    print(f"{'':<32} {'median wall s':>13} {'max wall s':>10} {'median CPU s':>12}  n")
    for name, values in seconds.items():
        wall, cpu = [v[0] for v in values], [v[1] for v in values]
        print(
            f"{name:<32} {statistics.median(wall):>13.3f} {max(wall):>10.3f}"
            f" {statistics.median(cpu):>12.3f}  {len(values)}"
        )


def paired_screen_changes(commit: str, processes: int, rounds: int) -> None:
    """The screen changes of this checkout and of ``commit`` in alternating fresh
    processes (``--json`` children; COMMIT's package imported from its worktree)."""
    from benchmarks.bench_startup import checkout_of

    with tempfile.TemporaryDirectory() as folder:
        other = checkout_of(commit, Path(folder) / "other")
        with other as theirs_folder:
            sides: dict[str, dict[str, list[tuple[float, float]]]] = {"ours": {}, "theirs": {}}
            for _ in range(processes):
                for side, package in (("ours", REPO), ("theirs", theirs_folder)):
                    command = [sys.executable, __file__, "--screens", "--json"]
                    command += ["--rounds", str(rounds), "--package", str(package)]
                    out = subprocess.run(command, check=True, capture_output=True, text=True)
                    for name, values in json.loads(out.stdout.splitlines()[-1]).items():
                        sides[side].setdefault(name, []).extend(map(tuple, values))
    print(f"screen changes, headless at 120x40, {processes} processes a side; theirs: {commit}")
    print(
        f"{'':<28} {'ours wall':>9} {'ours CPU':>8} {'their wall':>10} {'their CPU':>9}"
        f" {'CPU ratio':>9}  n"
    )
    for name, ours in sides["ours"].items():
        theirs = sides["theirs"].get(name, [(float("nan"), float("nan"))])
        medians = [statistics.median(v[i] for v in side) for side in (ours, theirs) for i in (0, 1)]
        print(
            f"{name:<28} {medians[0]:>9.3f} {medians[1]:>8.3f} {medians[2]:>10.3f}"
            f" {medians[3]:>9.3f} {medians[1] / medians[3]:>9.2f}  {len(ours)}"
        )


def main() -> None:
    # the app's settings and recent files in a folder of their own: the benchmark's
    # toggles and presets opened are not the user's
    private = tempfile.mkdtemp(prefix="bench-app-")
    for name in ("PLANAR_TUI_CONFIG_DIR", "PLANAR_TUI_STATE_DIR"):
        os.environ[name] = private
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--edits", type=int, default=5)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--screens", action="store_true", help="the screen changes only")
    parser.add_argument("--preview", action="store_true", help="the live preview only")
    parser.add_argument("--against", metavar="COMMIT", help="pair the screen changes")
    parser.add_argument("--processes", type=int, default=2, help="with --against, a side")
    parser.add_argument("--json", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--package", help=argparse.SUPPRESS)  # the checkout to import
    args = parser.parse_args()
    if args.package:
        sys.path.insert(0, args.package)
    load_before = os.getloadavg()[0]
    if args.against:
        paired_screen_changes(args.against, args.processes, args.rounds)
    elif args.json:
        print(json.dumps(asyncio.run(screen_changes(args.rounds))))
        return
    elif not args.preview:
        print_screen_changes(asyncio.run(screen_changes(args.rounds)))
    if args.screens or args.against:
        load_after = os.getloadavg()[0]
        print(
            f"1-min load: {load_before:.2f} before, {load_after:.2f} after ({os.cpu_count()} CPUs)"
        )
        return
    every_wall, every_cpu, _ = paving_alone(args.edits, None)
    wall, cpu, boxes = paving_alone(args.edits, 1)
    seconds = asyncio.run(app_latencies(args.edits))
    load_after = os.getloadavg()[0]
    print(f"preview of {PRESET.name}'s workspace job, {args.edits} edits each, {boxes} boxes")
    print(f"{'':<40} {'median s':>9} {'max s':>9}")
    print(row("paving alone, every core, wall", every_wall))
    print(row("paving alone, every core, CPU", every_cpu))
    print(row("paving alone, 1 thread, wall (baseline)", wall))
    print(row("paving alone, 1 thread, CPU", cpu))
    for name, values in seconds.items():
        print(row(f"edit of {name} -> map drawn", values))
        ratio = statistics.median(values) / statistics.median(wall)
        print(f"{'':<40} {ratio:>8.1f}x the paving alone; goal 1 s")
    print(f"1-min load: {load_before:.2f} before, {load_after:.2f} after ({os.cpu_count()} CPUs)")


if __name__ == "__main__":
    main()

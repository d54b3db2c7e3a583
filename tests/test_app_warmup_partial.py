"""The app's side of the core's progress data (issue 14): the workspace map of the boxes
kept so far and the box-estimate warning while a job runs, the last progress snapshot
(and its views of the run's arrays) dropped when a job ends, and the kernels warmed in a
background thread at start."""

from __future__ import annotations

import time

import numpy as np
import pytest

from planar_tui import warmup
from planar_tui.app.app import WorkbenchApp
from planar_tui.app.workbench import Workbench
from planar_tui.progress import ProgressState
from tests.test_app import DATA, SIZE, async_test, make_app, run_tab

pytestmark = pytest.mark.slow  # end to end (see pyproject.toml's markers)


@async_test
async def test_the_map_of_the_boxes_kept_so_far_and_the_estimate_warning(tmp_path):
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        app.action_show_tab("workspace")
        await pilot.pause()
        pane = app.query_one("#pane-workspace")
        boxes = np.array([[30.0 + i, 31.0 + i, 20.0, 21.0] for i in range(10)])
        boxes.flags.writeable = False  # the runner hands out read-only views
        state = ProgressState(
            0.4,
            1.0,
            "bisection",
            "1,234 boxes",
            warning="about 90,000 boxes expected, more than box_budget = 1,000",
            partial={"boxes_cm": boxes, "status": None},
        )
        pane.show_progress(state)
        await pilot.pause()
        screen = app.export_text()
        assert "warning: about 90,000 boxes expected" in screen
        assert "(so far)" in screen
        drawn = str(app.query_one("#workspace-map").render())
        assert "▒" in drawn and "█" not in drawn  # kept, none proved inside yet


@async_test
async def test_the_last_progress_snapshot_is_dropped_when_a_job_ends(tmp_path):
    app = make_app(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        seen = []
        original = app.jobs._store

        def store(state):
            seen.append(state)
            original(state)

        app.jobs._store = store
        await run_tab(app, pilot, "workspace")
        assert any(s.partial.get("boxes_cm") is not None for s in seen)  # views were kept
        assert app.jobs.latest is None  # and are let go with the run


@async_test
async def test_kernels_are_warmed_in_the_background_at_start(tmp_path, monkeypatch):
    """Only the torques kind is 'missing' (its marker redirected to an empty folder, the
    others' to a file that exists): the app compiles it through the real warm-up at start,
    says so twice, and marks it."""
    present = tmp_path / "warm-others"
    present.touch()
    monkeypatch.setattr(
        warmup,
        "marker",
        lambda kind: tmp_path / "warm-torques" if kind == "torques" else present,
    )
    app = WorkbenchApp(Workbench.open(DATA / "tiny.toml"), warm_kernels=True)
    notes = []
    monkeypatch.setattr(app, "notify", lambda message, **kw: notes.append(message))
    async with app.run_test(size=SIZE) as pilot:
        deadline = time.monotonic() + 120
        while not (tmp_path / "warm-torques").exists():
            assert time.monotonic() < deadline, "the warm-up did not finish"
            await pilot.pause(0.1)
        await app.workers.wait_for_complete()
        await pilot.pause()
    assert notes[0].startswith("Compiling the kernels of torques in the background")
    assert notes[-1].startswith("Kernels compiled")


@async_test
async def test_no_warm_up_when_every_kind_is_cached(monkeypatch):
    calls = []
    monkeypatch.setattr(warmup, "missing", lambda kinds: [])
    monkeypatch.setattr(warmup, "warm_kernels", lambda *a: calls.append(a))
    app = WorkbenchApp(Workbench.open(DATA / "tiny.toml"), warm_kernels=True)
    async with app.run_test(size=SIZE) as pilot:
        await app.workers.wait_for_complete()
        await pilot.pause()
    assert calls == []

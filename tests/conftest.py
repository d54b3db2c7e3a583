"""Shared fixtures and helpers: the repository paths, a CLI runner, and a run on 1 and 2
Numba threads."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

import pytest
from hypothesis import settings
from typer.testing import CliRunner

from planar_tui.runtime import prepare_kernels

REPO = Path(__file__).resolve().parent.parent
PRESETS = REPO / "presets"
REFERENCE = REPO / "tests" / "data" / "reference"

# Like every front end, the suite sets numba up before any kernel is imported (the test
# modules import kernels at module level): compiled kernels go to planar-tui's cache.
prepare_kernels()

# Dask's comms give up on a peer silent for 30 s (connect, and an open connection): on a
# machine busy with other work a worker process starting or restarting can take longer, so
# the suite's clusters (and the CLI processes it starts, which inherit the environment)
# wait up to 300 s; these only bound a hang. (`--scheduler`'s own probe has its own
# timeout, PLANAR_TUI_SCHEDULER_TIMEOUT_S, which this does not change.)
os.environ.setdefault("DASK_DISTRIBUTED__COMM__TIMEOUTS__CONNECT", "300s")
os.environ.setdefault("DASK_DISTRIBUTED__COMM__TIMEOUTS__TCP", "300s")

# Hypothesis draws the same examples on every run (derived from each test), so the suite
# passes or fails the same way on every machine; no example database is written (an
# example found once and replayed ever after would make a checkout's results its own).
# ``HYPOTHESIS_PROFILE=explore`` draws fresh random examples, to look for new failures.
settings.register_profile("repeatable", derandomize=True, database=None)
settings.register_profile("explore", database=None)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "repeatable"))


def on_one_and_two_threads(run):
    """``[run(), run()]`` with Numba's kernels on 1, then 2 threads (the setting restored
    after), for the tests that a parallel kernel's result does not depend on the count."""
    import numba

    before = numba.get_num_threads()
    results = []
    try:
        for threads in (1, 2):
            numba.set_num_threads(threads)
            results.append(run())
    finally:
        numba.set_num_threads(before)
    return results


def untracked_files() -> set[str]:
    """The repository's untracked, not ignored files (none when git cannot tell)."""
    listed = subprocess.run(
        ["git", "-C", str(REPO), "ls-files", "--others", "--exclude-standard", "-z"],
        capture_output=True,
        text=True,
    )
    return set(listed.stdout.split("\0")) - {""} if listed.returncode == 0 else set()


@pytest.fixture(scope="session", autouse=True)
def nothing_written_into_the_repository():
    """No test leaves a file in the repository (outputs go to ``tmp_path``)."""
    before = untracked_files()
    yield
    written = untracked_files() - before
    assert not written, f"the tests wrote into the repository: {sorted(written)}"


@pytest.fixture(autouse=True)
def isolated_design_cache(tmp_path_factory, monkeypatch):
    """Every test gets its own empty Sobol'/eFAST design-cache folder
    (``PLANAR_TUI_CACHE_DIR``), so no test reads or writes the user's cache
    (``~/.cache/planar-tui``) and none passes thanks to an entry a previous run left."""
    folder = tmp_path_factory.mktemp("design-cache")
    monkeypatch.setenv("PLANAR_TUI_CACHE_DIR", str(folder))
    return folder


@pytest.fixture(autouse=True)
def isolated_settings(tmp_path_factory, monkeypatch):
    """Every test gets its own empty settings folder (``PLANAR_TUI_CONFIG_DIR``), so no
    app started by a test reads or writes the user's settings."""
    folder = tmp_path_factory.mktemp("settings")
    monkeypatch.setenv("PLANAR_TUI_CONFIG_DIR", str(folder))
    return folder


@pytest.fixture(autouse=True)
def isolated_help_pages(tmp_path_factory, monkeypatch):
    """Every test gets its own empty folder of saved help pages
    (``PLANAR_TUI_HELP_CACHE_DIR``, :mod:`planar_tui.helpcache`): a console script started
    by a test renders its help rather than print a page an earlier test saved, and nothing
    is written in the user's cache."""
    folder = tmp_path_factory.mktemp("help-pages")
    monkeypatch.setenv("PLANAR_TUI_HELP_CACHE_DIR", str(folder))
    return folder


@pytest.fixture
def cli():
    """Invoke ``planar-tui`` in-process; returns click's Result (exit_code, stdout, stderr)."""
    from planar_tui.cli import app

    runner = CliRunner()

    def invoke(*args: str):
        return runner.invoke(app, [str(a) for a in args], catch_exceptions=False)

    return invoke


@pytest.fixture(autouse=True)
def isolated_state_dir(tmp_path_factory, monkeypatch):
    """Every test gets its own app state folder (``PLANAR_TUI_STATE_DIR``: the recent
    files' ``recent.json``), so no test reads or writes the user's."""
    folder = tmp_path_factory.mktemp("state")
    monkeypatch.setenv("PLANAR_TUI_STATE_DIR", str(folder))
    return folder

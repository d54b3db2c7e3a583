"""The compiled-kernel cache is keyed by the kernels' sources, so an edit to one kernel
module can never leave a stale copy of it inside another module's cached kernel."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys

import pytest
from numba import config

from planar_tui.runtime import kernel_cache_folder, kernel_source_digest, kernels_folder
from tests.conftest import REPO

pytestmark = pytest.mark.slow  # end to end (see pyproject.toml's markers)


def test_the_digest_changes_with_any_kernel_module(tmp_path):
    copy = tmp_path / "kernels"
    shutil.copytree(kernels_folder(), copy, ignore=shutil.ignore_patterns("__pycache__"))
    original = kernel_source_digest(copy)
    assert kernel_source_digest(copy) == original == kernel_source_digest()
    dynamics = copy / "dynamics.py"
    dynamics.write_text(dynamics.read_text() + "\n# an edit\n")
    edited = kernel_source_digest(copy)
    assert edited != original
    (copy / "new_kernel.py").write_text("")
    assert kernel_source_digest(copy) not in (original, edited)


def test_numba_caches_into_the_digest_folder(monkeypatch, tmp_path):
    assert str(kernel_cache_folder()) == config.CACHE_DIR
    assert kernel_cache_folder().name.endswith(kernel_source_digest())
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    assert kernel_cache_folder() == tmp_path / f"planar-tui-{kernel_source_digest()}"
    monkeypatch.delenv("NUMBA_CACHE_DIR")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    assert kernel_cache_folder() == tmp_path / "planar-tui" / f"numba-{kernel_source_digest()}"


def test_an_unwritable_cache_folder_falls_back_to_a_temporary_one_said_once(tmp_path):
    """With a home and cache folder that cannot be written (a path under a regular file:
    unwritable even for root, who ignores a read-only folder's mode), a job compiles its
    kernels into a private temporary folder, says so in one line, and writes nothing beside
    the kernels' sources (numba's own fallback)."""
    blocker = tmp_path / "not-a-folder"
    blocker.write_text("")
    temporary = tmp_path / "tmp"
    temporary.mkdir()
    env = {
        key: value
        for key, value in os.environ.items()
        if key not in ("NUMBA_CACHE_DIR", "PLANAR_TUI_CACHE_DIR")
    }
    env |= {
        "HOME": str(blocker / "home"),
        "XDG_CACHE_HOME": str(blocker / "cache"),
        "TMPDIR": str(temporary),
        "PYTHONPATH": str(REPO),
    }
    sources = kernels_folder()
    before = {path for path in sources.rglob("*") if path.is_file()}
    finished = subprocess.run(
        [sys.executable, "-m", "planar_tui", "torques", "paper-a-table1", "--out-dir", tmp_path],
        capture_output=True,
        text=True,
        env=env,
        cwd=tmp_path,
        timeout=300,
    )
    assert finished.returncode == 0, finished.stderr
    warnings = [line for line in finished.stderr.splitlines() if line.startswith("warning:")]
    assert len(warnings) == 1 and "kernel cache" in warnings[0], finished.stderr
    assert {path for path in sources.rglob("*") if path.is_file()} == before
    assert list(temporary.rglob("*.nbi")), "no compiled kernel in the temporary folder"
    assert (tmp_path / "table1-6r-torques.csv").is_file()

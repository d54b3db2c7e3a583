"""The warm-up markers follow numba's own cache keys: a kernel cached for sources at one
path (or with other stamps) is not a kernel cached for these, so a fresh clone warms up
again instead of compiling, uncancellable, inside a job's stage."""

from __future__ import annotations

import os
import shutil

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

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

"""The compiled-kernel cache is keyed by the kernels' sources, so an edit to one kernel
module can never leave a stale copy of it inside another module's cached kernel."""

from __future__ import annotations

import shutil

from numba import config

from planar_tui.runtime import kernel_cache_folder, kernel_source_digest, kernels_folder


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

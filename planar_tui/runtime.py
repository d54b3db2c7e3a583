"""Process set-up shared by every front end, done once and explicitly.

Nothing in :mod:`planar_tui` changes the process when it is imported. The front ends (the
CLI's ``main``, the app, the batch service before it runs a job, the test suite) call:

* :func:`configure_process` when they start: cheap, imports no numerical module. Sets
  ``OMP_WAIT_POLICY=PASSIVE`` unless the user set it: numba's OpenMP workers otherwise spin
  after every parallel region, taking a busy 2-core machine's CPU from the next region,
  the eFAST FFT threads and other processes (``planar-tui run`` Tables 4+5: 2.5 → 1.8 s
  median at load 2).
* :func:`prepare_kernels` before the first kernel module is imported: points numba's
  cache at :func:`kernel_cache_folder` and loads ``numba.np.arraymath`` without its
  import-time ``scipy.linalg`` BLAS probe (0.1-0.25 s of every jitted process).

Cache folders come from one place, :func:`user_cache_folder` (``platformdirs``: XDG on
Linux, ``~/Library/Caches`` on macOS, ``%LOCALAPPDATA%`` on Windows).
"""

from __future__ import annotations

import hashlib
import importlib
import importlib.util
import os
import sys
from pathlib import Path

APP_NAME = "planar-tui"
#: Moves (or, set empty, disables) the Sobol'/eFAST design cache.
DESIGN_CACHE_ENV_VAR = "PLANAR_TUI_CACHE_DIR"

_kernel_cache: Path | None = None


def configure_process() -> None:
    """Environment every planar-tui process runs with (a value the user set wins)."""
    os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")


def user_cache_folder() -> Path:
    """planar-tui's per-user cache folder (not created here)."""
    import platformdirs

    return Path(platformdirs.user_cache_dir(APP_NAME, appauthor=False))


def design_cache_folder() -> Path | None:
    """Folder of the SALib design cache: ``$PLANAR_TUI_CACHE_DIR`` if set (an empty value
    disables the persistent cache: ``None``), else :func:`user_cache_folder`."""
    configured = os.environ.get(DESIGN_CACHE_ENV_VAR)
    if configured is not None:
        return Path(configured).expanduser() if configured.strip() else None
    return user_cache_folder()


def kernels_folder() -> Path:
    """The folder of the ``planar_tui.kernels`` sources (found without importing numba)."""
    spec = importlib.util.find_spec("planar_tui.kernels")
    if spec is None or spec.origin is None:
        raise RuntimeError("planar_tui.kernels is not installed")
    return Path(spec.origin).resolve().parent


def kernel_source_digest(folder: Path | None = None) -> str:
    """A short SHA-256 of every kernel module's name and source text in ``folder``."""
    digest = hashlib.sha256()
    for path in sorted((folder or kernels_folder()).glob("*.py")):
        digest.update(path.name.encode() + b"\0" + path.read_bytes() + b"\0")
    return digest.hexdigest()[:16]


def kernel_cache_folder() -> Path:
    """Where the compiled kernels are cached: one folder per version of the kernels' sources.

    Numba's own cache notices an edit to a kernel's file but not to another module whose
    kernels it calls (a cached ``rk4_integrate`` kept the old forward dynamics it was
    compiled with, measured here), so every change to the kernels starts from an empty
    cache: ``$NUMBA_CACHE_DIR/planar-tui-DIGEST`` if the user set ``NUMBA_CACHE_DIR``, else
    ``user_cache_folder()/numba-DIGEST``. Deleting it is always safe.
    """
    digest = kernel_source_digest()
    if os.environ.get("NUMBA_CACHE_DIR"):
        return Path(os.environ["NUMBA_CACHE_DIR"]) / f"planar-tui-{digest}"
    return user_cache_folder() / f"numba-{digest}"


def _import_arraymath_without_blas_probe() -> None:
    """Import ``numba.np.arraymath`` without its import-time BLAS probe.

    When the first kernel is compiled or loaded from the cache, numba imports
    ``numba.np.arraymath``, which probes for BLAS by importing ``scipy.linalg`` (about
    0.25 s, a third of a warm CLI process here). scipy is a dependency, so BLAS is there;
    the probe is skipped and the real check stays where BLAS is used: numba's
    ``np.dot``/``np.linalg`` code generation calls ``numba.np.linalg.ensure_blas`` itself.
    """
    if "numba.np.arraymath" in sys.modules:
        return
    import numba.np.linalg as numba_linalg

    probe = numba_linalg.ensure_blas
    numba_linalg.ensure_blas = lambda: None
    try:
        importlib.import_module("numba.np.arraymath")  # registers np.dot with BLAS support
    finally:
        numba_linalg.ensure_blas = probe


def prepare_kernels() -> Path:
    """Set numba up for planar-tui's kernels; idempotent; returns the kernel cache folder.

    Must run before the first ``planar_tui.kernels`` module is imported: numba picks a
    kernel's cache folder when the kernel is decorated.
    """
    global _kernel_cache
    if _kernel_cache is not None:
        return _kernel_cache
    early = sorted(
        name
        for name in sys.modules
        if name.startswith("planar_tui.kernels.") and name != "planar_tui.kernels._jit"
    )
    if early:
        raise RuntimeError(f"prepare_kernels() must run before importing {', '.join(early)}")
    configure_process()
    from numba import config

    folder = kernel_cache_folder()
    config.CACHE_DIR = str(folder)
    _import_arraymath_without_blas_probe()
    _kernel_cache = folder
    return folder

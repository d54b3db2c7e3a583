"""The one decorator factory every kernel is compiled with."""

import hashlib
import importlib
import os
import sys
from pathlib import Path

import numba.np.linalg as numba_linalg
from numba import config, njit

# Numba's OpenMP workers spin after every parallel region by default; on a busy 2-core
# machine that spinning takes the CPU from the next region, the eFAST FFT threads and the
# other processes (measured: `planar-tui run` Tables 4+5, median 2.5 s → 1.8 s at load 2).
# libgomp reads this once, when the first parallel kernel starts it; a value set by the
# user wins.
os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")


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
    probe = numba_linalg.ensure_blas
    numba_linalg.ensure_blas = lambda: None
    try:
        importlib.import_module("numba.np.arraymath")  # registers np.dot with BLAS support
    finally:
        numba_linalg.ensure_blas = probe


_import_arraymath_without_blas_probe()


#: The ``kernels`` package folder.
KERNELS_FOLDER = Path(__file__).resolve().parent


def kernel_source_digest(folder: Path = KERNELS_FOLDER) -> str:
    """A short SHA-256 of every kernel module's name and source text in ``folder``."""
    digest = hashlib.sha256()
    for path in sorted(folder.glob("*.py")):
        digest.update(path.name.encode() + b"\0" + path.read_bytes() + b"\0")
    return digest.hexdigest()[:16]


def kernel_cache_folder() -> Path:
    """Where the compiled kernels are cached: one folder per version of the kernels' sources.

    Numba's own cache notices an edit to a kernel's file but not to another module whose
    kernels it calls (a cached ``rk4_integrate`` keeps the old forward dynamics it was
    compiled with, measured here), so every change to ``kernels/`` must start from an empty
    cache: ``$NUMBA_CACHE_DIR/planar-tui-DIGEST`` if the user set ``NUMBA_CACHE_DIR``, else
    ``$XDG_CACHE_HOME/planar-tui/numba-DIGEST`` (``~/.cache`` by default). Deleting it is
    always safe.
    """
    digest = kernel_source_digest()
    if os.environ.get("NUMBA_CACHE_DIR"):
        return Path(os.environ["NUMBA_CACHE_DIR"]) / f"planar-tui-{digest}"
    base = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache")
    return base / "planar-tui" / f"numba-{digest}"


config.CACHE_DIR = str(kernel_cache_folder())


def kernel(function=None, *, parallel: bool = False):
    """Compile ``function`` with ``njit(cache=True, nogil=True, error_model="numpy")``.

    ``parallel=True`` enables ``numba.prange`` loops. Usable bare (``@kernel``) or
    with arguments (``@kernel(parallel=True)``).
    """

    def wrap(f):
        return njit(cache=True, nogil=True, error_model="numpy", parallel=parallel)(f)

    return wrap if function is None else wrap(function)

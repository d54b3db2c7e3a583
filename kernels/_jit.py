"""The one decorator factory every kernel is compiled with."""

import importlib
import os
import sys

import numba.np.linalg as numba_linalg
from numba import njit

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


def kernel(function=None, *, parallel: bool = False):
    """Compile ``function`` with ``njit(cache=True, nogil=True, error_model="numpy")``.

    ``parallel=True`` enables ``numba.prange`` loops. Usable bare (``@kernel``) or
    with arguments (``@kernel(parallel=True)``).
    """

    def wrap(f):
        return njit(cache=True, nogil=True, error_model="numpy", parallel=parallel)(f)

    return wrap if function is None else wrap(function)

"""The one decorator factory every kernel is compiled with."""

import os

from numba import njit

# Numba's OpenMP workers spin after every parallel region by default; on a busy 2-core
# machine that spinning takes the CPU from the next region, the eFAST FFT threads and the
# other processes (measured: `planar-tui run` Tables 4+5, median 2.5 s → 1.8 s at load 2).
# libgomp reads this once, when the first parallel kernel starts it; a value set by the
# user wins.
os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")


def kernel(function=None, *, parallel: bool = False):
    """Compile ``function`` with ``njit(cache=True, nogil=True, error_model="numpy")``.

    ``parallel=True`` enables ``numba.prange`` loops. Usable bare (``@kernel``) or
    with arguments (``@kernel(parallel=True)``).
    """

    def wrap(f):
        return njit(cache=True, nogil=True, error_model="numpy", parallel=parallel)(f)

    return wrap if function is None else wrap(function)

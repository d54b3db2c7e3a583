"""The one decorator factory every kernel is compiled with.

Importing this module changes nothing in the process: where compiled kernels are cached,
the OpenMP wait policy and numba's BLAS probe are set up once, explicitly, by
:func:`planar_tui.runtime.configure_process` where a front end starts.
"""

from numba import njit


def kernel(function=None, *, parallel: bool = False):
    """Compile ``function`` with ``njit(cache=True, nogil=True, error_model="numpy")``.

    ``parallel=True`` enables ``numba.prange`` loops. Usable bare (``@kernel``) or
    with arguments (``@kernel(parallel=True)``).
    """

    def wrap(f):
        return njit(cache=True, nogil=True, error_model="numpy", parallel=parallel)(f)

    return wrap if function is None else wrap(function)

"""The one decorator factory every kernel is compiled with.

Importing this module changes nothing in the process: where compiled kernels are cached,
the OpenMP wait policy and numba's BLAS probe are set up once, explicitly, by
:func:`planar_tui.runtime.configure_process` where a front end starts.
"""

from numba import njit


def kernel(function=None, *, parallel: bool = False, inline: bool = False, fma: bool = False):
    """Compile ``function`` with ``njit(cache=True, nogil=True, error_model="numpy")``.

    ``parallel=True`` enables ``numba.prange`` loops. ``inline=True`` inlines the function's
    body into its callers at numba's level (``inline="always"``): LLVM never inlines one
    numba function into another, so a call inside a loop (e.g. the vector ``sincos`` of
    :mod:`kernels.lane_trig`) otherwise stays a call and keeps the loop scalar. ``fma=True``
    lets LLVM contract ``a * b + c`` into one fused multiply-add (``fastmath={"contract"}``,
    nothing else of fast-math): one rounding instead of two, so results move in the last
    bits; for a kernel tested against a reference to a tolerance. Usable bare
    (``@kernel``) or with arguments (``@kernel(parallel=True)``).
    """

    def wrap(f):
        return njit(
            cache=True,
            nogil=True,
            error_model="numpy",
            parallel=parallel,
            inline="always" if inline else "never",
            fastmath={"contract"} if fma else False,
        )(f)

    return wrap if function is None else wrap(function)

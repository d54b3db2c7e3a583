"""Numba kernels of planar-tui: pure array code, no I/O, no Textual.

Every public kernel is compiled with :func:`kernels._jit.kernel` (``njit(cache=True,
nogil=True)``) so a second process reuses the machine code and a thread worker of the
TUI releases the GIL while a kernel runs. Only ``numpy`` and ``numba`` are imported here.
"""

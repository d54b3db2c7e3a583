"""Numba kernels of planar-tui: pure array code, no I/O, no Textual.

Installed as ``planar_tui.kernels`` (the repository keeps them in ``kernels/``; see
``pyproject.toml``'s package-dir mapping). Every public kernel is compiled with
:func:`planar_tui.kernels._jit.kernel` (``njit(cache=True, nogil=True)``) so a second
process reuses the machine code and a thread worker of the TUI releases the GIL while a
kernel runs. Only ``numpy`` and ``numba`` are imported here, and nothing of the package
above; call :func:`planar_tui.runtime.configure_process` before the first kernel is
imported to put the compiled kernels in planar-tui's own cache folder.
"""

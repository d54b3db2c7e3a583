"""Which device integrates the robots: ``cpu``, ``cuda`` (a usable GPU, else an error) or
``auto`` (the GPU when one is usable, else the CPU, saying which)."""

from __future__ import annotations

from planar_tui.runtime import prepare_kernels

DEVICES = ("cpu", "cuda", "auto")
#: How to get the GPU path.
CUDA_HINT = "pip install 'planar-tui[cuda]' on a machine with an NVIDIA GPU"


def cuda_problem() -> str | None:
    """``None`` when the CUDA kernel can run here, else why not (one line): numba-cuda
    missing, no driver, no GPU. ``NUMBA_ENABLE_CUDASIM=1`` (numba's simulator) counts as
    usable."""
    prepare_kernels()  # before the first kernel module is imported
    try:
        from planar_tui.kernels import motion_cuda
    except ImportError as error:
        return f"numba's CUDA target cannot be imported ({error}); {CUDA_HINT}"
    return motion_cuda.usable()


def resolve(requested: str) -> tuple[str | None, str]:
    """``(device, note)``: the device that will run (``None``: ``cuda`` was asked for and
    cannot run; ``note`` says why) and a note for the summary (``cpu (no usable CUDA GPU
    ...)`` for ``auto`` falling back)."""
    if requested == "cpu":
        return "cpu", "cpu"
    problem = cuda_problem()
    if problem is None:
        return "cuda", "cuda"
    if requested == "cuda":
        return None, problem
    return "cpu", f"cpu ({problem})"

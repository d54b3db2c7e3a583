"""Persistent cache of SALib's unit-hypercube designs (``.npy`` files, written atomically).

SALib draws a design once per (method, D, N, seed, M, ``calc_second_order``) and the
versions of SALib, SciPy and NumPy (the design comes from ``scipy.stats.qmc.Sobol`` or
NumPy's generators through SALib): later runs read the same bytes back instead of importing
SALib (pandas, ``scipy.stats``: ~1.3 s) and re-running its Python-loop sampler. SALib stays
the sampler; results never depend on the cache (a cache hit is byte-identical to a fresh
draw, see ``tests/test_sensitivity_design_cache.py``).

Folder: :func:`planar_tui.runtime.design_cache_folder` (``$PLANAR_TUI_CACHE_DIR`` if set,
an empty value disabling the persistent cache; else planar-tui's user cache folder). A file is named by its key and the CRC-32 of its
data, ``KEY.CRC.npy``; an entry that cannot be read, has the wrong shape or dtype, or fails
its CRC is deleted and drawn again. Writes go to a temporary file renamed into place, so
concurrent runs and interrupted writes never leave a partial entry; an unwritable folder
only costs the speed-up.
"""

from __future__ import annotations

import contextlib
import os
import tempfile
import zlib
from collections.abc import Callable
from pathlib import Path

import numpy as np

from planar_tui.runtime import DESIGN_CACHE_ENV_VAR, design_cache_folder

ENV_VAR = DESIGN_CACHE_ENV_VAR
#: Bump when the file layout or key changes.
FORMAT = 1


def cache_dir() -> Path | None:
    """The cache folder (not created here), or None when disabled (``PLANAR_TUI_CACHE_DIR=""``)."""
    return design_cache_folder()


_VERSIONS: str | None = None


def sampler_versions() -> str:
    """``SALib-x_scipy-y_numpy-z`` from the installed distributions' metadata (no import)."""
    global _VERSIONS
    if _VERSIONS is None:
        from importlib.metadata import version

        _VERSIONS = "_".join(f"{name}-{version(name)}" for name in ("SALib", "scipy", "numpy"))
    return _VERSIONS


def design_key(method: str, num_vars: int, samples: int, seed: int, m_harmonics: int) -> str:
    """File-name key of one design: every argument the design depends on."""
    options = "so0" if method == "sobol" else f"M{m_harmonics}"  # calc_second_order=False
    return f"v{FORMAT}_{method}_D{num_vars}_N{samples}_seed{seed}_{options}_{sampler_versions()}"


def _crc(array: np.ndarray) -> str:
    return f"{zlib.crc32(array.data.cast('B')):08x}"


def _read(folder: Path, key: str, shape: tuple[int, int]) -> np.ndarray | None:
    """A valid cached design, or None; invalid entries are deleted."""
    for path in folder.glob(f"{key}.{'[0-9a-f]' * 8}.npy"):
        try:
            design = np.load(path, allow_pickle=False)
            valid = (
                design.shape == shape
                and design.dtype == np.float64
                and design.flags.c_contiguous
                and path.name == f"{key}.{_crc(design)}.npy"
            )
        except (OSError, ValueError, EOFError):
            valid = False
        if valid:
            return design
        with contextlib.suppress(OSError):  # read-only folder: ignored, drawn again
            path.unlink(missing_ok=True)
    return None


def _write(folder: Path, key: str, design: np.ndarray) -> None:
    """Save ``design`` atomically; errors (read-only folder, full disk) are ignored."""
    try:
        folder.mkdir(parents=True, exist_ok=True)
        handle, temp_name = tempfile.mkstemp(prefix=f".{key}.", suffix=".tmp", dir=folder)
        try:
            with os.fdopen(handle, "wb") as stream:
                np.save(stream, design, allow_pickle=False)
            os.replace(temp_name, folder / f"{key}.{_crc(design)}.npy")
        except BaseException:
            Path(temp_name).unlink(missing_ok=True)
            raise
    except OSError:
        pass


def cached_design(key: str, shape: tuple[int, int], draw: Callable[[], np.ndarray]) -> np.ndarray:
    """The design stored under ``key`` (of ``shape``), drawing and storing it on a miss."""
    folder = cache_dir()
    design = _read(folder, key, shape) if folder is not None and folder.is_dir() else None
    if design is None:
        design = np.ascontiguousarray(draw(), dtype=np.float64)
        if design.shape != shape:
            raise ValueError(f"design of shape {design.shape}, expected {shape}")
        if folder is not None:
            _write(folder, key, design)
    return design

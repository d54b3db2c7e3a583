"""Process set-up shared by every front end, done once and explicitly.

Nothing in :mod:`planar_tui` changes the process when it is imported. The front ends (the
CLI's ``main``, the app, the batch service before it runs a job, the test suite) call:

* :func:`configure_process` when they start: cheap, imports no numerical module. Sets
  ``OMP_WAIT_POLICY=PASSIVE`` unless the user set it: numba's OpenMP workers otherwise spin
  after every parallel region, taking a busy 2-core machine's CPU from the next region,
  the eFAST FFT threads and other processes (``planar-tui run`` Tables 4+5: 2.5 → 1.8 s
  median at load 2). Sets ``OPENBLAS_NUM_THREADS=1`` unless the user set it (read by
  numpy's OpenBLAS when numpy is first imported, so before that): the kernels run their
  own parallel loops, and OpenBLAS's second thread on a busy 2-core machine waits for a
  core between every one of the many small products of a PCE fit (a path study's PCE
  analysis, 3 009 outputs: 66 s wall, 20 s CPU with two threads against 10 s and 2.8 s
  with one, at load 11).
* :func:`prepare_kernels` before the first kernel module is imported: points numba's
  cache at :func:`kernel_cache_folder` (or, when that cannot be written, a private
  temporary folder, said once on stderr) and loads ``numba.np.arraymath`` without its
  import-time ``scipy.linalg`` BLAS probe (0.1-0.25 s of every jitted process).

Cache folders come from one place, :func:`user_cache_folder` (``platformdirs``: XDG on
Linux, ``~/Library/Caches`` on macOS, ``%LOCALAPPDATA%`` on Windows).
"""

from __future__ import annotations

import gc
import hashlib
import importlib
import importlib.util
import os
import stat
import sys
import tempfile
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

APP_NAME = "planar-tui"
#: Moves (or, set empty, disables) the Sobol'/eFAST design cache.
DESIGN_CACHE_ENV_VAR = "PLANAR_TUI_CACHE_DIR"

_kernel_cache: Path | None = None


def configure_process() -> None:
    """Environment every planar-tui process runs with (a value the user set wins)."""
    os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")


def user_cache_folder() -> Path:
    """planar-tui's per-user cache folder (not created here)."""
    import platformdirs

    return Path(platformdirs.user_cache_dir(APP_NAME, appauthor=False))


#: How many :func:`design_cache_suspended` blocks are running (in any thread).
_design_cache_suspensions = 0
_suspensions_lock = threading.Lock()


@contextmanager
def design_cache_suspended() -> Iterator[None]:
    """No design-cache folder while the block runs, in every thread: the warm-up's example
    jobs compile kernels and leave nothing in the user's design cache (a job that runs
    meanwhile draws its designs afresh, the same numbers)."""
    global _design_cache_suspensions
    with _suspensions_lock:
        _design_cache_suspensions += 1
    try:
        yield
    finally:
        with _suspensions_lock:
            _design_cache_suspensions -= 1


def design_cache_folder() -> Path | None:
    """Folder of the SALib design cache: ``$PLANAR_TUI_CACHE_DIR`` if set (an empty value
    disables the persistent cache: ``None``), else :func:`user_cache_folder`; ``None``
    while a :func:`design_cache_suspended` block runs."""
    if _design_cache_suspensions:
        return None
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


def cache_folder_problem(folder: Path) -> str | None:
    """Why ``folder`` cannot hold a cache (created here if missing), or ``None`` if a file
    can be created in it."""
    try:
        folder.mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryFile(dir=folder):
            pass
    except OSError as error:
        return error.strerror or str(error)
    return None


def _private_folder(folder: Path) -> bool:
    """Whether ``folder`` exists (or was just created) as a real folder of this user that
    no one else can write: a shared temporary folder must not feed us someone's kernels."""
    try:
        folder.mkdir(mode=0o700, exist_ok=True)
        info = folder.lstat()
    except OSError:
        return False
    mine = not hasattr(os, "getuid") or info.st_uid == os.getuid()
    return stat.S_ISDIR(info.st_mode) and mine and not info.st_mode & 0o022


def fallback_kernel_cache_folder(name: str) -> Path:
    """A temporary kernel cache: ``TMPDIR/planar-tui-USER/NAME`` when that folder is this
    user's alone (so later runs reuse it), else a new private folder for this process."""
    user = str(os.getuid()) if hasattr(os, "getuid") else "user"
    shared = Path(tempfile.gettempdir()) / f"{APP_NAME}-{user}"
    if _private_folder(shared) and cache_folder_problem(shared / name) is None:
        return shared / name
    return Path(tempfile.mkdtemp(prefix=f"{APP_NAME}-{name}-"))


def usable_kernel_cache_folder() -> Path:
    """:func:`kernel_cache_folder`, or when it cannot be written (a read-only home, a
    full disk) a temporary one, said in one ``warning:`` line on stderr. Numba would
    otherwise fall back to writing beside the kernels' sources, or compile every run."""
    folder = kernel_cache_folder()
    problem = cache_folder_problem(folder)
    if problem is None:
        return folder
    fallback = fallback_kernel_cache_folder(folder.name)
    print(
        f"warning: kernel cache {folder} cannot be written ({problem}); using {fallback} "
        "(set NUMBA_CACHE_DIR to choose a folder)",
        file=sys.stderr,
    )
    return fallback


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


def _import_numba_cffi_typing_without_cffi() -> None:
    """Import ``numba.core.typing.cffi_utils`` with cffi hidden from it.

    When the first kernel is compiled or loaded from the cache, numba's typing context
    imports ``numba.core.typing.cffi_utils``, which builds a ``cffi.FFI()`` when cffi is
    installed (pymoo's ``moocore`` needs it): that imports pycparser and compiles its C
    lexer, about 0.15 s, half of numba's first dispatch here. No kernel calls a cffi
    function, so numba's cffi support is left off (``cffi_utils.SUPPORTED`` is false);
    cffi itself is not touched, and a later ``import cffi`` works as usual.
    """
    name = "numba.core.typing.cffi_utils"
    if name in sys.modules:
        return
    absent = object()
    saved = sys.modules.get("cffi", absent)
    sys.modules["cffi"] = None  # type: ignore[assignment]  # `import cffi` raises ImportError
    try:
        importlib.import_module(name)
    finally:
        if saved is absent:
            del sys.modules["cffi"]
        else:
            sys.modules["cffi"] = saved  # type: ignore[assignment]


def _load_numba_registries() -> None:
    """Load numba's typing and lowering registries now, while the cyclic collector is off.

    numba loads them at the first kernel call (compiled or from the cache): some 250
    modules' templates, many objects and no garbage, 0.16 s with the collector on and
    0.14 s with it off here. Whatever runs a job goes on to call a kernel, so there this
    moves the work and adds none; a warm-up check that finds every kernel cached
    (``planar-tui warmup``, the app's start) calls none and pays it for nothing, beside
    the 0.35 s of importing numba it already paid.
    """
    from numba.core.registry import cpu_target

    cpu_target.target_context.refresh()


def prepare_kernels() -> Path:
    """Set numba up for planar-tui's kernels; idempotent; returns the kernel cache folder.

    Must run before the first ``planar_tui.kernels`` module is imported: numba picks a
    kernel's cache folder when the kernel is decorated. The folder is
    :func:`usable_kernel_cache_folder` (a temporary one, said once, if the user's cannot be
    written). numba is imported and its registries loaded with the cyclic collector off,
    without its BLAS probe and without building a cffi parser (the helpers below).
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
    with no_cyclic_collection():  # numba's import: many objects, no garbage (~7 % of it)
        from numba import config

        folder = usable_kernel_cache_folder()
        config.CACHE_DIR = str(folder)
        _import_arraymath_without_blas_probe()
        _import_numba_cffi_typing_without_cffi()
        _load_numba_registries()
    _kernel_cache = folder
    return folder


@contextmanager
def no_cyclic_collection() -> Iterator[None]:
    """No cyclic garbage collection while the block runs (imports: many objects that stay,
    next to no reference cycles to free), then the collector as it was."""
    collecting = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if collecting:
            gc.enable()

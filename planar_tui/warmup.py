"""Compile the kernels a job needs before it runs, as a stage of its own.

The first run after an install (or after an edit of ``kernels/``) compiles the Numba
kernels it calls: 10-30 s on a slow machine, silently, inside whatever stage calls them
first. :func:`warm_kernels` does it first, in a stage named :data:`STAGE` with its own
progress (completed = job kinds done, detail = the kernel being compiled), and only when
needed: a warm run (the kinds' markers present in the kernel cache folder) shows no such
stage.

How: each job kind is warmed by running a tiny example job of that kind (its
:class:`~planar_tui.jobkind.JobKind`'s ``warmup`` TOML after its robot kind's ``example``,
:func:`example`, read by the real preset loader) through its real runner, so exactly the kernel
signatures the runners use are compiled and cached, with nothing declared twice. Compiling
one function cannot be interrupted, so the example runs in a helper thread while the
caller's :class:`~planar_tui.progress.Progress` is checked every
:data:`~planar_tui.progress.POLL_S`: a cancel returns at once and the compilation finishes
in the background, harmlessly filling the cache. After a kind's example ran, a marker file
``warm-KIND-DIGEST`` is written in the kernel cache folder
(:func:`planar_tui.runtime.prepare_kernels`); the digest covers the kind's runner module,
numba's version and where the kernel sources are with their stamps (numba's own cache is
keyed by those: a fresh clone elsewhere compiles again, so it must warm up again).

Callers: :func:`planar_tui.batch.run_job` (every job), ``planar-tui warmup`` (every kind,
for batch machines) and the app at start, in a background thread:
``warm_kernels(JOB_KINDS, Progress(on_update=..., should_stop=...))``.
"""

from __future__ import annotations

import contextlib
import hashlib
import sys
import tempfile
import threading
from collections.abc import Iterable
from pathlib import Path

from planar_tui.progress import Progress
from planar_tui.runtime import design_cache_suspended

STAGE = "compiling kernels (first run only)"


def example(kind: str) -> str | None:
    """The TOML preset of ``kind``'s warm-up example: its robot kind's ``example`` table and
    its own ``warmup`` job tables (declared in the kind's module); ``None`` for a kind
    without one (nothing to compile)."""
    from planar_tui.registry import JOB_KINDS, ROBOT_KINDS

    declared = JOB_KINDS.get(kind)
    if declared is None or declared.warmup is None:
        return None
    return ROBOT_KINDS[declared.robot_kind].example + declared.warmup


_lock = threading.Lock()


def kernel_sources_stamp() -> bytes:
    """Where the kernel sources are and their ``(mtime, size)`` stamps: numba files a cached
    kernel under its source's path and keeps it only while the source's stamp is unchanged,
    so a fresh clone elsewhere (or a checkout touching ``kernels/``) compiles again even
    though the kernel cache folder (named by the sources' digest) is the same."""
    from planar_tui.runtime import kernels_folder

    folder = kernels_folder()
    stamps = [str(folder)]
    for path in sorted(folder.glob("*.py")):
        stat = path.stat()
        stamps.append(f"{path.name}:{stat.st_mtime_ns}:{stat.st_size}")
    return "\0".join(stamps).encode()


def marker(kind: str) -> Path:
    """The file that says ``kind``'s kernels are compiled into the current kernel cache:
    named by the kind's runner module, numba's version and :func:`kernel_sources_stamp`."""
    import numba

    from planar_tui.registry import JOB_KINDS
    from planar_tui.runtime import prepare_kernels

    module = sys.modules[JOB_KINDS[kind].run.__module__]
    digest = hashlib.sha256(
        Path(module.__file__).read_bytes() + numba.__version__.encode() + kernel_sources_stamp()
    )
    return prepare_kernels() / f"warm-{kind}-{digest.hexdigest()[:12]}"


def missing(kinds: Iterable[str]) -> list[str]:
    """The kinds among ``kinds`` whose kernels are not known to be compiled (no marker)."""
    return [
        kind
        for kind in dict.fromkeys(kinds)
        if example(kind) is not None and not marker(kind).exists()
    ]


class _CompileWatcher:
    """Names the kernel numba is compiling (numba's ``numba:compile`` events)."""

    def __init__(self):
        self.current = ""
        self.compiled = 0

    def __enter__(self):
        from numba.core import event

        watcher = self

        class Listener(event.Listener):
            def on_start(self, ev):
                name = getattr(ev.data.get("dispatcher"), "__name__", "")
                if name != "impl":  # numba's own overloads
                    watcher.current = name

            def on_end(self, ev):
                watcher.compiled += 1

        self._context = event.install_listener("numba:compile", Listener())
        self._context.__enter__()
        return self

    def __exit__(self, *exc):
        return self._context.__exit__(*exc)


def _run_example(kind: str) -> None:
    """Run ``kind``'s example job (compiling and caching its kernels), then mark it."""
    from planar_tui.presets import load_preset
    from planar_tui.registry import JOB_KINDS

    with _lock:  # one example at a time: concurrent warm-ups wait, then find the marker
        if marker(kind).exists():
            return
        with (
            tempfile.TemporaryDirectory(prefix="planar-tui-warmup-") as folder,
            design_cache_suspended(),
        ):
            path = Path(folder) / f"warmup-{kind}.toml"
            path.write_text(example(kind) or "", encoding="utf-8")
            for job in load_preset(path).jobs_of(kind):
                JOB_KINDS[kind].run(JOB_KINDS[kind].prepare_job(job), Progress())
        with contextlib.suppress(OSError):  # read-only cache: compiled in memory anyway
            marker(kind).touch()


def warm_kernels(kinds: Iterable[str], progress: Progress) -> list[str]:
    """Compile the kernels of the job kinds ``kinds`` that are not cached yet, in the
    stage :data:`STAGE` of ``progress`` (none when all are cached); returns the kinds
    compiled. Raises :class:`~planar_tui.errors.Cancelled` within
    :data:`~planar_tui.progress.POLL_S` of a cancel."""
    todo = missing(kinds)
    if not todo:
        return []
    progress.start(len(todo), STAGE, f"{todo[0]} kernels")
    with _CompileWatcher() as watcher:
        for kind in todo:
            shown = [""]

            def show_kernel(kind=kind, shown=shown) -> None:
                if watcher.current != shown[0]:
                    shown[0] = watcher.current
                    progress.advance(0.0, f"{kind}: {watcher.current}")

            progress.wait_for(_run_example, kind, on_poll=show_kernel)
            progress.advance(1.0, f"{kind} kernels ready", kernels_compiled=watcher.compiled)
    return todo

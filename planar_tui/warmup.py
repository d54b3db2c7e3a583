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

Callers: :func:`planar_tui.batch.run_job` (every job) and the app at start, in a
background thread: ``warm_kernels(JOB_KINDS, Progress(on_update=..., should_stop=...))``.
``planar-tui warmup`` (every kind, for batch machines) calls
:func:`warm_kernels_in_processes`: one child process per kind (:func:`child_main`), as
many at once as cores, each writing ``kernel NAME`` lines as its kernels start compiling;
a cancel ends them by SIGTERM (a kernel compiling in this process's helper thread cannot
be stopped, and an interpreter exiting under it printed an LLVM assertion).
"""

from __future__ import annotations

import contextlib
import hashlib
import sys
import tempfile
import threading
import time
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import TYPE_CHECKING, Any

from planar_tui import runtime
from planar_tui.presets import load_preset
from planar_tui.progress import POLL_S, Progress
from planar_tui.registry import JOB_KINDS, ROBOT_KINDS
from planar_tui.runtime import design_cache_suspended, prepare_kernels
from planar_tui.warmup_schedule import schedule

if TYPE_CHECKING:
    from planar_tui.jobkind import Job

STAGE = "compiling kernels (first run only)"


def parts(kind: str) -> dict[str, str]:
    """The job tables (TOML) of ``kind``'s warm-up examples by part, as declared in the
    kind's module: ``{"": tables}`` for a kind with one example, ``{}`` for a kind without
    one (nothing to compile)."""
    declared = JOB_KINDS.get(kind)
    if declared is None or declared.warmup is None:
        return {}
    if isinstance(declared.warmup, str):
        return {"": declared.warmup}
    return dict(declared.warmup)


def units(kind: str) -> list[str]:
    """The warm-up units of ``kind``: ``kind`` for a kind with one example, ``kind:part``
    for each part of one with several, none for a kind without."""
    return [f"{kind}:{part}" if part else kind for part in parts(kind)]


def units_for(job: Job[Any, Any]) -> list[str]:
    """The warm-up units a run of ``job`` needs: the parts its kind's ``warmup_parts``
    names for it (so a cold run compiles only the kernels the job calls), else all."""
    declared = JOB_KINDS[job.kind]
    if declared.warmup_parts is None or isinstance(declared.warmup, str):
        return units(job.kind)
    return [f"{job.kind}:{part}" for part in declared.warmup_parts(job)]


def example(unit: str) -> str | None:
    """The TOML preset of a warm-up unit (``kind`` or ``kind:part``): its robot kind's
    ``example`` table (unless a part brings its own robot table: the motion job's
    6-link chain), then the unit's job tables (a bare kind: every part's); ``None``
    where there is nothing to compile."""
    kind, _, part = unit.partition(":")
    tables = parts(kind)
    chosen = [tables[part]] if part in tables else [] if ":" in unit else list(tables.values())
    if not chosen:
        return None
    robot_kind = JOB_KINDS[kind].robot_kind
    own = any(line == f"[{robot_kind}]" for table in chosen for line in table.splitlines())
    return ("" if own else ROBOT_KINDS[robot_kind].example) + "".join(chosen)


_lock = threading.Lock()


def kernel_sources_stamp() -> bytes:
    """Where the kernel sources are and their ``(mtime, size)`` stamps: numba files a cached
    kernel under its source's path and keeps it only while the source's stamp is unchanged,
    so a fresh clone elsewhere (or a checkout touching ``kernels/``) compiles again even
    though the kernel cache folder (named by the sources' digest) is the same."""

    folder = runtime.kernels_folder()
    stamps = [str(folder)]
    for path in sorted(folder.glob("*.py")):
        stat = path.stat()
        stamps.append(f"{path.name}:{stat.st_mtime_ns}:{stat.st_size}")
    return "\0".join(stamps).encode()


def marker(unit: str) -> Path:
    """The file that says the kernels of a warm-up unit (``kind`` or ``kind:part``) are
    compiled into the current kernel cache: named by the unit, the kind's runner module,
    numba's version and :func:`kernel_sources_stamp`."""
    import numba

    kind, _, part = unit.partition(":")
    module = sys.modules[JOB_KINDS[kind].run.__module__]
    digest = hashlib.sha256(
        Path(module.__file__).read_bytes() + numba.__version__.encode() + kernel_sources_stamp()
    )
    name = f"{kind}-{part}" if part else kind
    return prepare_kernels() / f"warm-{name}-{digest.hexdigest()[:12]}"


def missing(kinds_or_units: Iterable[str]) -> list[str]:
    """The warm-up units (a kind stands for all of its units) whose kernels are not known
    to be compiled (no marker)."""
    expanded = [u for name in kinds_or_units for u in (units(name) if ":" not in name else [name])]
    return [
        unit
        for unit in dict.fromkeys(expanded)
        if example(unit) is not None and not marker(unit).exists()
    ]


class _CompileWatcher:
    """Names the kernel numba is compiling (numba's ``numba:compile`` events)."""

    def __init__(self, on_change: Callable[[str], None] | None = None):
        self.current = ""
        self.compiled = 0
        self.on_change = on_change

    def __enter__(self):
        from numba.core import event

        watcher = self

        class Listener(event.Listener):
            def on_start(self, ev):
                name = getattr(ev.data.get("dispatcher"), "__name__", "")
                if name not in ("impl", watcher.current):  # "impl": numba's own overloads
                    watcher.current = name
                    if watcher.on_change is not None:
                        watcher.on_change(name)

            def on_end(self, ev):
                watcher.compiled += 1

        self._context = event.install_listener("numba:compile", Listener())
        self._context.__enter__()
        return self

    def __exit__(self, *exc):
        return self._context.__exit__(*exc)


def _run_example(unit: str) -> None:
    """Run a warm-up unit's example jobs (compiling and caching their kernels), then mark
    it; a bare kind with several parts runs each part (each marked)."""
    if ":" not in unit and units(unit) != [unit]:
        for part in units(unit):
            _run_example(part)
        return
    kind = unit.partition(":")[0]
    with _lock:  # one example at a time: concurrent warm-ups wait, then find the marker
        if marker(unit).exists():
            return
        with (
            tempfile.TemporaryDirectory(prefix="planar-tui-warmup-") as folder,
            design_cache_suspended(),
        ):
            path = Path(folder) / f"warmup-{unit.replace(':', '-')}.toml"
            path.write_text(example(unit) or "", encoding="utf-8")
            for job in load_preset(path).jobs_of(kind):
                JOB_KINDS[kind].run(JOB_KINDS[kind].prepare_job(job), Progress())
        with contextlib.suppress(OSError):  # read-only cache: compiled in memory anyway
            marker(unit).touch()


def compiling_text(unit: str, kernel: str, elapsed_s: float) -> str:
    """The detail of the compile stage: the unit, the kernel numba is compiling (when
    known) and the unit's whole seconds so far (``workspace: compiling bisect_boxes, 12 s``)."""
    what = f"compiling {kernel}" if kernel else "compiling"
    return f"{unit}: {what}, {elapsed_s:.0f} s"


def warm_kernels(kinds_or_units: Iterable[str], progress: Progress) -> list[str]:
    """Compile the kernels of the warm-up units ``kinds_or_units`` (job kinds, each standing for all of
    its units, or ``kind:part``, :func:`units_for`) that are not cached yet, in the stage
    :data:`STAGE` of ``progress`` (none when all are cached; its detail names the kernel
    being compiled and the seconds so far, :func:`compiling_text`; its figure
    ``compile_s`` the stage's seconds); returns the units compiled.
    Raises :class:`~planar_tui.errors.Cancelled` within :data:`~planar_tui.progress.POLL_S`
    of a cancel."""
    todo = missing(kinds_or_units)
    if not todo:
        return []
    progress.start(len(todo), STAGE, f"{todo[0]} kernels")
    with _CompileWatcher() as watcher:
        for unit in todo:
            started_s = time.monotonic()
            shown = [""]

            def show_kernel(unit=unit, shown=shown, started_s=started_s) -> None:
                text = compiling_text(unit, watcher.current, time.monotonic() - started_s)
                if text != shown[0]:
                    shown[0] = text
                    progress.advance(0.0, text)

            progress.wait_for(_run_once, unit, on_poll=show_kernel)
            progress.advance(1.0, f"{unit} kernels ready", kernels_compiled=watcher.compiled)
        progress.advance(0.0, compile_s=time.monotonic() - progress.stage_started_s)
    return todo


#: One lock per warm-up unit: two threads of a process (the app's background warm-up and a
#: job's own compile stage) never compile the same unit side by side.
_UNIT_LOCKS: dict[str, threading.Lock] = {}
_UNIT_LOCKS_GUARD = threading.Lock()


def _run_once(unit: str) -> None:
    """:func:`_run_example` of ``unit`` unless it is compiled already: a thread finding
    another compiling the unit waits for it, then finds its marker and returns."""
    with _UNIT_LOCKS_GUARD:
        lock = _UNIT_LOCKS.setdefault(unit, threading.Lock())
    with lock:
        if missing([unit]):
            _run_example(unit)


def compile_processes() -> int:
    """How many warm-up processes run at once: the cores this process may use."""
    import os

    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # not Linux
        return max(1, os.cpu_count() or 1)


def _child_command(units_: list[str]) -> list[str]:
    """The command of a warm-up process: this Python running :func:`child_main`."""
    code = "from planar_tui.warmup import child_main; child_main()"
    return [sys.executable, "-c", code, *units_]


def child_main() -> None:
    """A warm-up process (``python -c ... UNIT...``): run the units' examples in turn,
    writing ``unit UNIT`` on stdout as each starts, ``kernel NAME`` as each kernel starts
    compiling and ``ready UNIT`` as each is done. Ctrl-C is the parent's to
    handle (it ends this process); SIGTERM ends it at once, mid-compile included."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    prepare_kernels()
    with _CompileWatcher(on_change=lambda name: print(f"kernel {name}", flush=True)):
        for unit in sys.argv[1:]:
            print(f"unit {unit}", flush=True)
            _run_example(unit)
            print(f"ready {unit}", flush=True)


def warm_kernels_in_processes(
    kinds_or_units: Iterable[str], progress: Progress, processes: int | None = None
) -> list[str]:
    """:func:`warm_kernels` in at most ``processes`` child processes (default
    :func:`compile_processes`), the units shared among them by :func:`schedule`: the
    compilations run side by side, each process paying its start once, and a cancel ends
    the children at once (SIGTERM: a kernel compiling is cut, the cache keeps what was
    written whole) and raises :class:`~planar_tui.errors.Cancelled` within
    :data:`~planar_tui.progress.POLL_S`. Returns the units compiled; a child that fails
    raises :class:`RuntimeError` with the last line it wrote on stderr."""
    import time

    todo = missing(kinds_or_units)
    if not todo:
        return []
    progress.start(len(todo), STAGE, f"{len(todo)} warm-up units")
    running: list[_Child] = []
    try:
        for units_ in schedule(todo, processes or compile_processes()):
            running.append(_Child(units_))
        while running:
            time.sleep(POLL_S)
            for child in list(running):
                for unit in child.ready():
                    progress.advance(1.0, f"{unit} kernels ready")
                if child.process.poll() is None:
                    if child.latest():
                        progress.advance(0.0, f"{child.current()}: {child.latest()}")
                    continue
                running.remove(child)
                child.finish()
                for unit in child.ready():
                    progress.advance(1.0, f"{unit} kernels ready")
            progress.check()
    finally:
        for child in running:
            child.end()
    return todo


class _Child:
    """One warm-up process running ``units`` in turn, the lines it writes on stdout
    (``unit UNIT`` as a unit starts, ``kernel NAME`` as a kernel starts compiling, ``ready
    UNIT`` as a unit is done) and on stderr (each pipe read by a helper thread, so that
    neither fills up)."""

    def __init__(self, units_: list[str]):
        import subprocess

        self.units = units_
        self.lines: list[str] = []
        self.errors: list[str] = []
        self.reported = 0  # units reported ready by :meth:`ready`
        self.process = subprocess.Popen(
            _child_command(units_),
            stdin=subprocess.DEVNULL,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        self._readers = [
            threading.Thread(target=self._read, args=(pipe, lines), daemon=True)
            for pipe, lines in (
                (self.process.stdout, self.lines),
                (self.process.stderr, self.errors),
            )
        ]
        for reader in self._readers:
            reader.start()

    @staticmethod
    def _read(pipe, lines: list[str]) -> None:
        for line in pipe:
            if line.strip():
                lines.append(line.strip())

    def latest(self) -> str:
        """The kernel compiling now (the last one named since the last unit started), or
        ``""`` (none yet, or the unit is ready)."""
        for line in reversed(list(self.lines)):
            if line.startswith(("unit ", "kernel ", "ready ")):
                return line.removeprefix("kernel ") if line.startswith("kernel ") else ""
        return ""

    def current(self) -> str:
        """The unit being compiled (the last one started, else the first)."""
        started = [line for line in list(self.lines) if line.startswith("unit ")]
        return started[-1].removeprefix("unit ") if started else self.units[0]

    def ready(self) -> list[str]:
        """The units done since the last call: those the process said ``ready``, and every
        one once it has exited with success."""
        done = sum(line.startswith("ready ") for line in list(self.lines))
        if self.process.poll() == 0:
            done = len(self.units)
        new = self.units[self.reported : done]
        self.reported = max(self.reported, done)
        return new

    def finish(self) -> None:
        """Raise :class:`RuntimeError` if the process failed (its last stderr line)."""
        self._close()
        if self.process.returncode != 0:
            last = self.errors[-1] if self.errors else f"exit status {self.process.returncode}"
            raise RuntimeError(f"compiling the {', '.join(self.units)} kernels failed: {last}")

    def end(self) -> None:
        """End the process (SIGTERM, then SIGKILL) and reap it."""
        import subprocess

        self.process.terminate()
        try:
            self.process.wait(timeout=5)
        except subprocess.TimeoutExpired:
            self.process.kill()
            self.process.wait()
        self._close()

    def _close(self) -> None:
        """Read the pipes to their end (the process has exited) and close them."""
        for reader in self._readers:
            reader.join()
        for pipe in (self.process.stdout, self.process.stderr):
            if pipe is not None:
                pipe.close()

"""The batch service below both front ends: plan outputs, check them, run jobs with
progress and cancel, write results atomically, and collect summary rows.

The CLI turns its options into calls here and prints; the app runs its jobs and exports
its results through the same functions, so both name and write files identically.
"""

from __future__ import annotations

import os
import stat
import time
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from planar_tui.csvio import write_csv_atomic
from planar_tui.errors import Cancelled, JobError, OutputFailed, PresetError, writing
from planar_tui.figures import save_result_figure
from planar_tui.jobkind import Job, JobResult, PreparedJob
from planar_tui.overrides import with_variant
from planar_tui.progress import Progress
from planar_tui.provenance import job_provenance, planned_sidecar, write_sidecar
from planar_tui.reader import NAME_MAX_BYTES, file_name_problem
from planar_tui.registry import JOB_KINDS
from planar_tui.runtime import prepare_kernels

#: A job as parsed or as prepared (:func:`prepare_jobs`): both read alike (``kind``,
#: ``label``, ``spec`` ...).
AnyJob = Job[Any, Any] | PreparedJob[Any, Any, Any]


@dataclass(frozen=True)
class OutputPlan:
    """Where one job's results go: its main CSV and its extra tables by name (the job as
    parsed, or prepared once the run plan prepared it)."""

    job: AnyJob
    main: Path
    extras: Mapping[str, Path] = field(default_factory=dict)
    figure: Path | None = None

    def paths(self) -> tuple[Path, ...]:
        """Every file this job writes, the main CSV first, the figure last."""
        return (self.main, *self.extras.values(), *((self.figure,) if self.figure else ()))


@dataclass(frozen=True)
class SummaryRow:
    """One finished job for the run summary: ``seconds`` the whole run, of which
    ``compile_seconds`` compiled its kernels (a first run only, the stage
    :data:`planar_tui.warmup.STAGE`)."""

    label: str
    seconds: float
    output: Path
    summary: str
    compile_seconds: float = 0.0


class JobFailed(Exception):
    """A job raised an unexpected error (its cause is ``__cause__``)."""

    def __init__(
        self, job: Job[object, object] | PreparedJob[object, object, object], error: BaseException
    ):
        why = error.message if isinstance(error, JobError) else f"{type(error).__name__}: {error}"
        super().__init__(f"{job.label} failed: {why}")
        self.job = job


class NonFiniteResult(Exception):
    """A finished job's result holds NaN or infinite values: it is not written."""

    def __init__(self, job: AnyJob, table: str, column: str):
        super().__init__(
            f"{job.label}: the result holds NaN or infinite values (first in the {table} "
            f"column {column}); nothing was written"
        )
        self.job = job


def numbered_path(base: Path, number: int, count: int) -> Path:
    """``base`` itself for a single job, ``stem-NUMBER.suffix`` when there are several."""
    return base if count == 1 else base.with_name(f"{base.stem}-{number}{base.suffix or '.csv'}")


def plan_outputs(
    jobs: Sequence[Job],
    out_dir: Path,
    out: Path | None = None,
    extra_out: Mapping[str, Path | None] | None = None,
    plot: Path | None = None,
) -> list[OutputPlan]:
    """Every job's main CSV path, its extra tables' paths and its figure, in job order.

    The main CSV goes to ``out_dir / job.output``, or to ``out`` (numbered ``FILE-1.csv``,
    ``FILE-2.csv`` ... when there are several jobs). Extra tables (e.g. a workspace's
    ``boxes``) go where the job kind's ``extra_outputs`` says, relative to ``out_dir``, or
    to the paths in ``extra_out`` by table name (numbered likewise). Names from the preset
    carry the job's ``variant``
    (:func:`~planar_tui.overrides.apply_overrides`); names given here are kept.
    The figure goes to ``plot`` (numbered likewise) or to the job's ``plot`` key,
    relative to ``out_dir``; no figure without either.
    """
    plans = []
    for number, job in enumerate(jobs, start=1):
        main = numbered_path(out, number, len(jobs)) if out else out_dir / job.output
        if not out:
            main = with_variant(main, job.variant)
        extras = {
            name: with_variant(out_dir / relative, job.variant)
            for name, relative in JOB_KINDS[job.kind].extra_outputs(job).items()
        }
        for name, override in (extra_out or {}).items():
            if override is not None:
                extras[name] = numbered_path(override, number, len(jobs))
        figure = numbered_path(plot, number, len(jobs)) if plot else None
        if figure is None and getattr(job.spec, "plot", None):
            figure = with_variant(out_dir / job.spec.plot, job.variant)
        plans.append(OutputPlan(job, main, extras, figure))
    return plans


def _output_error(path: Path | str, problem: str, expected: str) -> PresetError:
    return PresetError(path, "(output)", problem, expected)


def _name_max_bytes(folder: Path) -> int:
    """The longest file name ``folder``'s file system takes (``NAME_MAX``, 255 if unknown)."""
    try:
        return os.pathconf(folder, "PC_NAME_MAX")
    except (AttributeError, OSError, ValueError):
        return NAME_MAX_BYTES


def _nearest_existing(path: Path) -> Path:
    ancestor = path.parent
    while not ancestor.exists() and ancestor != ancestor.parent:
        ancestor = ancestor.parent
    return ancestor


def check_writable(path: Path, what: str = "CSV file") -> None:
    """Refuse an output path that cannot be written, or whose writing would destroy what
    is there (:class:`PresetError`, exit code 2): a name the file system cannot hold (a NUL
    character, a component or path too long), a folder, a device node, FIFO or socket, a
    read-only file, or a path whose nearest existing ancestor is not a writable folder.
    ``what`` names the file in messages (``"figure file"``)."""
    problem = file_name_problem(str(path))
    if problem is not None:
        raise _output_error(path, problem, "a file name the file system accepts")
    ancestor = _nearest_existing(path)
    name_max = _name_max_bytes(ancestor)
    longest = max((len(os.fsencode(part)) for part in path.parts), default=0)
    if longest > name_max:
        raise _output_error(
            path,
            f"has a name of {longest} bytes, longer than a file name may be ({name_max})",
            "a file name the file system accepts",
        )
    try:
        mode = os.stat(path).st_mode
    except (FileNotFoundError, NotADirectoryError):
        mode = None
    except OSError as error:
        raise _output_error(
            path, f"cannot be checked: {error.strerror}", f"a {what} path"
        ) from None
    if mode is not None and stat.S_ISDIR(mode):
        raise _output_error(path, "is a folder", f"a {what} path")
    if mode is not None and not stat.S_ISREG(mode):
        raise _output_error(
            path,
            f"is {_file_kind(mode)}, not a regular file (it would be replaced)",
            f"a regular {what} path",
        )
    # no write permission bit at all is read-only even for root, whom os.access lets write
    if mode is not None and not (os.access(path, os.W_OK) and mode & 0o222):
        raise _output_error(
            path,
            "is a read-only file (it would be replaced)",
            "a writable file, or a new path",
        )
    if not ancestor.is_dir() or not os.access(ancestor, os.W_OK | os.X_OK):
        raise _output_error(
            path,
            f"cannot be created: {ancestor} is not a writable folder",
            "a path inside a writable folder",
        )


def _file_kind(mode: int) -> str:
    """How a non-regular file is named in messages."""
    for test, name in (
        (stat.S_ISFIFO, "a FIFO (named pipe)"),
        (stat.S_ISCHR, "a character device"),
        (stat.S_ISBLK, "a block device"),
        (stat.S_ISSOCK, "a socket"),
    ):
        if test(mode):
            return name
    return "not a plain file"


def _identity(path: Path) -> str:
    """The absolute path with symbolic links resolved: two names of one file compare equal."""
    return os.path.realpath(path)


@dataclass(frozen=True)
class PlannedFile:
    """One file (or, with ``folder``, a folder the writer owns: a sweep's point files)
    that a run will write; ``writer`` names who writes it in messages
    (``paper:torques (output)``), ``what`` the kind of file (``"figure file"``);
    ``probe`` is the path checked for writability (a folder's first point file)."""

    path: Path
    writer: str
    what: str = "CSV file"
    folder: bool = False
    probe: Path | None = None


def plan_files(plans: Sequence[OutputPlan]) -> list[PlannedFile]:
    """The files of planned jobs (:func:`plan_outputs`): CSVs and extra tables, each with
    its provenance sidecar (:mod:`planar_tui.provenance`), and figures."""
    files = []
    for plan in plans:
        figure = (("plot", plan.figure),) if plan.figure else ()
        for name, path in (("output", plan.main), *plan.extras.items(), *figure):
            what = "figure file" if name == "plot" else "CSV file"
            files.append(PlannedFile(path, f"{plan.job.label} ({name})", what))
            if name != "plot":
                files += planned_sidecar(files[-1])
    return files


def check_planned(files: Sequence[PlannedFile], presets: Mapping[Path, str] | None = None) -> None:
    """Check every file a run plans, before anything runs (:class:`PresetError`, exit code
    2): each must be writable without destroying something (:func:`check_writable`), none
    may be one of the ``presets`` (path -> the label of a job of it), no two may be one file,
    none may lie inside another planned file (``a.csv/b.csv`` beside ``a.csv``), and no
    file or folder may lie in (or be) a planned folder (a sweep's ``point_outputs``, which
    its points fill)."""
    preset_ids = {_identity(path): label for path, label in (presets or {}).items()}
    writers: dict[str, str] = {}
    folders: list[tuple[str, PlannedFile]] = []
    for planned in files:
        check_writable(planned.probe or planned.path, planned.what)
        identity = _identity(planned.path)
        if identity in preset_ids:
            raise _output_error(
                planned.path,
                f"is the preset file of {preset_ids[identity]} (it would be replaced)",
                "an output path other than the preset",
            )
        if identity in writers:
            raise _output_error(
                planned.path,
                f"is written by both {writers[identity]} and {planned.writer}",
                "one file per table (set distinct output paths)",
            )
        writers[identity] = planned.writer
        if planned.folder:
            folders.append((identity, planned))
    files_by_identity = {_identity(planned.path): planned for planned in files}
    for identity, planned in files_by_identity.items():
        parent = os.path.dirname(identity)
        while parent != os.path.dirname(parent):
            holder = files_by_identity.get(parent)
            if holder is not None and not holder.folder:
                raise _output_error(
                    planned.path,
                    f"lies inside {holder.path}, which {holder.writer} writes as a file",
                    "a path that is not inside another planned file",
                )
            parent = os.path.dirname(parent)
    for folder, owner in folders:
        for identity, writer in writers.items():
            inside = identity.startswith(folder.rstrip(os.sep) + os.sep)
            if writer != owner.writer and inside:
                raise _output_error(
                    owner.path,
                    f"is {owner.writer}'s folder of point files, and {writer} "
                    f"writes {identity} inside it",
                    "a folder of its own for the point files",
                )


def prepare_jobs(jobs: Sequence[Job[object, object]]) -> tuple[PreparedJob[Any, Any, object], ...]:
    """Every job ready to run, in order: each kind's ``prepare`` hook, called once per job
    (e.g. the sensitivity's isotropic posture solved, its resources checked after the
    overrides), its result carried by a :class:`~planar_tui.jobkind.PreparedJob`.

    Parsing a preset stays cheap; this is the costly rest of validation, so call it for
    every job before the first one runs: it raises the first job's
    :class:`~planar_tui.errors.PresetError` (exit code 2) while nothing is written yet.
    """
    return tuple(JOB_KINDS[job.kind].prepare_job(job) for job in jobs)


def run_job(
    job: Job[object, object] | PreparedJob[object, object, object],
    progress: Progress | None = None,
) -> JobResult:
    """Run one job (prepared by its kind, once, unless :func:`prepare_jobs` did; kernels
    compiled first when not cached: the stage :data:`planar_tui.warmup.STAGE`); writes
    nothing.

    Raises :class:`~planar_tui.errors.Cancelled` when ``progress`` says stop, the job's
    own :class:`~planar_tui.errors.PresetError` (found while preparing it), and
    :class:`JobFailed` for a job that fails (its :class:`~planar_tui.errors.JobError`,
    e.g. a box budget, or anything unexpected).
    """
    from planar_tui.warmup import units_for, warm_kernels

    prepare_kernels()
    progress = progress or Progress()
    try:
        kind = JOB_KINDS[job.kind]
        ready = job if isinstance(job, PreparedJob) else kind.prepare_job(job)
        warm_kernels(units_for(ready.job), progress)
        return kind.run(ready, progress)
    except (PresetError, Cancelled, KeyboardInterrupt) as error:
        _release(error, progress)
        raise
    except Exception as error:
        _release(error, progress)
        raise JobFailed(job, error) from error


def _release(error: BaseException, progress: Progress) -> None:
    """Free what a failed or cancelled run holds even while the exception is kept (the app
    keeps it to show it): the local variables of the finished frames of its traceback (a
    workspace's boxes: gigabytes; the traceback's lines stay) and the partial results the
    progress refers to. A front end that kept a :class:`ProgressState` drops its
    ``partial`` likewise."""
    import traceback

    progress.partial = {}
    if error.__traceback__ is not None:
        traceback.clear_frames(error.__traceback__.tb_next)


def check_finite(job: AnyJob, result: JobResult) -> None:
    """Refuse a result holding NaN or infinities (:class:`NonFiniteResult`): a diverged
    integration or an overflow is a failure, never a table."""
    for name, table in (("main", result.table), *result.extra_tables.items()):
        column = table.first_non_finite_column()
        if column is not None:
            raise NonFiniteResult(job, "output" if name == "main" else name, column)


def write_result(
    plan: OutputPlan, result: JobResult, timing: tuple[float, float] | None = None
) -> list[Path]:
    """Write a finished job's tables atomically, none if any holds NaN or infinities
    (:class:`NonFiniteResult`), each followed by its provenance sidecar
    (:func:`planar_tui.provenance.write_sidecar`; ``timing`` is the run's ``(start epoch
    s, duration s)`` when known), then its figure if planned (matplotlib is imported only
    then, :mod:`planar_tui.figures`); :class:`OutputFailed` on an OS error."""
    check_finite(plan.job, result)
    record = job_provenance(plan.job, timing)
    written = []
    with writing(plan.main, filename_first=True):
        for path, table in (
            (plan.main, result.table),
            *((p, result.extra_tables[n]) for n, p in plan.extras.items()),
        ):
            written.append(write_csv_atomic(path, table))
            write_sidecar(path, record)
        if plan.figure is not None:
            written.append(_write_figure(plan, result))
    return written


def _write_figure(plan: OutputPlan, result: JobResult) -> Path:
    """Draw and write the job's figure; a result the figure cannot show (no varied column
    in a sweep, say) is :class:`OutputFailed`, never a traceback."""
    figure = plan.figure
    assert figure is not None  # called for a plan with a figure only
    try:
        return save_result_figure(plan.job, result, figure)
    except OSError:
        raise
    except Exception as error:
        raise OutputFailed(figure, f"cannot draw the figure: {error}") from None


def run_plans(
    plans: Sequence[OutputPlan],
    progress_for: Callable[[AnyJob], Any],
    on_finished: Callable[[AnyJob, JobResult], None] | None = None,
) -> Iterator[SummaryRow]:
    """Run the planned jobs in order, writing each job's files as soon as it finishes.

    ``progress_for(job)`` is a context manager yielding the job's
    :class:`~planar_tui.progress.Progress`; ``on_finished(job, result)`` is called after
    the files are written (e.g. to print the job's view). Yields one summary row per job.
    """
    for plan in plans:
        started, started_epoch_s = time.perf_counter(), time.time()
        with progress_for(plan.job) as progress:
            result = run_job(plan.job, progress)
        seconds = time.perf_counter() - started
        write_result(plan, result, (started_epoch_s, seconds))
        if on_finished is not None:
            on_finished(plan.job, result)
        compile_s = min(progress.figures.get("compile_s", 0.0), seconds)
        yield SummaryRow(plan.job.label, seconds, plan.main, result.summary, compile_s)

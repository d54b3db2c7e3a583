"""A whole sweep for both front ends: points validated, outputs checked, points run
in-process or on Dask, finished points checkpointed as they arrive, the CSV written once
every point is done.

The app calls :func:`run_sweep` with its :class:`~planar_tui.progress.Progress` (cancel
through it) and ``on_outcome`` for rows as they finish; the CLI adds ``out_dir``,
``workers``/``scheduler`` and ``resume``.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from planar_tui.csvio import CsvTable, write_csv_atomic
from planar_tui.errors import OutputFailed, PresetError, writing
from planar_tui.figures import dispatch
from planar_tui.figures.sweep import split_columns
from planar_tui.progress import Progress
from planar_tui.provenance import (
    planned_sidecar,
    point_provenance,
    study_provenance,
    write_sidecar,
)
from planar_tui.registry import JOB_KINDS
from planar_tui.sweep import execute
from planar_tui.sweep.budget import check_sweep_budget
from planar_tui.sweep.checkpoint import CheckpointWriter, checkpoint_path, read_finished
from planar_tui.sweep.pointfiles import (
    PointFileRecord,
    check_point_folder,
    manifest_path,
    with_sidecars,
    write_point_file,
)
from planar_tui.sweep.points import Point, SweepPoints, make_points
from planar_tui.sweep.spec import Sweep, parse_sweeps
from planar_tui.sweep.table import sweep_table
from planar_tui.sweep.worker import (
    CANCELLED,
    FAILED,
    OK,
    PointOutcome,
    PointTask,
    point_file_names,
)

if TYPE_CHECKING:
    from planar_tui.batch import PlannedFile
    from planar_tui.jobkind import Job


@dataclass
class SweepRun:
    """A sweep's points and their outcomes by point number (``resumed`` of them read from
    a checkpoint), where its CSV and figure went (``None`` when nothing was written), why
    its figure was not written (``figure_error``) and its checkpoint while it is kept.
    A ``cancelled`` run (the app's, stopped part-way) keeps its finished points; its
    table marks the others ``cancelled``. ``recomputed``: finished points of the
    checkpoint run again because a point file of theirs was missing."""

    sweep: Sweep
    points: Sequence[Point]
    outcomes: dict[int, PointOutcome] = field(default_factory=dict)
    resumed: int = 0
    recomputed: int = 0
    output: Path | None = None
    figure: Path | None = None
    figure_error: str | None = None
    checkpoint: Path | None = None
    cancelled: bool = False

    @property
    def failed(self) -> int:
        """How many points failed."""
        return sum(1 for outcome in self.outcomes.values() if outcome.status == FAILED)

    @property
    def table(self) -> CsvTable:
        """The sweep CSV of the points finished so far (all of them once it ran); a
        cancelled run's also lists the points not run, status ``cancelled``."""
        outcomes = dict(self.outcomes)
        if self.cancelled:
            for number in range(1, len(self.points) + 1):
                outcomes.setdefault(
                    number,
                    PointOutcome(number, CANCELLED, "not run: the sweep was cancelled", {}, 0.0),
                )
        values = {number: point_values(self.points, number) for number in outcomes}
        return sweep_table([path.text for path in self.sweep.paths], values, outcomes)


def point_values(points: Sequence[Point], number: int) -> tuple[Any, ...]:
    """The values of point ``number`` (1-based), without making its job when ``points``
    are :class:`~planar_tui.sweep.points.SweepPoints`."""
    if isinstance(points, SweepPoints):
        return points.values(number - 1)
    return points[number - 1].values


def write_figure(run: SweepRun, path: Path) -> Path:
    """Draw the sweep's figure (:mod:`planar_tui.figures.sweep`: a line against one
    varied key, a heat map against two) into ``path``, atomically; a sweep the figure
    cannot show (no varied key) is :class:`~planar_tui.errors.OutputFailed`."""

    with writing(path):
        try:
            return dispatch.save_table_figure(run.table, path, title=run.sweep.label)
        except OSError:
            raise
        except Exception as error:
            raise OutputFailed(path, f"cannot draw the figure: {error}") from None


def output_path(sweep: Sweep, out_dir: Path) -> Path:
    """The sweep's CSV in ``out_dir``."""
    return out_dir / sweep.output


def planned_files(sweep: Sweep, out_dir: Path) -> list[PlannedFile]:
    """Every file the sweep writes in ``out_dir`` (for
    :func:`planar_tui.batch.check_planned`): its CSV, its checkpoint, its figure and its
    point-file folder (which it owns whole; its first point file probed)."""
    from planar_tui.batch import PlannedFile

    output = output_path(sweep, out_dir)
    files = [
        PlannedFile(output, f"{sweep.label} (output)"),
        PlannedFile(checkpoint_path(output), f"{sweep.label} (checkpoint)"),
    ]
    files += planned_sidecar(files[0])
    if sweep.plot is not None:
        files.append(PlannedFile(out_dir / sweep.plot, f"{sweep.label} (plot)", "figure file"))
    if sweep.point_outputs is not None:
        folder = out_dir / sweep.point_outputs
        files.append(
            PlannedFile(
                folder,
                f"{sweep.label} (point_outputs)",
                "point file",
                folder=True,
                probe=folder / "point-1.csv",
            )
        )
        files.append(
            PlannedFile(manifest_path(output), f"{sweep.label} (point-file record)", "record file")
        )
    return files


def check_point_outputs(sweep: Sweep, out_dir: Path) -> None:
    """Refuse, before anything runs, a point folder that is a symbolic link or holds
    point files this sweep did not write (:func:`pointfiles.check_point_folder`)."""
    if sweep.point_outputs is not None:
        output = output_path(sweep, out_dir)
        check_point_folder(
            sweep.preset_path,
            f"{sweep.name}.point_outputs",
            out_dir / sweep.point_outputs,
            out_dir,
            manifest_path(output),
        )


def figure_problem(sweep: Sweep, points: Sequence[Point]) -> str | None:
    """Why the sweep's figure cannot be drawn whatever the points compute (no varied key
    column, by :func:`planar_tui.figures.sweep.split_columns` on the key columns), or
    ``None``."""
    paths = [path.text for path in sweep.paths]
    keys = CsvTable(
        ("point", *paths, "status"),
        [[n, *point_values(points, n), "ok"] for n in range(1, len(points) + 1)],
    )
    try:
        varied, _ = split_columns(keys)
    except (TypeError, ValueError):  # a key whose values are no numbers
        varied = []
    if varied:
        return None
    if len(points) < 2:
        return f"the sweep has {len(points)} point: a figure needs a key that varies"
    return "no varied key takes two numeric values: a figure needs one"


def check_figure(sweep: Sweep, points: Sequence[Point]) -> None:
    """Refuse, before anything runs, a ``plot`` the sweep's figure cannot draw
    (:func:`figure_problem`; :class:`~planar_tui.errors.PresetError`, exit code 2)."""
    problem = None if sweep.plot is None else figure_problem(sweep, points)
    if problem is not None:
        raise PresetError(
            sweep.preset_path,
            f"{sweep.name}.plot",
            problem,
            "a plot only for a sweep with a varied numeric key",
        )


def run_sweep(
    sweep: Sweep,
    progress: Progress | None = None,
    *,
    points: list[Point] | None = None,
    workers: int = 1,
    scheduler: str | None = None,
    out_dir: Path | None = None,
    resume: bool = False,
    on_outcome: Callable[[PointOutcome], None] | None = None,
    announce: Callable[[str], None] = lambda text: None,
    client: Any = None,
    keep_checkpoint: bool = False,
) -> SweepRun:
    """Run every point of ``sweep`` and return them (see :class:`SweepRun`).

    ``points`` are :func:`make_points`'s (made and validated here when not given: a
    :class:`~planar_tui.errors.PresetError` before anything runs). The points run on a
    :func:`~planar_tui.sweep.execute.point_runner`: the Dask ``client`` given (e.g. one
    local cluster for several sweeps), else this process for ``workers == 1`` without a
    ``scheduler`` (no Dask import), else a local Dask cluster of ``workers`` processes or
    the scheduler at ``scheduler``. With ``out_dir`` the CSV, the checkpoint and the point
    CSVs are written there; ``resume`` continues from the checkpoint of the same sweep
    (:func:`_open_checkpoint`). ``progress`` counts points (figure ``failed``); its cancel,
    or Ctrl-C, stops the run with :class:`~planar_tui.errors.Cancelled` /
    ``KeyboardInterrupt``: the checkpoint stays, no CSV is written. A checkpoint record
    that is not a finished point of this sweep is dropped with one ``announce`` line
    (warning), and its point runs again. ``on_outcome`` sees every point as it finishes
    (resumed ones first, in order). The checkpoint is deleted once the CSV is written,
    unless ``keep_checkpoint`` (the CLI deletes a run's checkpoints once all its sweeps are
    done: ``run.checkpoint``). A CSV or point file that cannot be written is
    :class:`~planar_tui.errors.OutputFailed` (the checkpoint stays); a figure that cannot be
    written is ``run.figure_error`` (the CSV is written).
    """
    started_s = time.time()
    progress = progress or Progress()
    run = SweepRun(sweep, make_points(sweep) if points is None else points)
    files = _open_files(run, out_dir, resume, announce)
    try:
        resumed = set(run.outcomes)
        _start_progress(run, progress, on_outcome)
        finished = _finished_point(run, files, progress, on_outcome)
        prefix = f"planar-tui-{sweep.fingerprint()[:8]}"
        needed = len(run.points) > len(resumed)
        with execute.point_runner(
            client, workers, scheduler, announce, progress, prefix, needed=needed
        ) as runner:
            runner.run(_tasks(run, resumed), finished)
        if files.output is not None:
            _write_table(run, files.output, started_s)
    finally:
        if files.writer is not None:
            files.writer.close()
    _finish(run, out_dir, keep_checkpoint)
    return run


@dataclass(frozen=True)
class _SweepFiles:
    """Where a sweep writes: its CSV, its point files' folder, its checkpoint writer and
    the record of its point files (each ``None`` where it writes none)."""

    output: Path | None
    folder: Path | None
    writer: CheckpointWriter | None
    record: PointFileRecord | None


def _open_files(
    run: SweepRun, out_dir: Path | None, resume: bool, announce: Callable[[str], None]
) -> _SweepFiles:
    """The open stage: the sweep's files in ``out_dir`` and its checkpoint, started afresh
    or resumed (:func:`_open_checkpoint`); nothing without ``out_dir``."""
    if out_dir is None:
        return _SweepFiles(None, None, None, None)
    sweep = run.sweep
    output = output_path(sweep, out_dir)
    folder = None if sweep.point_outputs is None else out_dir / sweep.point_outputs
    writer, record = _open_checkpoint(run, out_dir, output, folder, resume, announce)
    return _SweepFiles(output, folder, writer, record)


def _start_progress(
    run: SweepRun, progress: Progress, on_outcome: Callable[[PointOutcome], None] | None
) -> None:
    """The kernels warmed, the progress started at the points resumed, and those points
    shown to ``on_outcome`` first, in order."""
    from planar_tui.warmup import warm_kernels

    warm_kernels([run.sweep.job.kind], progress)
    progress.start(len(run.points), run.sweep.label, _detail(run))
    progress.advance(run.resumed, _detail(run), failed=run.failed)
    if on_outcome is not None:
        for number in sorted(run.outcomes):
            on_outcome(run.outcomes[number])


def _tasks(run: SweepRun, resumed: set[int]) -> Iterator[PointTask | PointOutcome]:
    """The points left, each made as it is reached; one found invalid only now (not
    among those checked up front) is a failed point."""
    sweep, points, total = run.sweep, run.points, len(run.points)
    for number in range(1, total + 1):
        if number in resumed:
            continue
        try:
            point = points[number - 1]
        except PresetError as error:
            yield PointOutcome(number, FAILED, error.message, {}, 0.0)
            continue
        yield PointTask(number, point.job, _point_stem(sweep, total, number))


def _finished_point(
    run: SweepRun,
    files: _SweepFiles,
    progress: Progress,
    on_outcome: Callable[[PointOutcome], None] | None,
) -> Callable[[PointOutcome], None]:
    """What each finished point does: its point files written, checkpointed, counted and
    shown to ``on_outcome``."""

    def finished(outcome: PointOutcome) -> None:
        if files.folder is not None and outcome.tables:
            timing = (time.time() - outcome.seconds, outcome.seconds)
            provenance = point_provenance(run.sweep, run.points[outcome.number - 1], timing)
            for name, text in outcome.tables.items():
                write_point_file(files.folder / name, text, files.record, provenance)
        if files.writer is not None:
            files.writer.add(outcome)
        run.outcomes[outcome.number] = outcome
        progress.advance(1, _detail(run), failed=run.failed)
        if on_outcome is not None:
            on_outcome(outcome)

    return finished


def _write_table(run: SweepRun, output: Path, started_s: float) -> None:
    """The write stage: the sweep CSV and its provenance sidecar, atomically
    (:class:`~planar_tui.errors.OutputFailed` where it cannot be written)."""
    with writing(output):
        write_csv_atomic(output, run.table)
        timing = (started_s, time.time() - started_s)
        write_sidecar(output, study_provenance("sweep", run.sweep, timing))
    run.output = output


def _finish(run: SweepRun, out_dir: Path | None, keep_checkpoint: bool) -> None:
    """The checkpoint deleted (unless kept) and the figure drawn where the CSV was written
    (a figure that cannot be written is ``run.figure_error``)."""
    if run.checkpoint is not None and not keep_checkpoint:
        run.checkpoint.unlink(missing_ok=True)
        run.checkpoint = None
    if run.output is not None and out_dir is not None and run.sweep.plot is not None:
        try:
            run.figure = write_figure(run, out_dir / run.sweep.plot)
        except OutputFailed as error:
            run.figure_error = str(error)


def _point_stem(sweep: Sweep, total: int, number: int) -> str | None:
    """The stem of point ``number``'s files (``point-007``), ``None`` without point files."""
    return None if sweep.point_outputs is None else f"point-{number:0{len(str(total))}d}"


def _job_of(points: Sequence[Point], number: int) -> Job | None:
    """Point ``number``'s job; ``None`` when it is not valid now (a device gone)."""
    try:
        return points[number - 1].job
    except PresetError:
        return None


def _open_checkpoint(
    run: SweepRun,
    out_dir: Path,
    output: Path,
    folder: Path | None,
    resume: bool,
    announce: Callable[[str], None],
) -> tuple[CheckpointWriter, PointFileRecord | None]:
    """The sweep's checkpoint beside ``output`` (in ``out_dir``), started afresh or, with ``resume``, with
    its finished points kept (into ``run.outcomes``; a point whose job is not valid now
    is not resumed, nor one whose point files in ``folder`` are missing: it runs again),
    and the record of the point files (``folder`` checked; afresh: the files this sweep
    wrote before go, and only those)."""
    sweep, points, total = run.sweep, run.points, len(run.points)
    checkpoint = checkpoint_path(output)
    finished = {}
    if resume:
        names = JOB_KINDS[sweep.job.kind].figure_names

        def columns(number: int) -> tuple[str, ...] | None:
            job = _job_of(points, number)
            return () if job is None else None if names is None else names(job)

        finished = read_finished(
            checkpoint,
            sweep.fingerprint(),
            total,
            columns,
            lambda text: announce(f"warning: {text}"),
        )
    record = None
    if folder is not None:

        def files_missing(number: int) -> bool:
            job = _job_of(points, number)
            if job is None:
                return True
            names = with_sidecars(point_file_names(_point_stem(sweep, total, number), job))
            return not all((folder / name).is_file() for name in names)

        missing = [
            number
            for number, outcome in finished.items()
            if outcome.status == OK and files_missing(number)
        ]
        for number in missing:
            del finished[number]
        run.recomputed = len(missing)
        check_point_folder(
            sweep.preset_path,
            f"{sweep.name}.point_outputs",
            folder,
            out_dir,
            manifest_path(output),
        )
        record = PointFileRecord(manifest_path(output), folder)
        if not finished:  # afresh: the files this sweep wrote before go, and only those
            record.start_afresh()
    writer = CheckpointWriter(checkpoint, sweep.fingerprint(), total, finished)
    run.checkpoint = checkpoint
    run.outcomes.update(finished)
    run.resumed = len(finished)
    return writer, record


def _detail(run: SweepRun) -> str:
    done = len(run.outcomes)
    text = f"{done}/{len(run.points)} points, {run.failed} failed"
    return text + resume_note(run)


def resume_note(run: SweepRun) -> str:
    """``, N from the checkpoint`` and ``, M run again (point files missing)`` as they
    apply (the progress detail's and the CLI summary's words)."""
    text = f", {run.resumed} from the checkpoint" if run.resumed else ""
    if run.recomputed:
        text += f", {run.recomputed} run again (point files missing)"
    return text


def check_preset_sweeps(preset: Any) -> None:
    """The CLI's checks of a preset's sweeps before it runs them, without files: every
    ``[[sweep]]`` table read, its points counted and a sample of them made
    (:func:`~planar_tui.sweep.points.make_points`), each ``plot`` drawable, and the
    sweeps' workers, memory and time within the limits with the default workers
    (:func:`~planar_tui.sweep.budget.check_sweep_budget`); :class:`PresetError` otherwise.
    The app checks a document with it, so it says "ok" only for what the CLI runs."""
    prepared = [(sweep, make_points(sweep)) for sweep in parse_sweeps(preset)]
    for sweep, points in prepared:
        check_figure(sweep, points)
    check_sweep_budget(prepared, None, None)

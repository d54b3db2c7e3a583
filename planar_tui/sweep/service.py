"""A whole sweep for both front ends: points validated, outputs checked, points run
in-process or on Dask, finished points checkpointed as they arrive, the CSV written once
every point is done.

The app calls :func:`run_sweep` with its :class:`~planar_tui.progress.Progress` (cancel
through it) and ``on_outcome`` for rows as they finish; the CLI adds ``out_dir``,
``workers``/``scheduler`` and ``resume``.
"""

from __future__ import annotations

import secrets
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from planar_tui.csvio import CsvTable, write_atomic, write_csv_atomic
from planar_tui.progress import Progress
from planar_tui.sweep.checkpoint import CheckpointWriter, checkpoint_path, read_finished
from planar_tui.sweep.points import Point, make_points
from planar_tui.sweep.spec import Sweep
from planar_tui.sweep.table import sweep_table
from planar_tui.sweep.worker import FAILED, PointOutcome, PointTask


@dataclass
class SweepRun:
    """A sweep's points and their outcomes by point number (``resumed`` of them read from
    a checkpoint), and where its CSV went (``None`` when nothing was written)."""

    sweep: Sweep
    points: list[Point]
    outcomes: dict[int, PointOutcome] = field(default_factory=dict)
    resumed: int = 0
    output: Path | None = None
    figure: Path | None = None

    @property
    def failed(self) -> int:
        """How many points failed."""
        return sum(1 for outcome in self.outcomes.values() if outcome.status == FAILED)

    @property
    def table(self) -> CsvTable:
        """The sweep CSV of the points finished so far (all of them once it ran)."""
        values = {point.number: point.values for point in self.points}
        return sweep_table([path.text for path in self.sweep.paths], values, self.outcomes)


def write_figure(run: SweepRun, path: Path) -> Path:
    """Draw the sweep's figure (:mod:`planar_tui.figures.sweep`: a line against one
    varied key, a heat map against two) into ``path``, atomically; a sweep the figure
    cannot show (no varied key) is :class:`~planar_tui.batch.OutputFailed`."""
    from planar_tui.batch import OutputFailed
    from planar_tui.figures.dispatch import save_table_figure

    try:
        return save_table_figure(run.table, path, title=run.sweep.label)
    except OSError as error:
        raise OutputFailed(path, error.strerror or str(error)) from None
    except Exception as error:
        raise OutputFailed(path, f"cannot draw the figure: {error}") from None


def output_path(sweep: Sweep, out_dir: Path) -> Path:
    """The sweep's CSV in ``out_dir``."""
    return out_dir / sweep.output


def check_outputs(sweeps: Sequence[Sweep], out_dir: Path) -> None:
    """Refuse, before anything runs, a sweep CSV, checkpoint or point folder that cannot be
    written (:func:`planar_tui.batch.check_writable`), or two sweeps on one file."""
    from planar_tui.batch import _output_error, check_writable

    seen: dict[Path, str] = {}
    for sweep in sweeps:
        output = output_path(sweep, out_dir)
        paths = [output, checkpoint_path(output)]
        if sweep.point_outputs is not None:
            paths.append(out_dir / sweep.point_outputs / "point-1.csv")
        if sweep.plot is not None:
            paths.append(out_dir / sweep.plot)
        for path in paths:
            check_writable(path)
        identity = output.resolve()
        if identity in seen:
            raise _output_error(output, f"is written by both {seen[identity]} and {sweep.label}",
                                "one file per sweep (set distinct output paths)")  # fmt: skip
        seen[identity] = sweep.label


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
) -> SweepRun:
    """Run every point of ``sweep`` and return them (see :class:`SweepRun`).

    ``points`` are :func:`make_points`'s (made and validated here when not given: a
    :class:`~planar_tui.errors.PresetError` before anything runs). ``workers == 1`` without
    a ``scheduler`` runs in this process (no Dask import); otherwise a local Dask cluster
    of ``workers`` processes, or the scheduler at ``scheduler``; or the Dask ``client``
    given (e.g. one local cluster for several sweeps, :func:`execute.dask_client`). With ``out_dir`` the CSV,
    the checkpoint and the point CSVs are written there; ``resume`` continues from the
    checkpoint of the same sweep. ``progress`` counts points (figure ``failed``); its
    cancel, or Ctrl-C, stops the run with :class:`~planar_tui.errors.Cancelled` /
    ``KeyboardInterrupt``: the checkpoint stays, no CSV is written. ``on_outcome`` sees
    every point as it finishes (resumed ones first, in order).
    """
    from planar_tui.registry import JOB_KINDS  # noqa: F401 (the kinds' modules, loaded once)
    from planar_tui.sweep import execute
    from planar_tui.warmup import warm_kernels

    progress = progress or Progress()
    points = make_points(sweep) if points is None else points
    total = len(points)
    run = SweepRun(sweep, points)
    output = None if out_dir is None else output_path(sweep, out_dir)
    writer = None
    if output is not None:
        checkpoint = checkpoint_path(output)
        finished = read_finished(checkpoint, sweep.fingerprint(), total) if resume else {}
        writer = CheckpointWriter(checkpoint, sweep.fingerprint(), total, finished)
        run.outcomes.update(finished)
        run.resumed = len(finished)
    width = len(str(total))
    folder = (
        None if out_dir is None or sweep.point_outputs is None else out_dir / sweep.point_outputs
    )

    def stem(number: int) -> str | None:
        return None if sweep.point_outputs is None else f"point-{number:0{width}d}"

    tasks = [PointTask(p.number, p.job, stem(p.number)) for p in points
             if p.number not in run.outcomes]  # fmt: skip
    try:
        warm_kernels([sweep.job.kind], progress)
        progress.start(total, sweep.label, _detail(run))
        progress.advance(run.resumed, _detail(run), failed=run.failed)
        if on_outcome is not None:
            for number in sorted(run.outcomes):
                on_outcome(run.outcomes[number])

        def finished_point(outcome: PointOutcome) -> None:
            if folder is not None:
                for name, text in outcome.tables.items():
                    write_atomic(folder / name, lambda stream, text=text: stream.write(text))
            if writer is not None:
                writer.add(outcome)
            run.outcomes[outcome.number] = outcome
            progress.advance(1, _detail(run), failed=run.failed)
            if on_outcome is not None:
                on_outcome(outcome)

        prefix = f"planar-tui-{sweep.fingerprint()[:8]}-{secrets.token_hex(4)}"
        if client is not None:
            execute.run_on_dask(client, tasks, progress, finished_point, prefix)
        elif workers <= 1 and scheduler is None:
            execute.run_in_process(tasks, progress, finished_point)
        elif tasks:
            target = execute.DaskTarget(workers, scheduler)
            with execute.dask_client(target, announce) as client:
                execute.run_on_dask(client, tasks, progress, finished_point, prefix)
        if output is not None:
            write_csv_atomic(output, run.table)
            run.output = output
            if sweep.plot is not None:
                run.figure = write_figure(run, out_dir / sweep.plot)
    except BaseException:
        if writer is not None:
            writer.close()
        raise
    if writer is not None:
        writer.remove()
    return run


def _detail(run: SweepRun) -> str:
    done = len(run.outcomes)
    text = f"{done}/{len(run.points)} points, {run.failed} failed"
    return text + (f", {run.resumed} from the checkpoint" if run.resumed else "")

"""One point run: what a task carries (the point's settings, a few hundred bytes) and what
it returns (its summary figures, its status, optionally its CSV text).

:func:`run_point` is the function Dask workers call; the in-process runner calls it too,
with the sweep's progress for cancel. A point's arrays never leave the process that
computed it; only ``point_outputs`` brings its CSV tables back, as text.
"""

from __future__ import annotations

import io
import time
from dataclasses import dataclass, field
from typing import Any

from planar_tui import batch
from planar_tui.errors import Cancelled, PresetError
from planar_tui.jobkind import Job
from planar_tui.progress import Progress
from planar_tui.registry import JOB_KINDS
from planar_tui.runtime import configure_process, prepare_kernels

OK = "ok"
FAILED = "failed"
#: An optimisation's evaluation whose design its job refuses (a centre its working mode
#: cannot reach): the optimiser's constraint, not a failure (:attr:`PointTask.refused`).
INFEASIBLE = "infeasible"
#: A point a cancelled sweep did not run (a row of the app's partial table; never in a CSV
#: the CLI writes).
CANCELLED = "cancelled"


@dataclass(frozen=True)
class PointTask:
    """A point to run: its number, its job (parsed settings and robot: small, picklable)
    and whether its CSV tables are wanted (``point_outputs``), as ``stem`` + ``.csv`` and
    ``stem-TABLE.csv`` for the job's extra tables. ``refused`` is the status of a point
    whose job refuses its values (a :class:`~planar_tui.errors.PresetError`): ``failed``
    in a sweep, :data:`INFEASIBLE` in an optimisation."""

    number: int
    job: Job
    tables_stem: str | None = None
    refused: str = FAILED


@dataclass(frozen=True)
class PointOutcome:
    """A finished point: ``status`` ``ok``, ``failed`` or ``infeasible`` (an optimisation's
    design its job refuses) with its one-line ``message``,
    the kind's summary ``figures`` (name with unit -> number or text, in column order),
    the wall ``seconds`` and, when asked for, its CSV ``tables`` (file name -> text)."""

    number: int
    status: str
    message: str
    figures: dict[str, Any]
    seconds: float
    tables: dict[str, str] = field(default_factory=dict)


def _scalar(value: Any) -> Any:
    """A figure as a plain Python value (NumPy scalars unwrapped)."""
    return value.item() if hasattr(value, "item") and not isinstance(value, str) else value


def _one_line(text: str) -> str:
    return " ".join(str(text).split())


def _csv_text(table) -> str:
    buffer = io.StringIO()
    table.write(buffer)
    return buffer.getvalue()


def point_file_names(stem: str, job: Job) -> list[str]:
    """The CSV files a finished ``ok`` point of ``job`` writes with ``point_outputs``:
    ``stem.csv``, then ``stem-TABLE.csv`` for each of its kind's extra tables."""
    extras = JOB_KINDS[job.kind].extra_outputs(job)
    return [f"{stem}.csv", *(f"{stem}-{name}.csv" for name in extras)]


def run_point(task: PointTask, progress: Progress | None = None) -> PointOutcome:
    """Run one point through the batch service; any failure of the point (a box budget,
    no isotropic posture, a diverged result, an unexpected error) becomes a ``failed``
    outcome with a one-line message (values the job refuses: ``task.refused``). Only a
    cancel (:class:`Cancelled`, Ctrl-C) escapes."""
    configure_process()
    started = time.perf_counter()
    job = task.job
    kind = JOB_KINDS[job.kind]
    try:
        result = batch.run_job(job, progress or Progress())
        batch.check_finite(job, result)
        figures = {}
        if kind.point_figures is not None:
            figures = {name: _scalar(v) for name, v in kind.point_figures(job, result).items()}
        tables = {}
        if task.tables_stem is not None:
            texts = [_csv_text(result.table)]
            texts += [_csv_text(result.extra_tables[name]) for name in kind.extra_outputs(job)]
            tables = dict(zip(point_file_names(task.tables_stem, job), texts, strict=True))
        status, message = OK, ""
    except (Cancelled, KeyboardInterrupt):
        raise
    except PresetError as error:
        status, message, figures, tables = task.refused, _one_line(error.message), {}, {}
    except (batch.JobFailed, batch.NonFiniteResult) as error:
        status, message, figures, tables = FAILED, _one_line(str(error)), {}, {}
    except Exception as error:  # a figure that cannot be computed, say
        text = f"{job.label} failed: {type(error).__name__}: {error}"
        status, message, figures, tables = FAILED, _one_line(text), {}, {}
    return PointOutcome(
        task.number, status, message, figures, time.perf_counter() - started, tables
    )


def warm_worker(kind: str) -> None:
    """Load what a point of job kind ``kind`` needs in a worker process (the package, the
    kernels from the shared cache, by a tiny example job) before the first point: a
    start-up cost a benchmark keeps out of the points' timings."""
    from planar_tui.warmup import _run_example

    configure_process()
    prepare_kernels()
    _run_example(kind)

"""An optimisation run for both front ends: pymoo's ask-and-tell loop whose generations run
as sweep points (in this process or on Dask), each evaluation checkpointed as it arrives,
then the optimum (or the Pareto set) re-run at the job's own settings.

Determinism: evaluations are numbered in the order the optimiser asks for them and a
generation is told to it only once every evaluation of it is back, in number order, so
the CSV does not depend on which worker finished first; pymoo is seeded. ``--resume``
replays the optimiser: a number already in the checkpoint is not run again.

The objective of pymoo is ``F = sense · value`` (``sense`` −1 to maximise); the
constraints are ``G ≤ 0`` (:class:`~planar_tui.optimise.spec.Constraint`) plus one more,
``G = 1`` for an evaluation that is not ``ok`` (``0`` otherwise): a design its job refuses
(status ``infeasible``) or one whose job broke (``failed``).
"""

from __future__ import annotations

import math
import secrets
import time
from collections.abc import Callable, Sequence
from contextlib import ExitStack
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from planar_tui.batch import OutputFailed
from planar_tui.csvio import CsvTable, write_csv_atomic
from planar_tui.errors import PresetError
from planar_tui.figures.canvas import save
from planar_tui.figures.optimise import draw
from planar_tui.optimise.spec import Optimisation
from planar_tui.progress import Progress
from planar_tui.provenance import planned_sidecar, study_provenance, write_sidecar
from planar_tui.registry import JOB_KINDS
from planar_tui.sweep import execute
from planar_tui.sweep.checkpoint import CheckpointWriter, checkpoint_path, read_finished
from planar_tui.sweep.points import make_point
from planar_tui.sweep.worker import FAILED, INFEASIBLE, OK, PointOutcome, PointTask

if TYPE_CHECKING:
    from planar_tui.batch import PlannedFile


@dataclass(frozen=True)
class Evaluation:
    """Evaluation ``number`` (1-based, in the order asked) of ``generation``: the design's
    ``values`` (one per variable) and its outcome."""

    number: int
    generation: int
    values: tuple[Any, ...]
    outcome: PointOutcome


@dataclass
class OptimiseRun:
    """The evaluations so far (``resumed`` of them from the checkpoint), the certified
    re-runs of the optimum or Pareto set (evaluation, outcome at the job's own settings)
    and where the files went. A ``cancelled`` run (stopped part-way) keeps every finished
    evaluation, those of its last generation included."""

    optimisation: Optimisation
    evaluations: list[Evaluation] = field(default_factory=list)
    certified: list[tuple[Evaluation, PointOutcome]] = field(default_factory=list)
    resumed: int = 0
    generations: int = 0
    output: Path | None = None
    pareto: Path | None = None
    figure: Path | None = None
    figure_error: str | None = None
    checkpoint: Path | None = None
    cancelled: bool = False
    #: When the run started (epoch s), for the CSVs' provenance sidecars.
    started_s: float = field(default_factory=time.time)

    @property
    def failed(self) -> int:
        """Evaluations whose job broke (status ``failed``)."""
        return sum(1 for e in self.evaluations if e.outcome.status == FAILED)

    @property
    def infeasible(self) -> int:
        """Evaluations whose design the job refuses (status ``infeasible``: a centre its
        working mode cannot reach)."""
        return sum(1 for e in self.evaluations if e.outcome.status == INFEASIBLE)

    @property
    def table(self) -> CsvTable:
        """Every evaluation: number, generation, variables, the objectives' and
        constraints' columns, ``feasible``, ``status``, ``message``."""
        opt = self.optimisation
        header = (
            "evaluation",
            "generation",
            *(v.path.text for v in opt.variables),
            *opt.columns,
            "feasible",
            "status",
            "message",
        )
        rows = []
        for e in self.evaluations:
            figures = [e.outcome.figures.get(c, "") for c in opt.columns]
            rows.append(
                [
                    e.number,
                    e.generation,
                    *e.values,
                    *figures,
                    str(feasible(opt, e.outcome)).lower(),
                    e.outcome.status,
                    e.outcome.message,
                ]
            )
        return CsvTable(header, rows)

    def best(self) -> list[Evaluation]:
        """The optimum (one objective: the feasible evaluation of least ``F``, the first
        one on a tie) or the Pareto set (several: the feasible evaluations no other
        dominates, one per distinct design), in evaluation order."""
        return best_of(self.optimisation, self.evaluations)

    @property
    def optimum_table(self) -> CsvTable:
        """The certified optimum or Pareto set: evaluation, variables, the objectives as
        evaluated (``coarse_COLUMN``), then every column of the job's summary at its own
        settings (the certified bracket among them), ``status``, ``message``."""
        opt = self.optimisation
        columns: dict[str, None] = {}
        for _, outcome in self.certified:
            columns.update(dict.fromkeys(outcome.figures))
        names = [n for n in columns if n not in {v.path.text for v in opt.variables}]
        header = (
            "evaluation",
            *(v.path.text for v in opt.variables),
            *(f"coarse_{o.column}" for o in opt.objectives),
            *names,
            "status",
            "message",
        )
        rows = [
            [
                e.number,
                *e.values,
                *(e.outcome.figures[o.column] for o in opt.objectives),
                *(outcome.figures.get(n, "") for n in names),
                outcome.status,
                outcome.message,
            ]
            for e, outcome in self.certified
        ]
        return CsvTable(header, rows)


def number_of(opt: Optimisation, outcome: PointOutcome, column: str) -> float:
    """An evaluation's figure ``column`` as a float; a column the job does not report, or
    one that is no number, is a :class:`PresetError` naming the table (exit 2)."""
    value = outcome.figures.get(column)
    if value is None:
        raise PresetError(
            opt.preset_path,
            opt.name,
            f"names the column {column!r}, not one of the job's",
            "one of " + ", ".join(outcome.figures),
        )
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise PresetError(
            opt.preset_path,
            opt.name,
            f"names the column {column!r}, which is not a number ({value!r})",
            "a numeric column",
        )
    return float(value)


def feasible(opt: Optimisation, outcome: PointOutcome) -> bool:
    """Whether an evaluation succeeded and holds every constraint (its own operator)."""
    return outcome.status == OK and all(
        c.holds(number_of(opt, outcome, c.column)) for c in opt.constraints
    )


def objectives_of(opt: Optimisation, outcome: PointOutcome) -> tuple[float, ...]:
    """pymoo's ``F``: ``sense · value`` per objective."""
    return tuple(o.sense * number_of(opt, outcome, o.column) for o in opt.objectives)


def best_of(opt: Optimisation, evaluations: Sequence[Evaluation]) -> list[Evaluation]:
    """See :meth:`OptimiseRun.best`. ``a`` dominates ``b`` when ``F(a) ≤ F(b)`` in every
    objective and ``<`` in one."""
    candidates: dict[str, Evaluation] = {}
    for e in evaluations:
        if feasible(opt, e.outcome):
            candidates.setdefault(repr(e.values), e)  # choices may be lists
    scored = [(objectives_of(opt, e.outcome), e) for e in candidates.values()]
    if len(opt.objectives) == 1:
        return [min(scored, key=lambda s: (s[0], s[1].number))[1]] if scored else []

    def dominates(a: tuple[float, ...], b: tuple[float, ...]) -> bool:
        return all(x <= y for x, y in zip(a, b, strict=True)) and a != b

    front = [e for f, e in scored if not any(dominates(g, f) for g, _ in scored)]
    return sorted(front, key=lambda e: e.number)


def convergence(opt: Optimisation, evaluations: Sequence[Evaluation]) -> list[float]:
    """The best objective value (as the column's value) after each evaluation, ``nan``
    before the first feasible one (one objective)."""
    best, sense, history = math.inf, opt.objectives[0].sense, []
    for e in evaluations:
        if feasible(opt, e.outcome):
            best = min(best, sense * number_of(opt, e.outcome, opt.objectives[0].column))
        history.append(sense * best if math.isfinite(best) else math.nan)
    return history


def make_algorithm(opt: Optimisation) -> Any:
    """pymoo's algorithm on the problem (one real per variable, :attr:`Variable.bounds`),
    set up with the seed: a GA (or DE) for one objective, NSGA-II for several."""
    import numpy as np
    from pymoo.core.problem import Problem
    from pymoo.core.termination import NoTermination

    bounds = np.array([v.bounds for v in opt.variables], dtype=float)
    problem = Problem(
        n_var=len(opt.variables),
        n_obj=len(opt.objectives),
        n_ieq_constr=len(opt.constraints) + 1,
        xl=bounds[:, 0],
        xu=bounds[:, 1],
    )
    kind = opt.algorithm
    if kind == "auto":
        kind = "ga" if len(opt.objectives) == 1 else "nsga2"
    if kind == "de":
        from pymoo.algorithms.soo.nonconvex.de import DE

        algorithm = DE(pop_size=opt.population)
    elif kind == "nsga2":
        from pymoo.algorithms.moo.nsga2 import NSGA2

        algorithm = NSGA2(pop_size=opt.population)
    else:
        from pymoo.algorithms.soo.nonconvex.ga import GA

        algorithm = GA(pop_size=opt.population)
    algorithm.setup(problem, termination=NoTermination(), seed=opt.seed)
    return algorithm


def output_path(opt: Optimisation, out_dir: Path) -> Path:
    return out_dir / opt.output


def planned_files(opt: Optimisation, out_dir: Path) -> list[PlannedFile]:
    """Every file the optimisation writes (for :func:`planar_tui.batch.check_planned`)."""
    from planar_tui.batch import PlannedFile

    output = output_path(opt, out_dir)
    files = [
        PlannedFile(output, f"{opt.label} (output)"),
        PlannedFile(out_dir / opt.pareto_output, f"{opt.label} (pareto_output)"),
        PlannedFile(checkpoint_path(output), f"{opt.label} (checkpoint)"),
    ]
    files += planned_sidecar(files[0]) + planned_sidecar(files[1])
    if opt.plot is not None:
        files.append(PlannedFile(out_dir / opt.plot, f"{opt.label} (plot)", "figure file"))
    return files


class _Runner:
    """Runs point tasks in this process or on a Dask client, keeping their outcomes."""

    def __init__(self, client: Any, progress: Progress, prefix: str):
        self.client, self.progress, self.prefix = client, progress, prefix

    def run(self, tasks: list[PointTask], on_outcome: Callable[[PointOutcome], None]) -> None:
        if not tasks:
            return
        if self.client is None:
            execute.run_in_process(tasks, self.progress, on_outcome)
        else:
            prefix = f"{self.prefix}-{secrets.token_hex(3)}"
            execute.run_on_dask(self.client, tasks, self.progress, on_outcome, prefix)


def _task_or_failure(
    opt: Optimisation, number: int, values: tuple[Any, ...], coarse: bool
) -> PointTask | PointOutcome:
    """The task of one design, or its infeasible outcome when its job cannot be made (a
    value the job refuses: the evaluation is infeasible, the optimisation goes on; a job
    that refuses it only while running says so likewise, ``refused``)."""
    try:
        point = make_point(opt.sweep(coarse), number, opt.point_values(values, coarse))
    except PresetError as error:
        return PointOutcome(number, INFEASIBLE, " ".join(error.message.split()), {}, 0.0)
    return PointTask(number, point.job, refused=INFEASIBLE)


def run_optimisation(
    opt: Optimisation,
    progress: Progress | None = None,
    *,
    workers: int = 1,
    scheduler: str | None = None,
    client: Any = None,
    out_dir: Path | None = None,
    resume: bool = False,
    on_generation: Callable[[OptimiseRun], None] | None = None,
    announce: Callable[[str], None] = lambda text: None,
    keep_checkpoint: bool = False,
) -> OptimiseRun:
    """Run ``opt`` (see the module's docstring) and return it (:class:`OptimiseRun`).

    Where the evaluations run is :func:`planar_tui.sweep.service.run_sweep`'s choice:
    ``client``, else this process for ``workers == 1`` without ``scheduler``, else a
    local cluster or the scheduler. With ``out_dir`` every evaluation is appended to the
    checkpoint as it arrives (``resume`` continues it) and the CSVs and figure are written
    at the end. ``progress`` counts evaluations; its cancel or Ctrl-C propagates
    (:class:`~planar_tui.errors.Cancelled`, ``KeyboardInterrupt``) with the checkpoint
    kept. ``on_generation`` sees the run after each generation (the app's screen); a
    cancelled run is handed to it once more, ``cancelled``, before the cancel propagates."""
    import numpy as np

    from planar_tui.warmup import warm_kernels

    progress = progress or Progress()
    run = OptimiseRun(opt)
    output = None if out_dir is None else output_path(opt, out_dir)
    total = 2 * opt.budget  # evaluations, then at most one certified re-run each
    finished: dict[int, PointOutcome] = {}
    writer = None
    if output is not None:
        run.checkpoint = checkpoint_path(output)
        if resume:
            finished = read_finished(
                run.checkpoint,
                opt.fingerprint(),
                total,
                _columns_of(opt),
                lambda text: announce(f"warning: {text}"),
            )
        try:
            writer = CheckpointWriter(run.checkpoint, opt.fingerprint(), total, finished)
        except OSError as error:
            raise OutputFailed(run.checkpoint, error.strerror or str(error)) from None

    def keep(outcome: PointOutcome, outcomes: dict[int, PointOutcome]) -> None:
        if writer is not None:
            try:
                writer.add(outcome, sync=False)  # synced once a generation
            except OSError as error:
                raise OutputFailed(writer.path, error.strerror or str(error)) from None
        outcomes[outcome.number] = outcome
        progress.advance(1, _detail(run, len(outcomes)), failed=run.failed)

    def evaluate(
        numbered: list[tuple[int, tuple[Any, ...]]], coarse: bool, outcomes: dict[int, PointOutcome]
    ) -> dict[int, PointOutcome]:
        outcomes.update({n: finished[n] for n, _ in numbered if n in finished})
        run.resumed += len(outcomes)
        if outcomes:
            progress.advance(len(outcomes), _detail(run, len(outcomes)), failed=run.failed)
        tasks = []
        for number, values in numbered:
            if number in outcomes:
                continue
            task = _task_or_failure(opt, number, values, coarse)
            if isinstance(task, PointOutcome):
                keep(task, outcomes)
            else:
                tasks.append(task)
        runner.run(tasks, lambda outcome: keep(outcome, outcomes))
        return outcomes

    algorithm = make_algorithm(opt)
    try:
        with ExitStack() as stack:
            if client is None and (workers > 1 or scheduler is not None):
                target = execute.DaskTarget(workers, scheduler)
                client = stack.enter_context(execute.dask_client(target, announce))
            runner = _Runner(client, progress, f"planar-tui-opt-{opt.fingerprint()[:8]}")
            warm_kernels([opt.job.kind], progress)
            progress.start(opt.budget, opt.label, "starting")
            while len(run.evaluations) < opt.budget:
                population = algorithm.ask()
                population = population[: opt.budget - len(run.evaluations)]
                run.generations += 1
                start = len(run.evaluations)
                designs = [
                    (
                        start + i + 1,
                        tuple(v.decode(x) for v, x in zip(opt.variables, row, strict=True)),
                    )
                    for i, row in enumerate(population.get("X"))
                ]
                outcomes: dict[int, PointOutcome] = {}
                try:
                    evaluate(designs, True, outcomes)
                except BaseException:  # a cancel: the generation's finished ones are kept
                    run.cancelled = True
                    run.evaluations += [
                        Evaluation(n, run.generations, values, outcomes[n])
                        for n, values in designs
                        if n in outcomes
                    ]
                    if on_generation is not None:
                        on_generation(run)
                    raise
                generation = [
                    Evaluation(n, run.generations, values, outcomes[n]) for n, values in designs
                ]
                run.evaluations += generation
                if writer is not None:
                    _sync(writer)
                population.set(
                    "F",
                    np.array([_f(opt, e.outcome) for e in generation]),
                    "G",
                    np.array([_g(opt, e.outcome) for e in generation]),
                )
                algorithm.tell(infills=population)
                if on_generation is not None:
                    on_generation(run)
            best = run.best()
            progress.start(len(best), f"{opt.label} (certified)", "re-running the optimum")
            numbered = [(opt.budget + k, e.values) for k, e in enumerate(best, start=1)]
            outcomes = evaluate(numbered, False, {})
            if writer is not None:
                _sync(writer)
            run.certified = [(e, outcomes[opt.budget + k]) for k, e in enumerate(best, start=1)]
    except PresetError:  # the table names a column the job lacks: nothing to resume
        if writer is not None:
            writer.close()
            writer.path.unlink(missing_ok=True)
        raise
    finally:
        if writer is not None:
            writer.close()
    if out_dir is not None:
        _write_outputs(run, out_dir, keep_checkpoint)
    return run


def _columns_of(opt: Optimisation) -> Callable[[int], tuple[str, ...] | None]:
    """The figures a resumed evaluation's record must hold: the job's columns, where its
    kind names them without running (else ``None``: any)."""
    names = JOB_KINDS[opt.job.kind].figure_names
    columns = None if names is None else tuple(names(opt.job))
    return lambda number: columns


def _write_outputs(run: OptimiseRun, out_dir: Path, keep_checkpoint: bool) -> None:
    """The evaluations' and the optimum's CSVs (:class:`~planar_tui.batch.OutputFailed`
    if one cannot be written: the checkpoint stays), then the checkpoint goes (unless
    ``keep_checkpoint``) and the figure is drawn (its failure: ``run.figure_error``)."""
    opt = run.optimisation
    run.output, run.pareto = output_path(opt, out_dir), out_dir / opt.pareto_output
    record = study_provenance("optimise", opt, (run.started_s, time.time() - run.started_s))
    for path, table in ((run.output, run.table), (run.pareto, run.optimum_table)):
        try:
            write_csv_atomic(path, table)
            write_sidecar(path, record)
        except OSError as error:
            raise OutputFailed(path, error.strerror or str(error)) from None
    if run.checkpoint is not None and not keep_checkpoint:
        run.checkpoint.unlink(missing_ok=True)
        run.checkpoint = None
    if opt.plot is not None:
        try:
            run.figure = write_figure(run, out_dir / opt.plot)
        except OutputFailed as error:
            run.figure_error = str(error)


def _sync(writer: Any) -> None:
    """A generation's evaluations to disk (one ``fsync``: a machine crash loses at most
    the generation running; Ctrl-C or a killed process loses none, each is flushed)."""
    try:
        writer.sync()
    except OSError as error:
        raise OutputFailed(writer.path, error.strerror or str(error)) from None


def _f(opt: Optimisation, outcome: PointOutcome) -> tuple[float, ...]:
    if outcome.status != OK:
        return (0.0,) * len(opt.objectives)
    return objectives_of(opt, outcome)


def _g(opt: Optimisation, outcome: PointOutcome) -> tuple[float, ...]:
    if outcome.status != OK:
        return (0.0,) * len(opt.constraints) + (1.0,)
    return (*(c.g(number_of(opt, outcome, c.column)) for c in opt.constraints), 0.0)


def _detail(run: OptimiseRun, done: int) -> str:
    text = f"generation {run.generations}, {run.infeasible} infeasible, {run.failed} failed"
    return text + (f", {run.resumed} from the checkpoint" if run.resumed else "")


def write_figure(run: OptimiseRun, path: Path) -> Path:
    """The convergence (one objective) or front (two or more: the first two) figure
    (:mod:`planar_tui.figures.optimise`), written atomically."""
    try:
        return save(draw(figure_data(run)), path)
    except OSError as error:
        raise OutputFailed(path, error.strerror or str(error)) from None


def figure_data(run: OptimiseRun) -> dict[str, Any]:
    """What the figure draws: the objectives' names, every feasible evaluation's
    objective values, the best-so-far (one objective) and the optimum or front."""
    opt = run.optimisation
    ok = [e for e in run.evaluations if feasible(opt, e.outcome)]
    names = [o.column for o in opt.objectives]

    def values(evaluations: Sequence[Evaluation]) -> list[list[float]]:
        return [[number_of(opt, e.outcome, n) for n in names] for e in evaluations]

    return {
        "title": opt.label,
        "names": names,
        "numbers": [e.number for e in ok],
        "points": values(ok),
        "best": values(run.best()),
        "history": convergence(opt, run.evaluations) if len(names) == 1 else [],
    }

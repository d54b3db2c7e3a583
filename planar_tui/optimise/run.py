"""An optimisation run for both front ends: pymoo's ask-and-tell loop whose generations run
as sweep points (in this process or on Dask), each evaluation checkpointed as it arrives,
then the optimum (or the Pareto set) re-run at the job's own settings.

Determinism: evaluations are numbered in the order the optimiser asks for them and a
generation is told to it only once every evaluation of it is back, in number order, so
the CSV does not depend on which worker finished first; pymoo is seeded. ``--resume``
replays the optimiser: a number already in the checkpoint is not run again.

The objective of pymoo is ``F = sense · value`` (``sense`` −1 to maximise); the
constraints are ``G ≤ 0`` (:class:`~planar_tui.optimise.problem.Constraint`) plus one more,
``G = 1`` for an evaluation that is not ``ok`` (``0`` otherwise): a design its job refuses
(status ``infeasible``) or one whose job broke (``failed``).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from planar_tui.csvio import write_csv_atomic
from planar_tui.errors import OutputFailed, PresetError, writing
from planar_tui.figures.canvas import save
from planar_tui.figures.optimise import draw
from planar_tui.optimise.evaluations import (
    Evaluation,
    OptimiseRun,
    figure_data,
    number_of,
    objectives_of,
)
from planar_tui.optimise.problem import Optimisation
from planar_tui.progress import Progress
from planar_tui.provenance import planned_sidecar, study_provenance, write_sidecar
from planar_tui.registry import JOB_KINDS
from planar_tui.sweep import execute
from planar_tui.sweep.checkpoint import checkpoint_path
from planar_tui.sweep.points import make_point
from planar_tui.sweep.worker import INFEASIBLE, OK, PointOutcome, PointTask

if TYPE_CHECKING:
    from planar_tui.batch import PlannedFile
    from planar_tui.sweep.checkpoint import CheckpointWriter


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
    progress = progress or Progress()
    run = OptimiseRun(opt)
    output = None if out_dir is None else output_path(opt, out_dir)
    total = 2 * opt.budget  # evaluations, then at most one certified re-run each
    finished: dict[int, PointOutcome] = {}
    writer = None
    if output is not None:
        finished, writer = _open_checkpoint(run, output, total, resume, announce)
    evaluator = _Evaluator(run, progress, finished, writer)
    algorithm = make_algorithm(opt)
    try:
        prefix = f"planar-tui-opt-{opt.fingerprint()[:8]}"
        with execute.point_runner(client, workers, scheduler, announce, progress, prefix) as runner:
            evaluator.runner = runner
            _evolve(evaluator, algorithm, on_generation)
            _certify(evaluator)
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


@dataclass
class _Evaluator:
    """The evaluate stage: designs run on the point ``runner``, those the checkpoint
    finished (``finished``) taken from it; each outcome kept (checkpointed by ``writer``,
    synced once a generation, and counted by ``progress``)."""

    run: OptimiseRun
    progress: Progress
    finished: dict[int, PointOutcome]
    writer: CheckpointWriter | None
    runner: Any = None

    def keep(self, outcome: PointOutcome, outcomes: dict[int, PointOutcome]) -> None:
        """One outcome checkpointed, kept in ``outcomes`` and counted."""
        if self.writer is not None:
            self.writer.add(outcome, sync=False)  # synced once a generation
        outcomes[outcome.number] = outcome
        self.progress.advance(1, _detail(self.run, len(outcomes)), failed=self.run.failed)

    def evaluate(
        self,
        numbered: list[tuple[int, tuple[Any, ...]]],
        coarse: bool,
        outcomes: dict[int, PointOutcome],
    ) -> dict[int, PointOutcome]:
        """The outcomes of the ``numbered`` designs (into ``outcomes``): resumed ones first,
        a design whose job cannot be made infeasible, the others run."""
        run, progress = self.run, self.progress
        outcomes.update({n: self.finished[n] for n, _ in numbered if n in self.finished})
        run.resumed += len(outcomes)
        if outcomes:
            progress.advance(len(outcomes), _detail(run, len(outcomes)), failed=run.failed)
        tasks = []
        for number, values in numbered:
            if number in outcomes:
                continue
            task = _task_or_failure(run.optimisation, number, values, coarse)
            if isinstance(task, PointOutcome):
                self.keep(task, outcomes)
            else:
                tasks.append(task)
        if tasks:
            self.runner.run(tasks, lambda outcome: self.keep(outcome, outcomes))
        return outcomes


def _evolve(
    evaluator: _Evaluator, algorithm: Any, on_generation: Callable[[OptimiseRun], None] | None
) -> None:
    """The kernels warmed, then generations (:func:`_generation`) until the budget of
    evaluations is spent."""
    from planar_tui.warmup import warm_kernels

    run, opt = evaluator.run, evaluator.run.optimisation
    warm_kernels([opt.job.kind], evaluator.progress)
    evaluator.progress.start(opt.budget, opt.label, "starting")
    while len(run.evaluations) < opt.budget:
        _generation(evaluator, algorithm, on_generation)


def _generation(
    evaluator: _Evaluator, algorithm: Any, on_generation: Callable[[OptimiseRun], None] | None
) -> None:
    """One generation: ask pymoo, evaluate (coarse), tell; ``on_generation`` sees the run
    after it, and once more, ``cancelled``, when a cancel stops it (the generation's
    finished evaluations are kept)."""
    run = evaluator.run
    population, designs = _ask(run, algorithm)
    outcomes: dict[int, PointOutcome] = {}
    try:
        evaluator.evaluate(designs, True, outcomes)
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
    generation = [Evaluation(n, run.generations, values, outcomes[n]) for n, values in designs]
    run.evaluations += generation
    if evaluator.writer is not None:  # one fsync a generation: a machine crash loses at
        evaluator.writer.sync()  # most the generation running (each evaluation is flushed)
    _tell(run.optimisation, algorithm, population, generation)
    if on_generation is not None:
        on_generation(run)


def _certify(evaluator: _Evaluator) -> None:
    """The certify stage: the optimum's evaluations re-run at the job's own precision
    (numbered after the budget), into ``run.certified``."""
    run, opt = evaluator.run, evaluator.run.optimisation
    best = run.best()
    evaluator.progress.start(len(best), f"{opt.label} (certified)", "re-running the optimum")
    numbered = [(opt.budget + k, e.values) for k, e in enumerate(best, start=1)]
    outcomes = evaluator.evaluate(numbered, False, {})
    if evaluator.writer is not None:
        evaluator.writer.sync()
    run.certified = [(e, outcomes[opt.budget + k]) for k, e in enumerate(best, start=1)]


def _open_checkpoint(
    run: OptimiseRun, output: Path, total: int, resume: bool, announce: Callable[[str], None]
) -> tuple[dict[int, PointOutcome], CheckpointWriter]:
    """The optimisation's checkpoint beside ``output`` (``run.checkpoint``), started afresh
    or, with ``resume``, with its finished evaluations kept (returned by number; a record
    that is not one is dropped with one ``announce`` warning)."""
    from planar_tui.sweep.checkpoint import CheckpointWriter, checkpoint_path, read_finished

    opt = run.optimisation
    run.checkpoint = checkpoint_path(output)
    finished: dict[int, PointOutcome] = {}
    if resume:
        finished = read_finished(
            run.checkpoint,
            opt.fingerprint(),
            total,
            _columns_of(opt),
            lambda text: announce(f"warning: {text}"),
        )
    return finished, CheckpointWriter(run.checkpoint, opt.fingerprint(), total, finished)


def _ask(run: OptimiseRun, algorithm: Any) -> tuple[Any, list[tuple[int, tuple[Any, ...]]]]:
    """The next generation (``run.generations`` counts it): pymoo's population, cut to the
    budget left, and its designs numbered on from the evaluations so far, each decoded to
    the variables' TOML values."""
    opt = run.optimisation
    population = algorithm.ask()
    population = population[: opt.budget - len(run.evaluations)]
    run.generations += 1
    start = len(run.evaluations)
    designs = [
        (start + i + 1, tuple(v.decode(x) for v, x in zip(opt.variables, row, strict=True)))
        for i, row in enumerate(population.get("X"))
    ]
    return population, designs


def _tell(opt: Optimisation, algorithm: Any, population: Any, generation: list[Evaluation]) -> None:
    """Tell pymoo a generation's ``F`` (``sense · value``) and ``G`` (constraints, then 1
    for an evaluation that is not ``ok``)."""
    import numpy as np

    population.set(
        "F",
        np.array([_f(opt, e.outcome) for e in generation]),
        "G",
        np.array([_g(opt, e.outcome) for e in generation]),
    )
    algorithm.tell(infills=population)


def _columns_of(opt: Optimisation) -> Callable[[int], tuple[str, ...] | None]:
    """The figures a resumed evaluation's record must hold: the job's columns, where its
    kind names them without running (else ``None``: any)."""
    names = JOB_KINDS[opt.job.kind].figure_names
    columns = None if names is None else tuple(names(opt.job))
    return lambda number: columns


def _write_outputs(run: OptimiseRun, out_dir: Path, keep_checkpoint: bool) -> None:
    """The evaluations' and the optimum's CSVs (:class:`~planar_tui.errors.OutputFailed`
    if one cannot be written: the checkpoint stays), then the checkpoint goes (unless
    ``keep_checkpoint``) and the figure is drawn (its failure: ``run.figure_error``)."""
    opt = run.optimisation
    run.output, run.pareto = output_path(opt, out_dir), out_dir / opt.pareto_output
    record = study_provenance("optimise", opt, (run.started_s, time.time() - run.started_s))
    for path, table in ((run.output, run.table), (run.pareto, run.optimum_table)):
        with writing(path):
            write_csv_atomic(path, table)
            write_sidecar(path, record)
    if run.checkpoint is not None and not keep_checkpoint:
        run.checkpoint.unlink(missing_ok=True)
        run.checkpoint = None
    if opt.plot is not None:
        try:
            run.figure = write_figure(run, out_dir / opt.plot)
        except OutputFailed as error:
            run.figure_error = str(error)


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
    with writing(path):
        return save(draw(figure_data(run)), path)

"""One run plan for both front ends: which jobs and sweeps run, every file they write
(checked once, together, before anything runs) and what happens to sweeps' checkpoints.

:func:`plan_run` builds it from the jobs (parsed, selected and overridden) and the presets
whose sweeps run; the CLI turns its options into one call and prints, the app plans its
"run all" and its sweeps here too. Everything that can be refused is refused here, so a
run that starts writes nothing it was not allowed to: a figure its kind cannot draw, an
output path that cannot be written or that two writers share, a sweep's unreadable point,
a sweep figure without a varied key, a checkpoint of an interrupted run without
``--resume``. New kinds of work (an optimisation, say) add their planned entries and files
to :class:`RunPlan` and are checked with the rest.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from planar_tui.batch import (
    OutputPlan,
    PlannedFile,
    check_planned,
    numbered_path,
    plan_files,
    plan_outputs,
    prepare_jobs,
)
from planar_tui.errors import PresetError
from planar_tui.optimise import TABLE as OPTIMISE_TABLE
from planar_tui.registry import JOB_KINDS
from planar_tui.sweep import TABLE as SWEEP_TABLE

if TYPE_CHECKING:
    from planar_tui.jobkind import Job
    from planar_tui.optimise.problem import Optimisation
    from planar_tui.presets import Preset
    from planar_tui.sweep.points import Point
    from planar_tui.sweep.spec import Sweep


@dataclass(frozen=True)
class SweepPlan:
    """One sweep with its validated points (:func:`planar_tui.sweep.points.make_points`)."""

    sweep: Sweep
    points: Sequence[Point]


@dataclass(frozen=True)
class RunPlan:
    """What a run does, in order: ``jobs`` (each with its files, prepared unless the plan
    was made with ``prepare=False``), then ``sweeps``, then ``optimisations``; ``out_dir`` is where the presets'
    names point (``None``: nothing is written, the app's sweeps); ``resume`` continues the
    sweeps from their checkpoints; ``notes`` are what the front end says before it runs
    (a checkpoint of an earlier version of a sweep that is replaced)."""

    jobs: tuple[OutputPlan, ...] = ()
    sweeps: tuple[SweepPlan, ...] = ()
    optimisations: tuple[Optimisation, ...] = ()
    out_dir: Path | None = None
    resume: bool = False
    notes: tuple[str, ...] = ()

    def files(self) -> list[PlannedFile]:
        """Every file the run writes (jobs' CSVs, extra tables and figures; sweeps' CSVs,
        checkpoints, figures and point-file folders)."""
        files = plan_files(self.jobs)
        if self.out_dir is not None and self.sweeps:
            from planar_tui.sweep.service import planned_files

            files += [f for entry in self.sweeps for f in planned_files(entry.sweep, self.out_dir)]
        if self.out_dir is not None and self.optimisations:
            from planar_tui.optimise.run import planned_files as optimise_files

            files += [f for o in self.optimisations for f in optimise_files(o, self.out_dir)]
        return files


def check_figures(jobs: Sequence[Job[Any, Any]], plot: Path | None) -> None:
    """Refuse a figure for a job whose kind draws none (:class:`PresetError`, one line),
    asked by ``--plot`` (``plot``) or by the job's ``plot`` key."""
    from planar_tui.figures.dispatch import figure_problem

    for job in jobs:
        problem = figure_problem(job.kind)
        if problem is None:
            continue
        if plot is not None:
            raise PresetError(
                "command line",
                "--plot",
                f"{job.label}: {problem}",
                f"no --plot for a {job.kind} job",
            )
        if getattr(job.spec, "plot", None):
            raise PresetError(job.preset_path, f"{job.key}.plot", problem, "no plot key")


def check_has_work(preset: Preset) -> None:
    """Refuse a preset with neither a job nor a sweep table (nothing to run:
    :class:`PresetError`, exit code 2, rather than a silent success)."""
    if not preset.jobs and preset.raw.get(SWEEP_TABLE) is None:
        kinds = ", ".join(f"[{name}]" for name in JOB_KINDS)
        raise PresetError(
            preset.path,
            "(file)",
            "has no job and no [[sweep]] table: nothing to run",
            f"a job table ({kinds}) or a [[sweep]] table",
        )


def has_studies(preset: Preset) -> bool:
    """Whether ``preset`` holds a sweep or an optimisation table (a run of the others
    imports no sweep or optimisation module)."""
    return SWEEP_TABLE in preset.raw or OPTIMISE_TABLE in preset.raw


def plan_sweeps(
    presets: Sequence[Preset], plot: Path | None = None
) -> tuple[list[Sweep], list[SweepPlan]]:
    """The presets' sweeps with their points, every point validated; ``plot`` (the
    command line's) replaces their ``plot`` keys, numbered ``FILE-1.png`` ... for several,
    taken from the current folder as the jobs' ``--plot`` is (not from the output folder
    as the preset's key is)."""
    from planar_tui.sweep.points import make_points
    from planar_tui.sweep.spec import parse_sweeps

    sweeps = [sweep for preset in presets for sweep in parse_sweeps(preset)]
    if plot is not None:
        sweeps = [
            dataclasses.replace(
                sweep, plot=str(numbered_path(plot, number, len(sweeps)).absolute())
            )
            for number, sweep in enumerate(sweeps, start=1)
        ]
    return sweeps, [SweepPlan(sweep, make_points(sweep)) for sweep in sweeps]


def plan_sweep(sweep: Sweep) -> SweepPlan:
    """One sweep built elsewhere (the app's sweep dialog), its points validated."""
    from planar_tui.sweep.points import make_points

    return SweepPlan(sweep, make_points(sweep))


def checkpoint_notes(sweeps: Sequence[SweepPlan], out_dir: Path, resume: bool) -> list[str]:
    """Decide each sweep's checkpoint: none, or one to resume (with ``resume``) is fine;
    one of the same sweep without ``resume`` is refused (:class:`PresetError`); one of an
    earlier version of the sweep is replaced, and said in the note returned."""
    from planar_tui.sweep.service import output_path

    return [
        note
        for entry in sweeps
        if (
            note := checkpoint_note(
                entry.sweep.label,
                entry.sweep.fingerprint(),
                output_path(entry.sweep, out_dir),
                resume,
            )
        )
        is not None
    ]


def checkpoint_note(label: str, fingerprint: str, output: Path, resume: bool) -> str | None:
    """One study's checkpoint (a sweep's or an optimisation's, ``label``, writing
    ``output``) decided as :func:`checkpoint_notes` says: ``None``, a note, or refused."""
    from planar_tui.sweep.checkpoint import checkpoint_path, existing_fingerprint

    checkpoint = checkpoint_path(output)
    found = existing_fingerprint(checkpoint)
    if found is None or (resume and found == fingerprint):
        return None
    if found == fingerprint:
        raise PresetError(
            checkpoint,
            "(checkpoint)",
            f"holds finished points of {label}, an interrupted run",
            "--resume to finish it, or delete the file to start over",
        )
    return (
        f"note: {checkpoint} belongs to an earlier version of {label} (the preset "
        "changed): it is replaced"
    )


def plan_optimisations(presets: Sequence[Preset], plot: Path | None = None) -> list[Optimisation]:
    """The presets' optimisations, checked; ``plot`` replaces their ``plot`` keys as
    :func:`plan_sweeps`' does."""
    from planar_tui.optimise.spec import parse_optimisations

    found = [o for preset in presets for o in parse_optimisations(preset)]
    if plot is None:
        return found
    return [
        dataclasses.replace(o, plot=str(numbered_path(plot, k, len(found)).absolute()))
        for k, o in enumerate(found, start=1)
    ]


def plan_run(
    jobs: Sequence[Job[Any, Any]],
    out_dir: Path,
    *,
    out: Path | None = None,
    extra_out: Mapping[str, Path | None] | None = None,
    plot: Path | None = None,
    sweeps_of: Sequence[Preset] = (),
    sweep_plot: Path | None = None,
    resume: bool = False,
    prepare: bool = True,
    optimise_of: Sequence[Preset] = (),
    optimise_plot: Path | None = None,
    workers: int | None = None,
    scheduler: str | None = None,
) -> RunPlan:
    """The run of ``jobs`` (their files named by :func:`planar_tui.batch.plan_outputs`
    from ``out``, ``extra_out`` and ``plot``) and of the sweeps of ``sweeps_of`` (their
    figures under ``sweep_plot``), all refused before anything runs if anything is wrong
    (:class:`PresetError`): figures (:func:`check_figures`), every planned file once
    (:func:`planar_tui.batch.check_planned`, the presets protected), the sweeps' figures
    and checkpoints (:func:`checkpoint_notes`), their point folders
    (:func:`planar_tui.sweep.service.check_point_outputs`), their workers, memory and time
    on ``workers`` (the machine's cores when ``None``) or a ``scheduler``
    (:func:`planar_tui.sweep.budget.check_sweep_budget`), the optimisations of
    ``optimise_of`` (their figures under ``optimise_plot``) and their checkpoints, then
    (``prepare``) every job prepared by its kind (:func:`planar_tui.batch.prepare_jobs`)."""
    check_figures(jobs, plot)
    outputs = plan_outputs(jobs, out_dir, out, extra_out, plot)
    sweeps_of = [preset for preset in sweeps_of if SWEEP_TABLE in preset.raw]
    sweeps, sweep_plans = plan_sweeps(sweeps_of, sweep_plot) if sweeps_of else ([], [])
    optimise_of = [preset for preset in optimise_of if OPTIMISE_TABLE in preset.raw]
    optimisations = plan_optimisations(optimise_of, optimise_plot) if optimise_of else []
    plan = RunPlan(tuple(outputs), tuple(sweep_plans), tuple(optimisations), out_dir, resume)
    presets: dict[Path, str] = {job.preset_path: job.label for job in jobs}
    presets.update({sweep.preset_path: sweep.label for sweep in sweeps})
    presets.update({o.preset_path: o.label for o in optimisations})
    check_planned(plan.files(), presets)
    if sweep_plans:  # a run of jobs alone imports no sweep module
        from planar_tui.sweep.budget import check_sweep_budget
        from planar_tui.sweep.service import check_figure, check_point_outputs

        for entry in sweep_plans:
            check_figure(entry.sweep, entry.points)
            check_point_outputs(entry.sweep, out_dir)
        check_sweep_budget([(e.sweep, e.points) for e in sweep_plans], workers, scheduler)
    if optimisations:
        from planar_tui.optimise.budget import check_optimise_budget

        check_optimise_budget(optimisations, workers, scheduler)
    notes = checkpoint_notes(sweep_plans, out_dir, resume) if sweep_plans else []
    for o in optimisations:
        note = checkpoint_note(o.label, o.fingerprint(), out_dir / o.output, resume)
        notes += [note] if note is not None else []
    if prepare and outputs:
        prepared = prepare_jobs(jobs)
        outputs = [dataclasses.replace(o, job=j) for o, j in zip(outputs, prepared, strict=True)]
    return dataclasses.replace(plan, jobs=tuple(outputs), notes=tuple(notes))

"""The ``[motion_uncertainty]`` job: how tolerances on lengths and masses move the robot.

Every link length and mass (optionally inertia) is uniform on ``nominal ± tolerance`` (as
in ``[sensitivity]``); every sampled robot is integrated by RK4 under the constant torques
(as in ``[simulate]``). Results: the band (mean, standard deviation, 5/50/95 % percentiles of
every output at every recorded step, over independent uniform robots: the Monte-Carlo or
Sobol' A/B robots, or N extra Monte-Carlo robots when eFAST runs alone), Sobol'/eFAST/PCE
indices of every output at every recorded time (Sobol'/eFAST's confidence intervals at the
times ``at_s`` only) and aggregated over each trajectory, a Table-4-shaped table per time
of ``at_s``. Details: ``docs/motion.md``.
"""

from __future__ import annotations

from typing import Any

from planar_tui import uq
from planar_tui.jobkind import Command, JobKind, Option, Tab
from planar_tui.motion.runner import (
    MotionResult,
    check_motion,
    prepare_motion,
    run_motion,
)
from planar_tui.motion.spec import METHODS, MotionJob, MotionSpec, resource_estimate


def indices_file(job: MotionJob) -> str:
    """The indices CSV's name: ``indices_output``, else ``OUTPUT-indices.csv`` beside the
    job's ``output``."""
    if job.spec.indices_output:
        return job.spec.indices_output
    stem = job.output[:-4] if job.output.lower().endswith(".csv") else job.output
    return f"{stem}-indices.csv"


def extra_outputs(job: MotionJob) -> dict[str, str]:
    """The indices CSV when an index method runs, and the aggregated indices' CSV beside
    it (``-indices`` → ``-aggregated``)."""
    files = {}
    if any(uq.METHODS[method].indices for method in job.spec.methods):
        files["indices"] = indices_file(job)
        stem = (
            files["indices"][:-4] if files["indices"].lower().endswith(".csv") else files["indices"]
        )
        stem = stem[: -len("-indices")] if stem.endswith("-indices") else stem
        files["aggregated"] = f"{stem}-aggregated.csv"
    return files


_WARMUP_JOB = (
    "[[motion_uncertainty]]\nduration_s = 0.002\nstep_s = 0.001\nsamples = 128\n"
    'methods = ["montecarlo", "sobol", "efast"]\n'
)
#: The warm-up examples (:mod:`planar_tui.warmup`): every method on the robot kind's
#: 2-link example (the general lane kernel, the designs and estimators), and Monte Carlo on
#: a :data:`~kernels.motion_lanes.FUSED_LINKS`-link chain, its own robot (the fused step;
#: the general part runs after it in the same process, sharing the general lane kernels:
#: :data:`planar_tui.warmup_schedule.SHARES`).
WARMUP_PARTS = {
    "general": _WARMUP_JOB,
    "fused": "[robot]\nlengths_m = [0.3, 0.25, 0.2, 0.2, 0.15, 0.15]\n"
    "masses_kg = [0.5, 0.5, 0.4, 0.4, 0.3, 0.3]\n"
    "[[motion_uncertainty]]\nduration_s = 0.002\nstep_s = 0.001\nsamples = 128\n"
    'methods = ["montecarlo"]\n',
}


def warmup_parts(job: MotionJob) -> tuple[str, ...]:
    """The warm-up parts a run of ``job`` needs: the fused step's too for a chain of
    :data:`~kernels.motion_lanes.FUSED_LINKS` links."""
    from planar_tui.kernels.motion_lanes import FUSED_LINKS

    return ("general", "fused") if len(job.robot.lengths_m) == FUSED_LINKS else ("general",)


def render_motion(job: MotionJob, result: MotionResult, console: Any) -> None:
    """The CLI view: the band at the end and a Table-4-shaped table per time."""
    from planar_tui.motion.results import render

    render(job, result, console)


def point_figures(job: MotionJob, result: MotionResult) -> dict[str, Any]:
    """A sweep row's figures: per output its mean and standard deviation at the last
    recorded time, and the parameter of largest total index (first index method, last
    time) per output."""
    from planar_tui.motion.results import figures

    return figures(result)


JOB_KIND = JobKind(
    name="motion_uncertainty",
    robot_kind="robot",
    settings=MotionSpec,
    run=run_motion,
    summary="Monte-Carlo band and Sobol'/eFAST/PCE indices of the motion under tolerances",
    render=render_motion,
    extra_outputs=extra_outputs,
    prepare=prepare_motion,
    check=check_motion,
    point_figures=point_figures,
    command=Command(
        "motion",
        "Monte-Carlo band and Sobol'/eFAST/PCE indices of the motion of every "
        "motion_uncertainty job under length and mass tolerances: band CSV, indices CSV at "
        "every recorded time (the job's indices_output, or OUTPUT-indices.csv), aggregated "
        "indices CSV (OUTPUT-aggregated.csv) and a Table-4-shaped table per time of at_s.\n\n"
        "An option that changes a job's setting is appended to the stem of the files the preset "
        "names; a name given with --out is kept.",
        options=(
            *uq.sampling_options(METHODS, "N"),
            Option("--device", "device", "cpu, cuda or auto; overrides `device`."),
        ),
    ),
    tab=Tab(
        "Motion",
        5,
        "planar_tui.app.widgets.motion_pane:MotionPane",
        view="Output",
        view_help="the next output (θ1…θn, tip x, tip y)",
    ),
    figure="planar_tui.figures.dispatch:from_main_table",
    warmup=WARMUP_PARTS,
    warmup_parts=warmup_parts,
    estimate=lambda job: resource_estimate(job.spec, job.robot),
    app_default={
        "duration_s": 0.5,
        "step_s": 0.001,
        "tolerance_length_mm": 1.0,
        "tolerance_mass_g": 10.0,
        "methods": ["montecarlo", "sobol"],
        "samples": 128,
        "seed": 42,
        "output": "app-motion.csv",
    },
)

"""Runner of the ``[sensitivity]`` job: sample, evaluate, analyse, tabulate.

Progress goes through three stages (sampling, evaluation, analysis); a cancel raises
:class:`~planar_tui.errors.Cancelled` between chunks and the CLI then writes nothing.
"""

from __future__ import annotations

import math

import numpy as np

from planar_tui.jobs.base import JobResult
from planar_tui.presets import Job
from planar_tui.progress import Progress
from planar_tui.sensitivity.engine import (
    analyse,
    build_problem,
    default_efast_samples,
    evaluate,
    unit_design,
)
from planar_tui.sensitivity.results import Analysis, csv_table, sensitivity_percent


def robot_label(robot) -> str:
    """The robot's name, or ``nR`` when it has none."""
    return robot.name or f"{robot.n_links}R"


def sample_sizes(spec, num_vars: int) -> dict[str, int]:
    """N per method: the Sobol' base N, and eFAST's (given, or matching the Sobol' cost)."""
    efast = spec.efast_samples or default_efast_samples(spec.samples, num_vars)
    return {"sobol": spec.samples, "efast": efast}


def run_sensitivity(job: Job, progress: Progress) -> JobResult:
    """Indices of every torque for every method and speed of one job (one posture)."""
    spec, robot = job.spec, job.robot
    problem = build_problem(
        robot, spec.tolerance_length_m, spec.tolerance_mass_kg, spec.tolerance_inertia_kgm2
    )
    sizes = sample_sizes(spec, problem.num_vars)
    progress.start(len(spec.methods), "sampling")
    designs = {}
    for method in spec.methods:
        designs[method] = unit_design(method, problem.num_vars, sizes[method], spec.seed)
        progress.advance(1, method)
    states = [(method, speed) for speed in spec.speeds_rad_s for method in spec.methods]
    n = robot.n_links
    alpha = np.full(n, spec.alpha_rad_s2)
    theta = np.array(spec.posture.theta_rad)
    progress.start(len(states), "evaluation")
    outputs = {}
    for method, speed in states:
        omega = np.full(n, speed)
        outputs[method, speed] = evaluate(problem, designs[method], robot, theta, omega, alpha)
        progress.advance(1, f"{method} {speed:g} rad/s")
    progress.start(len(states), "analysis")
    analyses = []
    for method, speed in states:
        indices = analyse(method, outputs.pop((method, speed)), problem.num_vars, spec.seed)
        percent = sensitivity_percent(indices, spec.percent_of)
        analyses.append(
            Analysis(method, spec.posture.label, speed, problem.names, indices, percent)
        )
        progress.advance(1, f"{method} {speed:g} rad/s")
    label = robot_label(robot)
    kappa = spec.posture.condition_number
    sobol_conf = [float(a.indices[[1, 3]].max()) for a in analyses if a.method == "sobol"]
    summary = (
        f"{label} {spec.posture.label}"
        + (f" (κ = {kappa:.6g})" if math.isfinite(kappa) else "")
        + f", {len(spec.speeds_rad_s)} speed(s), "
        + ", ".join(f"{m} N={sizes[m]}" for m in spec.methods)
        + (f", max Sobol' CI ±{max(sobol_conf):.4f}" if sobol_conf else "")
    )
    data = {"robot": label, "posture": spec.posture, "analyses": analyses, "samples": sizes}
    return JobResult(table=csv_table(label, analyses), summary=summary, data=data)

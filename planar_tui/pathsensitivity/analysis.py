"""The path-sensitivity runner: designs, every robot along the path, the indices.

The estimators and tables are the serial arm's path study's
(:mod:`planar_tui.sensitivity.path`): indices of each actuator's peak |effort| and RMS
effort (the main table), of every effort at every step (``path``) and aggregated over the
path (Gamboa et al. 2014, weighted by the efforts' variances over independent uniform
robots: ``path_aggregated``).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from planar_tui.errors import JobError
from planar_tui.jobkind import JobResult, PreparedJob
from planar_tui.pathsensitivity.sizes import inputs_of, sample_sizes
from planar_tui.progress import Progress
from planar_tui.sensitivity.path import effort_names, path_labels, path_tables, path_variances
from planar_tui.sensitivity.runner import analyse_outputs
from planar_tui.workspace.path.model import OK, problem_text


def path_context(spec: Any) -> str:
    """A table's title: the path from, to, in how long."""

    def pose(values: tuple[float, ...]) -> str:
        return "[" + ", ".join(f"{v:g}" for v in values) + "]"

    return f"path {pose(spec.from_pose)} → {pose(spec.to_pose)} in {spec.duration_s:g} s"


@dataclass(frozen=True, kw_only=True)
class PathSensitivityResult(JobResult):
    """Indices of one job: per method an
    :class:`~planar_tui.sensitivity.results.Analysis` of the peak and RMS efforts
    (``analyses``), the inputs' names, N per method, and each robot's efforts' nominal
    peak and RMS (``nominal``: (2, k))."""

    robot_label: str
    analyses: list[Any]
    names: tuple[str, ...]
    samples: dict[str, int] = field(default_factory=dict)
    nominal: Any = None


def _listed(values: Any) -> str:
    return "[" + ", ".join(f"{v:.4g}" for v in values) + "]"


def nominal_efforts(ready: PreparedJob[Any, Any, Any], states: Any) -> Any:
    """The nominal robot's efforts (K + 1, k) along the path; a path it cannot follow
    fails the job as its path job would (exit 1, the first failing time named)."""
    import numpy as np

    spec = ready.prepared
    solution = spec.mechanism.inverse_dynamics(
        ready.robot, spec, states.pose, states.rate, states.acceleration
    )
    bad = np.flatnonzero(solution.status != OK)
    if len(bad):
        k = int(bad[0])
        raise JobError(
            ready.preset_path,
            ready.key,
            f"the nominal robot's path fails at t = {states.times_s[k]:.6g} s (step {k}): "
            f"{problem_text(int(solution.status[k]))}",
            "a path inside the workspace, off its singularities",
        )
    return solution.effort


def analyse_varying(
    ready: PreparedJob[Any, Any, Any],
    problem: Any,
    method: str,
    unit: Any,
    values: Any,
    progress: Progress,
) -> tuple[Any, Any, Any, str]:
    """``(indices, loo, varying, note)``:
    :func:`~planar_tui.sensitivity.runner.analyse_outputs` of the outputs that vary over the
    robots; one that does not (a torque at rest on a horizontal machine: 0 for every robot)
    has no variance to apportion and no indices (``varying`` false: empty cells in the CSV,
    zeros in the arrays), as the motion job's (a failed run's NaN counts as varying, so it
    is still caught)."""
    import numpy as np

    varying = ~(values == values[:1]).all(axis=0)
    indices = np.zeros((4, values.shape[1], problem.num_vars))
    loo = np.zeros(values.shape[1]) if method == "pce" else None
    if not varying.any():
        progress.advance(1.0, method)
        return indices, loo, varying, ""
    found, found_loo, note = analyse_outputs(
        ready, problem, method, unit, values[:, varying], progress, method
    )
    indices[:, varying] = found
    if loo is not None:
        loo[varying] = found_loo
    return indices, loo, varying, note


def analyse_path(ready: PreparedJob[Any, Any, Any], progress: Progress) -> PathSensitivityResult:
    """Indices of the peak, RMS and per-step efforts for every method of one job."""
    import numpy as np

    from planar_tui.pathsensitivity.engine import (
        design_efforts,
        path_outputs,
        path_states,
        scaled,
    )
    from planar_tui.sensitivity.engine import Problem, montecarlo_design, unit_design
    from planar_tui.sensitivity.pce import pce_unit_design
    from planar_tui.sensitivity.results import Analysis, csv_table, sensitivity_percent

    spec, robot = ready.prepared, ready.robot
    inputs = inputs_of(spec, robot)
    names = tuple(i.name for i in inputs)
    model = spec.mechanism.path_model(robot)
    actuators = model.actuators
    nominal = np.array([i.nominal for i in inputs])
    half = np.array([i.half_width for i in inputs])
    problem = Problem(names, nominal - half, nominal + half, actuators)
    sizes = sample_sizes(spec, len(inputs))
    states = path_states(spec)
    efforts = nominal_efforts(ready, states)
    progress.start(len(spec.methods), "sampling")
    designs = {}
    for method in spec.methods:
        if method == "pce":
            designs[method] = pce_unit_design(len(inputs), sizes[method], spec.seed)
            progress.advance(1.0, method)
        else:
            designs[method] = unit_design(method, len(inputs), sizes[method], spec.seed, progress)
    extra = {}
    progress.start(len(spec.methods) + ("efast" in spec.methods), "evaluation")
    if "efast" in spec.methods:  # its curves are no independent robots: the weights' rows
        unit = montecarlo_design(len(inputs), sizes["efast"], spec.seed)
        rows = design_efforts(robot, spec, inputs, scaled(inputs, unit), states, progress, "mc")
        extra["efast"] = path_outputs(rows, states.times_s)
    outputs = {}
    for method in spec.methods:
        rows = scaled(inputs, designs[method])
        found = design_efforts(robot, spec, inputs, rows, states, progress, method)
        outputs[method] = path_outputs(found, states.times_s)
    progress.start(len(spec.methods), "analysis")
    context = path_context(spec)
    analyses, along, variances, notes = [], [], {}, []
    for method in spec.methods:
        values = outputs.pop(method)
        variances[method] = path_variances(
            method, values, extra.get(method), designs[method], actuators
        )
        indices, loo, varying, note = analyse_varying(
            ready, problem, method, designs[method], values, progress
        )
        notes += [f"{method}: {note}"] if note else []
        runs = len(designs[method])
        percent = sensitivity_percent(indices, "ST")
        along.append(
            Analysis(
                method,
                "path",
                0.0,
                names,
                indices,
                percent,
                runs=runs,
                loo_error=loo,
                defined=varying,
            )
        )
        head = indices[:, : 2 * actuators]
        analyses.append(
            Analysis(
                method,
                "path",
                0.0,
                names,
                head,
                sensitivity_percent(head, "ST"),
                path_labels(actuators, "F" if model.prismatic else "τ"),
                context,
                runs=runs,
                loo_error=None if loo is None else loo[: 2 * actuators],
                defined=varying[: 2 * actuators],
            )
        )
    nominal_outputs = path_outputs(efforts[None], states.times_s)[0]
    peak, rms = nominal_outputs[:actuators], nominal_outputs[actuators : 2 * actuators]
    label = getattr(robot, "name", "") or ready.kind
    sobol_conf = [float(a.indices[[1, 3]].max()) for a in analyses if a.method == "sobol"]
    loo_max = [float(a.loo_error.max()) for a in analyses if a.loo_error is not None]
    summary = (
        f"{label}, {context}, "
        f"{len(inputs)} inputs, "
        + ", ".join(f"{m} N={sizes[m]}" for m in spec.methods)
        + f"; nominal peak |effort| {_listed(peak)}, RMS {_listed(rms)}"
        + (f"; max Sobol' CI ±{max(sobol_conf):.4f}" if sobol_conf else "")
        + (f"; max PCE LOO error {max(loo_max):.2g}" if loo_max else "")
        + "".join(f"; {note}" for note in notes)
    )
    return PathSensitivityResult(
        table=csv_table(label, analyses),
        extra_tables=path_tables(
            along,
            spec,
            actuators,
            variances,
            effort_names(actuators, model.effort, model.effort_unit),
        ),
        summary=summary,
        robot_label=label,
        analyses=analyses,
        names=names,
        samples={m: sizes[m] for m in spec.methods},
        nominal=np.stack([peak, rms]),
    )

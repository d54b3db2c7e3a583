r"""The SALib hand-off (``--export-problem DIR``): a job's model runs as SALib reads them.

For every design a sensitivity or motion job ran (``sobol``, ``efast``, ``montecarlo``),
``DIR/METHOD/`` holds:

* ``problem.json``: the SALib problem, ``{"num_vars", "names", "bounds", "outputs"}``
  (``SALib.ProblemSpec(json.load(...))``): the inputs ``l1 … ln, m1 … mn`` (``I1 … In``)
  in SI units and their uniform bounds ``nominal ± tolerance``;
* ``X.npy``: the sample matrix (rows × inputs), each row one robot as planar-tui ran it,
  the unit design scaled as SALib scales it, :math:`x (u - l) + l`;
* ``Y.npy``: the model outputs (rows × outputs; one column is saved as a vector of rows,
  as ``ProblemSpec`` takes a single output), in the order of ``outputs``: the joint
  torques (N m) at each speed for a sensitivity job, the motion outputs (rad, m) at each
  time of ``at_s`` for a motion job;
* ``run.json``: where the runs come from (planar-tui version, preset, job, method, N,
  seed, the design's row layout) and the SALib analysis that matches the design.

The rows keep their design's order, so SALib's own estimator of a design reads them as
is: ``SALib.analyze.sobol.analyze(problem, Y[:, k], calc_second_order=False)`` on the
Saltelli rows, ``SALib.analyze.fast.analyze(problem, Y[:, k], M=4)`` on eFAST's, and any
given-data method (``delta``, ``rbd_fast``, ``pawn``, ``hdmr``, ``dgsm`` needs its own
design) on the independent Monte-Carlo rows (or, loosely, on any of them). Morris needs
its own design (trajectories): it cannot reuse these runs.
"""

from __future__ import annotations

import json
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from planar_tui import __version__
from planar_tui.errors import PresetError
from planar_tui.interop.files import refuse_existing, write_new, write_new_text
from planar_tui.motion.engine import design_methods as motion_designs
from planar_tui.sensitivity.engine import build_problem
from planar_tui.sensitivity.spec import sample_sizes

#: The option that asks for the hand-off (named in messages).
OPTION = "--export-problem"
#: Per design: its row layout and the SALib analysis that reads it.
DESIGNS = {
    "sobol": (
        "SALib's Saltelli design without second order: N blocks of D + 2 rows "
        "(A, A_B^(1) ... A_B^(D), B), scrambled Sobol' sequence",
        "SALib.analyze.sobol.analyze(problem, Y[:, k], calc_second_order=False)",
    ),
    "efast": (
        "SALib's eFAST search curves (fast_sampler, M = 4): D blocks of N rows",
        "SALib.analyze.fast.analyze(problem, Y[:, k], M=4)",
    ),
    "montecarlo": (
        "N independent uniform robots, numpy default_rng(seed).random((N, D)) scaled",
        "any given-data method: SALib.analyze.delta / rbd_fast / pawn / hdmr",
    ),
}
FILES = ("problem.json", "X.npy", "Y.npy", "run.json")


@dataclass(frozen=True)
class ModelRuns:
    """The runs of one design: ``method``, base size ``samples`` (N), ``seed``, the
    ``problem`` (a :class:`~planar_tui.sensitivity.engine.Problem`: names and bounds),
    the unit design ``unit`` (rows × D) and the ``outputs`` (rows × K) named by
    ``output_names``."""

    method: str
    samples: int
    seed: int
    problem: Any
    unit: np.ndarray
    outputs: np.ndarray
    output_names: tuple[str, ...]

    def inputs(self) -> np.ndarray:
        """The sample matrix in SI units, scaled as SALib (and planar-tui) scale it."""
        return self.unit * (self.problem.upper - self.problem.lower) + self.problem.lower

    def salib_problem(self) -> dict[str, Any]:
        """The ``ProblemSpec`` dictionary: names, bounds and outputs."""
        return {**self.problem.salib(), "outputs": list(self.output_names)}


def write_problem(
    directory: Path, runs: Sequence[ModelRuns], about: Mapping[str, Any]
) -> list[Path]:
    """Write ``DIR/METHOD/{problem.json, X.npy, Y.npy, run.json}`` for every design;
    ``about`` (preset, job, version ...) goes into each ``run.json``. Refused before
    anything is written if any of those files exists (:class:`PresetError`)."""
    directory = Path(directory)
    planned = [directory / run.method / name for run in runs for name in FILES]
    refuse_existing(planned, OPTION)
    written = []
    for run in runs:
        folder = directory / run.method
        layout, analysis = DESIGNS[run.method]
        record = {
            **about,
            "method": run.method,
            "samples_N": run.samples,
            "seed": run.seed,
            "rows": int(run.unit.shape[0]),
            "design": layout,
            "salib_analysis": analysis,
        }
        written.append(write_new_text(folder / "problem.json", _json(run.salib_problem()), OPTION))
        written.append(_write_array(folder / "X.npy", run.inputs()))
        outputs = run.outputs[:, 0] if run.outputs.shape[1] == 1 else run.outputs
        written.append(_write_array(folder / "Y.npy", outputs))
        written.append(write_new_text(folder / "run.json", _json(record), OPTION))
    return written


def _json(value: Any) -> str:
    return json.dumps(value, indent=2, ensure_ascii=False) + "\n"


def _write_array(path: Path, array: np.ndarray) -> Path:
    def write(temp: Path) -> None:
        with open(temp, "xb") as stream:
            np.save(stream, np.ascontiguousarray(array, dtype=np.float64), allow_pickle=False)

    return write_new(path, write, OPTION)


def sensitivity_output_names(n_links: int, speeds_rad_s: Sequence[float]) -> tuple[str, ...]:
    """``tau1_Nm … taun_Nm`` per speed (suffixed ``_at_W_rad_s`` when there are several)."""
    several = len(speeds_rad_s) > 1
    return tuple(
        f"tau{i}_Nm" + (f"_at_{speed:g}_rad_s" if several else "")
        for speed in speeds_rad_s
        for i in range(1, n_links + 1)
    )


def motion_output_names(names: Sequence[str], times_s: Sequence[float]) -> tuple[str, ...]:
    """The motion outputs per time of ``at_s``: ``theta1_rad_at_1_s``, ``tip_x_m_at_1_s`` …"""
    return tuple(f"{name}_at_{t_s:g}_s" for t_s in times_s for name in names)


def sensitivity_runs(job: Any, result: Any) -> list[ModelRuns]:
    """The model runs of a sensitivity job that ran (``result``: its posture), per method:
    the unit design (SALib's, cached: the one the job ran) and the joint torques at every
    speed, evaluated again by the job's own kernel (:func:`~planar_tui.sensitivity.engine.
    evaluate`: rows are independent, so the values are the job's, bit for bit); cheap next
    to the job's analysis."""
    from planar_tui.sensitivity.engine import build_problem, evaluate, unit_design

    spec, robot = job.spec, job.robot
    problem = build_problem(
        robot, spec.tolerance_length_m, spec.tolerance_mass_kg, spec.inertia_tolerance_kgm2
    )
    sizes = sample_sizes(spec, problem.num_vars)
    n = robot.n_links
    theta, alpha = np.array(result.posture.theta_rad), np.full(n, spec.alpha_rad_s2)
    names = sensitivity_output_names(n, spec.speeds_rad_s)
    runs = []
    for method in design_methods(job):
        unit = unit_design(method, problem.num_vars, sizes[method], spec.seed)
        torques = [
            evaluate(problem, unit, robot, theta, np.full(n, speed), alpha)
            for speed in spec.speeds_rad_s
        ]
        outputs = np.concatenate(torques, axis=1)
        runs.append(ModelRuns(method, sizes[method], spec.seed, problem, unit, outputs, names))
    return runs


def motion_runs(job: Any, result: Any) -> list[ModelRuns]:
    """The model runs of a motion job that ran, per design (its ``design`` and the outputs
    of every robot at the times of ``at_s``, ``at_outputs``, kept by the runner)."""
    spec, robot = job.spec, job.robot
    problem = build_problem(
        robot,
        spec.tolerance_length_mm * 1e-3,
        spec.tolerance_mass_g * 1e-3,
        spec.tolerance_inertia_kgm2,
    )
    steps = sorted(result.at_outputs)
    names = motion_output_names(result.names, [step * spec.step_s for step in steps])
    runs = []
    for method, rows in result.design.rows.items():
        if method not in DESIGNS:  # PCE's regression rows: no SALib design
            continue
        outputs = np.concatenate([result.at_outputs[step][rows] for step in steps], axis=1)
        unit = result.design.unit[rows]
        runs.append(ModelRuns(method, spec.samples, spec.seed, problem, unit, outputs, names))
    return runs


def design_methods(job: Any) -> tuple[str, ...]:
    """The SALib designs (:data:`DESIGNS`) a sensitivity or motion job runs (a motion
    job's eFAST alone adds N Monte-Carlo robots for its band:
    :func:`planar_tui.motion.engine.design_methods`); PCE's regression rows are no SALib
    design and are not exported."""
    if job.kind == "motion_uncertainty":
        return tuple(m for m in motion_designs(job.spec.methods) if m in DESIGNS)
    return tuple(m for m in job.spec.methods if m in DESIGNS)


def planned_files(job: Any, directory: Path) -> list[Path]:
    """Every file :func:`export_job` will write for ``job`` (checked before it runs);
    :class:`~planar_tui.errors.PresetError` when the job runs no SALib design (PCE alone)."""
    methods = design_methods(job)
    if not methods:
        raise PresetError(
            "command line",
            OPTION,
            f"job {job.label} runs only {', '.join(job.spec.methods)}, "
            "which has no SALib design to export",
            "a job whose methods include sobol or efast",
        )
    return [Path(directory) / method / name for method in methods for name in FILES]


def export_job(job: Any, result: Any, directory: Path) -> list[Path]:
    """Write the runs of a finished sensitivity or motion job to ``directory``."""
    runs = (
        motion_runs(job, result)
        if job.kind == "motion_uncertainty"
        else sensitivity_runs(job, result)
    )
    about = {"planar_tui_version": __version__, "preset": str(job.preset_path), "job": job.label}
    return write_problem(directory, runs, about)

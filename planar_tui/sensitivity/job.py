"""The ``[sensitivity]`` job: Sobol'/eFAST sensitivity of the joint torques (paper A, §3).

The job kind: its settings (:mod:`planar_tui.sensitivity.spec`), its runner
(:mod:`planar_tui.sensitivity.runner`: design, evaluate, analyse), the files it writes,
its terminal view and a sweep row's figures.
"""

from __future__ import annotations

from typing import Any

from planar_tui import uq
from planar_tui.dynamics.robot import SerialRobot
from planar_tui.jobkind import Command, Job, JobKind, Tab
from planar_tui.sensitivity.figure_names import figure_names
from planar_tui.sensitivity.runner import SensitivityResult, prepare_sensitivity, run_sensitivity
from planar_tui.sensitivity.spec import METHODS, SensitivitySpec, resource_estimate


def path_outputs_files(job: Job[SensitivitySpec, SerialRobot]) -> dict[str, str]:
    """With a ``path``: its per-step indices beside the job's CSV (``-path.csv``) and the
    aggregated indices (``-path-aggregated.csv``)."""
    if job.spec.path is None:
        return {}
    stem = job.output[:-4] if job.output.lower().endswith(".csv") else job.output
    return {"path": f"{stem}-path.csv", "path_aggregated": f"{stem}-path-aggregated.csv"}


def render_sensitivity(
    job: Job[SensitivitySpec, SerialRobot], result: SensitivityResult, console: Any
) -> None:
    """The CLI view of one job: its index tables fitted to the terminal width (percent
    view), and the stacked bars (Figs 5/6) when speeds are swept."""
    from planar_tui.sensitivity.bars import sensitivity_bars
    from planar_tui.sensitivity.tables import VIEWS, fit_tables

    analyses = result.analyses
    console.print(f"{result.robot_label}: {job.label}", style="bold", markup=False)
    console.print(fit_tables(analyses, VIEWS[0], console.width, job.spec.percent_of).renderable)
    if len({a.speed_rad_s for a in analyses}) > 1:
        console.print(sensitivity_bars(analyses, analyses[0].method))


def point_figures(
    job: Job[SensitivitySpec, SerialRobot], result: SensitivityResult
) -> dict[str, str | float]:
    """A sweep row's figures, per torque ``i`` (at each speed, suffixed ``_w2``, ``_w3`` …
    from the second on): the dominant parameter by the percent of the job's first method,
    its percent, the lengths' and the masses' shares (sums of their percents), the
    largest Sobol' 95 % half-width of ``S1`` and ``ST`` over the parameters (empty without
    Sobol') and its variance (N² m², without a ``path``); then the largest variance over
    the torques. With a ``path`` the outputs are ``tau{j}_peak`` and ``tau{j}_rms``
    instead."""
    method = job.spec.methods[0]
    figures: dict[str, str | float] = {}
    path = job.spec.path is not None
    n = job.robot.n_links
    for k, speed in enumerate((0.0,) if path else job.spec.speeds_rad_s, start=1):
        at = {a.method: a for a in result.analyses if a.speed_rad_s == speed}
        chosen, sobol = at[method], at.get("sobol")
        suffix = "" if k == 1 else f"_w{k}"
        names = chosen.names
        for i, percent in enumerate(chosen.percent, start=1):
            top = int(percent.argmax())
            out = f"tau{(i - 1) % n + 1}_{'peak' if i <= n else 'rms'}" if path else f"tau{i}"
            figures[f"{out}_dominant{suffix}"] = names[top]
            figures[f"{out}_dominant_percent{suffix}"] = float(percent[top])
            for group, prefix in (("lengths", "l"), ("masses", "m")):
                share = sum(
                    float(p)
                    for p, name in zip(percent, names, strict=True)
                    if name.startswith(prefix)
                )
                figures[f"{out}_{group}_percent{suffix}"] = share
            halfwidth = "" if sobol is None else float(sobol.indices[[1, 3], i - 1].max())
            figures[f"{out}_sobol_halfwidth_max{suffix}"] = halfwidth
            if not path:
                figures[f"{out}_variance_Nm2{suffix}"] = result.variances_Nm2[speed][i - 1]
        if not path:
            figures[f"tau_variance_max_Nm2{suffix}"] = max(result.variances_Nm2[speed])
    return figures


JOB_KIND = JobKind(
    name="sensitivity",
    robot_kind="robot",
    settings=SensitivitySpec,
    run=run_sensitivity,
    summary="Sobol'/eFAST/PCE sensitivity of the joint torques to lengths and masses",
    render=render_sensitivity,
    prepare=prepare_sensitivity,
    extra_outputs=path_outputs_files,
    point_figures=point_figures,
    command=Command(
        "sensitivity",
        "Sobol'/eFAST sensitivity of the joint torques of every sensitivity job; one CSV "
        "each.\n\nAn option that changes a job's setting is appended to the stem of the file "
        "the preset names (tiny-sensitivity--samples-512.csv); a name given with --out is kept.",
        options=uq.sampling_options(METHODS, "Sobol' base N (a power of two)"),
    ),
    tab=Tab(
        "Sensitivity",
        1,
        "planar_tui.app.widgets.sensitivity_pane:SensitivityPane",
        view="S1/ST/%",
        view_help="percent / S1 / ST / ± half-width",
    ),
    figure="planar_tui.figures.sensitivity:from_result",
    warmup="[sensitivity]\nsamples = 8\nefast_samples = 65\n",
    figure_names=figure_names,
    estimate=lambda job: resource_estimate(job.spec, job.robot),
    app_default={
        "posture": "singular",
        "speed_rad_s": 1.0,
        "tolerance_length_mm": 1.0,
        "tolerance_mass_g": 1.0,
        "methods": ["sobol", "efast"],
        "samples": 1024,
        "seed": 42,
        "output": "app-sensitivity.csv",
    },
)

"""The simulate job's energy figure is the balance E(t) − E(0) − W(t), W the work of the
constant torques: ≈ 0 for RK4 at 1e-4 s (a conservation law) while E itself changes by
joules under the Table 1 torques."""

from __future__ import annotations

import dataclasses

import numpy as np

from planar_tui import batch
from planar_tui.presets import JOB_KINDS, load_preset
from tests.conftest import PRESETS


def test_a_torque_runs_sweep_figure_is_its_energy_drift_net_of_the_torques_work():
    preset = load_preset(PRESETS / "paper-a-table1.toml")
    job = next(j for j in preset.jobs if j.key == "simulate[1]")
    job = dataclasses.replace(job, spec=dataclasses.replace(job.spec, duration_s=0.3))
    (job,) = batch.prepare_jobs([job])
    result = batch.run_job(job)
    column = list(result.table.header).index("energy_J")
    energy = np.array([row[column] for row in result.table.rows])
    assert np.max(np.abs(energy - energy[0])) > 0.5  # the torques do joules of work
    figures = JOB_KINDS["simulate"].point_figures(job, result)
    assert 0.0 <= figures["energy_drift_max_J"] < 1e-9
    assert "max |E - E0 - W| = " in result.summary

"""The ``"pce"`` method of the [motion_uncertainty] job.

The 1-link zero-gravity motion θ(t) = τt²/(2(I + m l²/4)) from rest: its indices are the
same at every t > 0 (θ ∝ t²), equal to Gauss-Legendre quadrature
(``tests/test_motion_job.exact_moments``); the PCE gives them at every recorded time, within
0.01 at the default ``pce_samples``, and aggregated over the trajectory (the same values:
the aggregate of equal indices); the indices CSV has a row per recorded time; the band
comes from the PCE's robots; a LOO error above the bound fails the job with its line.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from planar_tui import figures
from planar_tui.batch import run_job
from planar_tui.errors import PresetError
from tests.test_motion_job import CASES, exact_moments, one_link_job

INERTIA = CASES["l-m"][0]


def test_pce_indices_at_every_recorded_time_match_quadrature():
    job = one_link_job(["pce"], 8)  # `samples` does not apply to pce
    result = run_job(job)
    _, variance, _, first, total = exact_moments(INERTIA)
    exact_first, exact_total = np.array(first) / variance, np.array(total) / variance
    table = result.extra_tables["indices"]
    rows = [dict(zip(table.header, row, strict=True)) for row in table.rows]
    assert table.header[-2:] == ("runs", "loo_error")
    times = sorted({row["t_s"] for row in rows})
    assert len(times) == len(result.t_s) == 11  # 0, 0.05 … 0.5 s: every recorded time
    names = ("l1", "m1")
    for row in rows:
        assert row["method"] == "pce" and row["runs"] == 128  # max(128, 64 D), D = 2
        if row["output"] == "theta1_rad" and row["t_s"] > 0:
            j = names.index(row["parameter"])
            assert abs(row["S1"] - exact_first[j]) <= 0.01
            assert abs(row["ST"] - exact_total[j]) <= 0.01
            assert row["loo_error"] < 1e-3
    aggregated = result.extra_tables["aggregated"]
    cells = {(r[0], r[1]): r for r in aggregated.rows}
    for j, name in enumerate(names):
        _, _, _, s1, st, _, runs = cells[("theta1_rad", name)]
        assert runs == 128
        assert abs(s1 - exact_first[j]) <= 0.01 and abs(st - exact_total[j]) <= 0.01
    assert {r[0] for r in aggregated.rows} >= {"theta1_rad", "all outputs"}
    assert [a.speed_rad_s for a in result.analyses] == [pytest.approx(0.5)]  # at_s: the end
    fig = figures.figure_for_table(table, job.label)  # 11 times: stacked lines
    assert any(ax.get_gid() == "stacked" for ax in fig.axes)


def test_the_band_of_a_pce_job_comes_from_its_robots():
    result = run_job(one_link_job(["pce"], 8))
    assert result.robots == 128
    assert result.band[-1, 1, 0] > 0.0  # θ1 spreads at the end


def test_a_pce_loo_error_above_the_bound_fails_the_motion_job():
    job = one_link_job(["pce"], 8)
    job = dataclasses.replace(job, spec=dataclasses.replace(job.spec, pce_max_loo_error=1e-14))
    with pytest.raises(PresetError) as raised:
        run_job(job)
    message = str(raised.value)
    assert "motion_uncertainty.pce_samples: PCE leave-one-out error " in message
    assert "exceeds pce_max_loo_error = 1e-14 (expected raise pce_samples (now 128)" in message

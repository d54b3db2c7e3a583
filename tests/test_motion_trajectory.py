"""Sobol' and eFAST indices at every recorded time and aggregated over a trajectory.

The point estimates at every time (:func:`~planar_tui.sensitivity.engine.point_indices`)
are the bootstrapped analyses' S1 and ST, half-widths not computed; the aggregated indices
(Gamboa et al. 2014) of Sobol' (weights: the variances over the design's A and B rows) and
of eFAST (over N independent Monte-Carlo rows) against their definition by Gauss-Legendre
quadrature (``tests/test_sensitivity_pce.aggregate_by_quadrature``); on the 1-link motion
(θ ∝ t², the same indices at every t > 0) Sobol' at every time agrees with the PCE and with
quadrature; the rows at ``at_s`` equal those the job wrote before every time was analysed
(``tests/data/motion/at_s_indices.csv``, written by commit 1322af0 from :data:`MOTION`;
to 1e-12, as main's lane-batched RK4 integrator changed the last digits since).
"""

from __future__ import annotations

import csv
import io
from pathlib import Path

import numpy as np
import pytest

from planar_tui.batch import run_job
from planar_tui.sensitivity.aggregate import aggregated_indices
from planar_tui.sensitivity.engine import (
    analyse,
    independent_rows,
    montecarlo_design,
    point_indices,
    unit_design,
)
from tests.test_motion_job import exact_moments, job_of, one_link_job
from tests.test_sensitivity_pce import aggregate_by_quadrature, aggregate_model

SEED = 1
ROBOT = {
    "lengths_m": [0.4, 0.3],
    "masses_kg": [2.0, 1.0],
    "inertias_kgm2": [0.03, 0.01],
    "gravity_m_s2": 9.81,
}
MOTION = {
    "duration_s": 0.2,
    "step_s": 0.01,
    "torques_Nm": [1.0, 0.5],
    "methods": ["pce", "sobol", "efast"],
    "samples": 128,
    "tolerance_length_mm": 20.0,
    "tolerance_mass_g": 200.0,
    "at_s": [0.05, 0.2],
    "every": 5,
}
STORED = Path(__file__).parent / "data" / "motion" / "at_s_indices.csv"


def dict_rows(table) -> list[dict]:
    buffer = io.StringIO()
    table.write(buffer)
    return list(csv.DictReader(io.StringIO(buffer.getvalue())))


@pytest.mark.parametrize("method", ["sobol", "efast"])
def test_point_indices_are_the_analyses_point_estimates(method):
    unit = unit_design(method, 3, 256, SEED)
    y = aggregate_model(2.0 * unit - 1.0).T
    y = np.column_stack([y, np.full(len(y), 3.0)])  # a constant output: zeros, no NaN
    point = point_indices(method, y, 3)
    full = analyse(method, np.ascontiguousarray(y[:, :-1]), 3, SEED)
    assert np.abs(point[[0, 2], :-1] - full[[0, 2]]).max() <= 1e-12
    assert np.isnan(point[[1, 3]]).all()
    assert np.all(point[[0, 2], -1] == 0.0)


@pytest.mark.parametrize("method", ["sobol", "efast"])
def test_aggregated_indices_match_their_definition_by_quadrature(method):
    """N = 1024: Sobol' ≤ 0.005 and eFAST ≤ 0.003 off over seeds 1-3 (measured); 0.02."""
    first, total, variance = aggregate_by_quadrature()
    unit = unit_design(method, 3, 1024, SEED)
    y = aggregate_model(2.0 * unit - 1.0).T  # (S, T)
    if method == "sobol":
        weights = y[independent_rows("sobol", len(y), 3)].var(axis=0)
    else:  # the search curves are not independent robots
        weights = aggregate_model(2.0 * montecarlo_design(3, 1024, SEED) - 1.0).T.var(axis=0)
    assert weights == pytest.approx(variance, rel=0.1)
    aggregated = aggregated_indices(point_indices(method, y, 3)[[0, 2]], weights)
    assert np.abs(aggregated[0] - first / variance.sum()).max() <= 0.02
    assert np.abs(aggregated[1] - total / variance.sum()).max() <= 0.02


def test_the_rows_at_at_s_are_unchanged_and_every_recorded_time_has_rows():
    result = run_job(job_of(ROBOT, MOTION))
    rows = dict_rows(result.extra_tables["indices"])
    with STORED.open(encoding="utf-8") as stream:
        stored = list(csv.DictReader(stream))
    assert rows[0].keys() == stored[0].keys()
    key = ("output", "t_s", "parameter", "method")
    by_key = {tuple(row[k] for k in key): row for row in rows}
    for old in stored:
        new = by_key[tuple(old[k] for k in key)]
        if new["S1"] == "":  # no variance at t = 0: no index now (stored as 0 before)
            index_cells = {old[c] for c in ("S1", "S1_conf", "ST", "ST_conf", "percent")}
            assert old["t_s"] == "0.0" and index_cells == {"0.0"}, old
            continue
        for column, cell in old.items():
            if column in key or cell == "":
                assert new[column] == cell
            else:  # main's lane-batched RK4 moved them by 3.6e-14 here
                assert float(new[column]) == pytest.approx(float(cell), rel=1e-10, abs=1e-12)
    times = {(row["t_s"], row["method"]) for row in rows}
    assert times == {
        (t, m) for t in ("0.0", "0.05", "0.1", "0.15", "0.2") for m in ("pce", "sobol", "efast")
    }
    for row in rows:  # confidence intervals at at_s only; no index of an angle at t = 0
        at_rest = row["t_s"] == "0.0" and row["output"] in ("theta1_rad", "theta2_rad", "tip_y_m")
        if at_rest:  # θ = 0 and tip y = 0 for every robot: nothing varies
            assert row["S1"] == row["ST"] == row["ST_conf"] == row["percent"] == ""
            continue
        at_s = row["t_s"] in ("0.05", "0.2")
        assert (row["ST_conf"] != "") == (at_s or row["method"] == "pce"), row
    aggregated = dict_rows(result.extra_tables["aggregated"])
    assert {(r["output"], r["method"]) for r in aggregated} == {
        (o, m)
        for o in ("theta1_rad", "theta2_rad", "tip_x_m", "tip_y_m", "all outputs")
        for m in ("pce", "sobol", "efast")
    }
    assert {r["runs"] for r in aggregated if r["method"] == "sobol"} == {str(128 * 6)}


@pytest.mark.parametrize("method", ["sobol", "efast"])
def test_every_time_and_aggregated_indices_of_the_one_link_motion(method):
    """θ(t) ∝ t²: the same indices at every t > 0, and aggregated; Sobol' and eFAST at
    N = 512 within 0.03 of the PCE's and of quadrature (Sobol''s 95 % half-width at the end
    is about 0.01 here; eFAST's bias a few thousandths)."""
    result = run_job(one_link_job(["pce", method], 512))
    _, variance, _, first, total = exact_moments()
    exact = {"S1": np.array(first) / variance, "ST": np.array(total) / variance}
    names = ("l1", "m1")
    rows = [r for r in dict_rows(result.extra_tables["indices"]) if r["output"] == "theta1_rad"]
    pce = {(r["t_s"], r["parameter"]): r for r in rows if r["method"] == "pce"}
    checked = 0
    for row in rows:
        if row["method"] != method or float(row["t_s"]) == 0.0:
            continue
        for index in ("S1", "ST"):
            value = float(row[index])
            assert abs(value - float(pce[row["t_s"], row["parameter"]][index])) <= 0.03
            assert abs(value - exact[index][names.index(row["parameter"])]) <= 0.03
        checked += 1
    assert checked == 10 * 2  # 0.05 … 0.5 s, two inputs
    for r in dict_rows(result.extra_tables["aggregated"]):
        if r["output"] == "theta1_rad" and r["method"] == method:
            j = names.index(r["parameter"])
            assert abs(float(r["S1"]) - exact["S1"][j]) <= 0.03
            assert abs(float(r["ST"]) - exact["ST"][j]) <= 0.03

"""The lane-batched sensitivity model (kernels/sensitivity_model.py, issue 21).

Oracle: the scalar Newton-Euler kernel ``inverse_dynamics_batch`` (one robot at a time) on
the design scaled first with SALib's arithmetic; the lane kernel keeps its statements and
operation order, so the torques must be the same doubles, for full and partial blocks.
"""

from __future__ import annotations

import numpy as np
import pytest
from planar_tui.kernels.dynamics_batch import inverse_dynamics_batch
from planar_tui.kernels.sensitivity_model import LANES, design_torques


@pytest.mark.parametrize("n", [2, 6])
@pytest.mark.parametrize("sampled_inertias", [False, True])
@pytest.mark.parametrize("rows", [1, LANES - 1, 2 * LANES + 3])
def test_lane_torques_are_the_scalar_kernels_doubles(n, sampled_inertias, rows):
    rng = np.random.default_rng(n * 1000 + rows)
    num_vars = 3 * n if sampled_inertias else 2 * n
    unit = rng.random((rows, num_vars))
    lower = rng.uniform(0.05, 1.0, num_vars)
    upper = lower + rng.uniform(1e-3, 0.1, num_vars)
    inertias = rng.uniform(1e-3, 1e-2, n)
    state = (rng.normal(size=n), rng.normal(size=n), rng.normal(size=n))
    scaled = unit * (upper - lower) + lower  # SALib's scale_samples
    columns = [np.ascontiguousarray(scaled[:, k * n : (k + 1) * n]) for k in range(2)]
    if sampled_inertias:
        columns.append(np.ascontiguousarray(scaled[:, 2 * n :]))
    else:
        columns.append(np.tile(inertias, (rows, 1)))
    expected = inverse_dynamics_batch(*columns, 9.81, *state)
    torques = design_torques(unit, lower, upper, inertias, 9.81, *state)
    assert np.abs(expected).max() > 0.1  # a real load
    assert np.array_equal(torques, expected)

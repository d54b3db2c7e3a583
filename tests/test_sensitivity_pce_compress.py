"""The PCE of many outputs on their principal components
(planar_tui/sensitivity/pce_compress.py): the same fit, output by output, as the
uncompressed one, on a path's every torque at every step."""

from __future__ import annotations

from functools import cache

import numpy as np

from planar_tui.pathsensitivity.engine import design_efforts, path_outputs, path_states, scaled
from planar_tui.pathsensitivity.inputs import robot_inputs
from planar_tui.sensitivity import pce, pce_indices
from planar_tui.sensitivity.pce_compress import TOLERANCE, compress
from planar_tui.workspace.rrr.path import Path3RRRSpec
from planar_tui.workspace.rrr.robot import Robot3RRR


@cache
def path_case():
    """A 3-RRR's peak, RMS and every torque at 101 steps (309 outputs) over 256 robots of
    ten inputs (lengths, masses, inertias)."""
    robot = Robot3RRR(
        proximal_mass_kg=0.6,
        distal_mass_kg=0.4,
        platform_mass_kg=1.5,
        proximal_inertia_kgm2=0.0045,
        distal_inertia_kgm2=0.003,
        platform_inertia_kgm2=0.025,
        gravity_m_s2=9.81,
    )
    spec = Path3RRRSpec(
        from_pose=(36, 5, -2), to_pose=(44, 9, 2), duration_s=0.5, steps=100, elbow=(1, -1, -1)
    )
    lengths = ("base_side_cm", "platform_side_cm", "proximal_cm", "distal_cm")
    inputs = robot_inputs(robot, lengths, 0.01, 0.02, 2e-4)
    unit = np.asarray(pce.pce_unit_design(len(inputs), 256, 3))
    states = path_states(spec)
    efforts = design_efforts(robot, spec, inputs, scaled(inputs, unit), states)
    outputs = path_outputs(efforts, states.times_s)
    unit.setflags(write=False)
    outputs.setflags(write=False)
    return unit, outputs


def test_the_compressed_fit_is_the_uncompressed_fit_output_by_output():
    """Fitted on its principal components (fewer than a fifth of the outputs' count), each
    output keeps the same terms, LOO error, indices and bootstrap half-widths as when the
    309 columns are fitted as they are, to 1e-8."""
    unit, y = path_case()
    components = compress(y)
    assert components is not None and components.scores.shape[1] < y.shape[1] / 5
    rebuilt = components.mean + components.scores @ components.loadings.T
    centred = y - y.mean(axis=0)
    lost = ((y - rebuilt) ** 2).sum(axis=0) / (centred**2).sum(axis=0)
    assert lost.max() <= TOLERANCE
    fits = [pce.fit_pce(unit, y, compressed=flag) for flag in (True, False)]
    assert fits[0].compressed is not None and fits[1].compressed is None
    np.testing.assert_array_equal(fits[0].indices, fits[1].indices)
    np.testing.assert_array_equal(fits[0].term_counts, fits[1].term_counts)
    np.testing.assert_allclose(fits[0].loo_error, fits[1].loo_error, rtol=1e-8, atol=1e-12)
    results = []
    for fit in fits:
        first, total = pce_indices.indices_from_coefficients(fit.indices, fit.coefficients)
        results.append((first, total, *pce.bootstrap_halfwidths(fit, y, 5, 30)))
    assert results[1][3].max() > 1e-4  # the half-widths are not trivially 0
    for compressed, plain in zip(*results, strict=True):
        np.testing.assert_allclose(compressed, plain, atol=1e-8)


def test_few_outputs_or_failed_runs_are_fitted_as_they_are():
    y = path_case()[1]
    assert compress(y[:, :20]) is None
    broken = y.copy()
    broken[3, 40] = np.nan
    assert compress(broken) is None

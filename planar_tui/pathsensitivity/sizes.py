"""A path-sensitivity job's inputs and sample sizes (read by its checks and its runner)."""

from __future__ import annotations

from typing import Any

from planar_tui import uq
from planar_tui.pathsensitivity.inputs import Input, robot_inputs


def inputs_of(spec: Any, robot: Any) -> tuple[Input, ...]:
    """The job's uncertain inputs (:func:`~planar_tui.pathsensitivity.inputs.robot_inputs`)."""
    return robot_inputs(
        robot,
        spec.length_fields(robot),
        spec.tolerance_length_mm / 10.0,
        spec.tolerance_mass_g / 1000.0,
        spec.tolerance_inertia_kgm2,
        spec.key_names,
    )


def sample_sizes(spec: Any, num_vars: int) -> dict[str, int]:
    """N per method: the Sobol' base N, eFAST's (given, or matching the Sobol' cost but at
    least ``4 M² (D − 1) + 1``, where its D − 1 complementary frequencies are distinct), the
    PCE's robots (given, or ``max(128, 64 D)``)."""
    from planar_tui.sensitivity.engine import default_efast_samples
    from planar_tui.sensitivity.pce import default_pce_samples

    distinct = 4 * uq.EFAST_HARMONICS**2 * (num_vars - 1) + 1

    return {
        "sobol": spec.samples,
        "efast": spec.efast_samples or max(default_efast_samples(spec.samples, num_vars), distinct),
        "pce": spec.pce_samples or default_pce_samples(num_vars),
    }

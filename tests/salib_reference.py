"""SALib itself, the reference the package's sampling and estimators equal: its unit
designs (drawn in one call) and its ``analyze`` per output column. Test code only (the
package never runs SALib's analysis)."""

from __future__ import annotations

import warnings

import numpy as np

from planar_tui.sensitivity.estimators import CONF_LEVEL, NUM_RESAMPLES
from planar_tui.uq import EFAST_HARMONICS


def salib_unit_design(method: str, num_vars: int, samples: int, seed: int) -> np.ndarray:
    """SALib's design on the unit hypercube, drawn by SALib itself in one call (the
    reference :func:`draw_unit_design` is checked against, byte for byte).

    ``sobol``: ``SALib.sample.sobol.sample(N, calc_second_order=False)``, N (D + 2) rows;
    ``efast``: ``SALib.sample.fast_sampler.sample(N, M=4)``, N D rows.
    """
    unit = {"num_vars": num_vars, "names": [f"x{i}" for i in range(num_vars)]}
    unit["bounds"] = [[0.0, 1.0]] * num_vars
    if method == "sobol":
        from SALib.sample import sobol

        return sobol.sample(unit, samples, calc_second_order=False, seed=seed)
    from SALib.sample import fast_sampler

    return fast_sampler.sample(unit, samples, M=EFAST_HARMONICS, seed=seed)


def salib_per_column(analyze, problem, outputs, **options) -> np.ndarray:
    """Run a SALib ``analyze`` on each output column; stack S1, S1_conf, ST, ST_conf.

    SALib's eFAST warning about its bootstrap confidence intervals (SALib #649) is
    acknowledged here: those half-widths are labelled unreliable wherever shown."""
    analyses = []
    for column in np.asarray(outputs).T:
        with warnings.catch_warnings():
            warnings.filterwarnings("ignore", message="FAST confidence intervals")
            analyses.append(analyze(problem, np.ascontiguousarray(column), **options))
    keys = ("S1", "S1_conf", "ST", "ST_conf")
    return np.array([[np.asarray(a[k], dtype=np.float64) for a in analyses] for k in keys])


def salib_sobol_indices(problem, outputs, seed, num_resamples=NUM_RESAMPLES, conf_level=CONF_LEVEL):
    """The reference: ``SALib.analyze.sobol.analyze`` on each output column."""
    from SALib.analyze import sobol

    options = {"num_resamples": num_resamples, "conf_level": conf_level, "seed": seed}
    return salib_per_column(sobol.analyze, problem, outputs, calc_second_order=False, **options)


def salib_efast_indices(
    problem, outputs, seed, m_harmonics=4, num_resamples=NUM_RESAMPLES, conf_level=CONF_LEVEL
):
    """The reference: ``SALib.analyze.fast.analyze`` on each output column."""
    from SALib.analyze import fast

    options = {"num_resamples": num_resamples, "conf_level": conf_level, "seed": seed}
    return salib_per_column(fast.analyze, problem, outputs, M=m_harmonics, **options)

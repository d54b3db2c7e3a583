"""Sample (SALib), evaluate (batched Numba inverse dynamics), analyse (fast estimators).

The unit-hypercube designs depend only on (method, D, N, seed), so SALib draws each once
(kept per process and in the persistent :mod:`.design_cache`) and they are scaled per
robot exactly as ``SALib.util.scale_samples`` does (``x (ub - lb) + lb``): the scaled
matrix is bit-identical to SALib sampling the real problem. One design serves every posture and speed of a job: only the state changes.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

#: eFAST interference factor M (paper A, Saltelli et al. 1999).
M_HARMONICS = 4


@dataclass(frozen=True)
class Problem:
    """Uncertain inputs: names (``l1``…, ``m1``…, optionally ``I1``…) and uniform bounds."""

    names: tuple[str, ...]
    lower: np.ndarray
    upper: np.ndarray
    n_links: int

    @property
    def num_vars(self) -> int:
        return len(self.names)

    def salib(self) -> dict:
        """The SALib problem dictionary."""
        bounds = [[float(a), float(b)] for a, b in zip(self.lower, self.upper, strict=True)]
        return {"num_vars": self.num_vars, "names": list(self.names), "bounds": bounds}


def build_problem(robot, tolerance_length_m, tolerance_mass_kg, tolerance_inertia_kgm2=None):
    """Inputs ``l_i ∈ [l_i ± δl]``, ``m_i ∈ [m_i ± δm]`` (and ``I_i ± δI`` if given)."""
    lengths, masses, inertias = robot.arrays()
    n = robot.n_links
    names = [f"l{i}" for i in range(1, n + 1)] + [f"m{i}" for i in range(1, n + 1)]
    nominal = [lengths, masses]
    spread = [np.full(n, tolerance_length_m), np.full(n, tolerance_mass_kg)]
    if tolerance_inertia_kgm2 is not None:
        names += [f"I{i}" for i in range(1, n + 1)]
        nominal.append(inertias)
        spread.append(np.full(n, tolerance_inertia_kgm2))
    centre = np.concatenate(nominal)
    half = np.concatenate(spread)
    return Problem(tuple(names), centre - half, centre + half, n)


def design_rows(method: str, num_vars: int, samples: int) -> int:
    """Rows of a design: N (D + 2) for Sobol' (no second order), N D for eFAST."""
    return samples * (num_vars + 2) if method == "sobol" else samples * num_vars


def salib_unit_design(method: str, num_vars: int, samples: int, seed: int) -> np.ndarray:
    """SALib's design on the unit hypercube, drawn now.

    ``sobol``: ``SALib.sample.sobol.sample(N, calc_second_order=False)``, N (D + 2) rows;
    ``efast``: ``SALib.sample.fast_sampler.sample(N, M=4)``, N D rows.
    """
    unit = {"num_vars": num_vars, "names": [f"x{i}" for i in range(num_vars)]}
    unit["bounds"] = [[0.0, 1.0]] * num_vars
    if method == "sobol":
        from SALib.sample import sobol

        return sobol.sample(unit, samples, calc_second_order=False, seed=seed)
    from SALib.sample import fast_sampler

    return fast_sampler.sample(unit, samples, M=M_HARMONICS, seed=seed)


@lru_cache(maxsize=16)
def unit_design(method: str, num_vars: int, samples: int, seed: int) -> np.ndarray:
    """SALib's unit design (read-only), cached per process and on disk (:mod:`.design_cache`)."""
    from planar_tui.sensitivity.design_cache import cached_design, design_key

    design = cached_design(
        design_key(method, num_vars, samples, seed, M_HARMONICS),
        (design_rows(method, num_vars, samples), num_vars),
        lambda: salib_unit_design(method, num_vars, samples, seed),
    )
    design.setflags(write=False)
    return design


def scaled_design(problem: Problem, method: str, samples: int, seed: int) -> np.ndarray:
    """The design of ``problem``: unit design scaled as SALib scales it."""
    unit = unit_design(method, problem.num_vars, samples, seed)
    return unit * (problem.upper - problem.lower) + problem.lower


def evaluate(problem: Problem, unit: np.ndarray, robot, theta_rad, omega_rad_s, alpha_rad_s2):
    """Joint torques (S, n) of every row of the unit design ``unit`` scaled to ``problem``:
    one batched kernel call, bit-identical to the torques of :func:`scaled_design`."""
    from planar_tui.kernels.sensitivity_model import design_torques

    return design_torques(
        unit,
        problem.lower,
        problem.upper,
        np.ascontiguousarray(robot.arrays()[2], dtype=np.float64),
        float(robot.gravity_m_s2),
        np.asarray(theta_rad, dtype=np.float64),
        np.asarray(omega_rad_s, dtype=np.float64),
        np.asarray(alpha_rad_s2, dtype=np.float64),
    )


def analyse(method: str, outputs: np.ndarray, num_vars: int, seed: int) -> np.ndarray:
    """(4, n, D) indices S1, S1 half-width, ST, ST half-width of every torque."""
    from planar_tui.sensitivity.estimators import efast_indices, sobol_indices

    if method == "sobol":
        return sobol_indices(outputs, num_vars, seed)
    return efast_indices(outputs, num_vars, seed, M_HARMONICS)


def default_efast_samples(sobol_samples: int, num_vars: int) -> int:
    """eFAST N per input matching the Sobol' cost N (D + 2) in model runs (> 4 M²)."""
    return max(sobol_samples * (num_vars + 2) // num_vars, 4 * M_HARMONICS**2 + 1)

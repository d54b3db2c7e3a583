"""Sample (SALib), evaluate (batched Numba inverse dynamics), analyse (fast estimators).

The unit-hypercube designs depend only on (method, D, N, seed), so SALib draws each once
(kept per process and in the persistent :mod:`.design_cache`) and they are scaled per
robot exactly as ``SALib.util.scale_samples`` does (``x (ub - lb) + lb``): the scaled
matrix is bit-identical to SALib sampling the real problem. One design serves every posture and speed of a job: only the state changes.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from dataclasses import dataclass

import numpy as np

from planar_tui.jobkind import resolve
from planar_tui.progress import Progress
from planar_tui.sensitivity.design_cache import cached_design, design_key
from planar_tui.sensitivity.estimators import (
    efast_indices,
    efast_point_indices,
    sobol_bootstrap_counts,
    sobol_indices,
)
from planar_tui.uq import EFAST_HARMONICS as M_HARMONICS
from planar_tui.uq import EFAST_MIN_SAMPLES, design_rows


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


#: Sobol' base points drawn per chunk (a few ms each; a cancel check after each).
SOBOL_CHUNK_POINTS = 1 << 14


def _sobol_chunks(num_vars: int, samples: int, seed: int) -> Iterator[np.ndarray]:
    """SALib's Saltelli design without second order, ``SOBOL_CHUNK_POINTS`` base points
    (``D + 2`` rows each) at a time.

    The same operations as ``SALib.sample.sobol.sample`` on the unit cube: one scrambled
    ``scipy.stats.qmc.Sobol(2D, seed=seed)`` sequence, whose successive ``random(n)`` draws
    continue it exactly, arranged as rows ``A, A_B^(1) … A_B^(D), B`` (copies only), and
    SALib's scaling to [0, 1] (``x * 1 + 0``, exact)."""
    from scipy.stats import qmc

    engine = qmc.Sobol(d=2 * num_vars, scramble=True, seed=seed)
    columns = np.arange(num_vars)
    for start in range(0, samples, SOBOL_CHUNK_POINTS):
        base = engine.random(min(SOBOL_CHUNK_POINTS, samples - start))
        a, b = base[:, :num_vars], base[:, num_vars:]
        block = np.empty((len(base), num_vars + 2, num_vars))
        block[:, 0] = a
        block[:, 1 : num_vars + 1] = a[:, None, :]
        block[:, 1 + columns, columns] = b  # A_B^(k): column k of B in A
        block[:, num_vars + 1] = b
        yield block.reshape(-1, num_vars)


def _efast_chunks(num_vars: int, samples: int, seed: int) -> Iterator[np.ndarray]:
    """SALib's eFAST (``fast_sampler``, M = 4) search curves, one input's N rows at a time:
    the operations of ``SALib.sample.fast_sampler.sample`` in the same order (one
    ``default_rng(seed).random()`` phase per input)."""
    n, m_harmonics = samples, M_HARMONICS
    omega = np.zeros([num_vars])
    omega[0] = math.floor((n - 1) / (2 * m_harmonics))
    m = math.floor(omega[0] / (2 * m_harmonics))
    if m >= (num_vars - 1):
        omega[1:] = np.floor(np.linspace(1, m, num_vars - 1))
    else:
        omega[1:] = np.arange(num_vars - 1) % m + 1
    s = (2 * math.pi / n) * np.arange(n)
    rng = np.random.default_rng(seed)
    omega2 = np.zeros([num_vars])
    for i in range(num_vars):
        omega2[i] = omega[0]
        omega2[list(range(i)) + list(range(i + 1, num_vars))] = omega[1:]
        phi = 2 * math.pi * rng.random()
        block = np.zeros([n, num_vars])
        for j in range(num_vars):
            block[:, j] = 0.5 + (1 / math.pi) * np.arcsin(np.sin(omega2[j] * s + phi))
        yield block


def draw_unit_design(
    method: str, num_vars: int, samples: int, seed: int, on_chunk: Callable[[float], None]
) -> np.ndarray:
    """SALib's unit design (byte-identical to ``tests/salib_reference.salib_unit_design``), drawn in chunks
    of a few milliseconds; ``on_chunk(fraction)`` runs after each (it may raise
    :class:`~planar_tui.errors.Cancelled`)."""
    rows = design_rows(method, num_vars, samples)
    design = np.empty((rows, num_vars))
    chunks = _sobol_chunks if method == "sobol" else _efast_chunks
    filled = 0
    for chunk in chunks(num_vars, samples, seed):
        design[filled : filled + len(chunk)] = chunk
        filled += len(chunk)
        on_chunk(len(chunk) / rows)
    return design


_DESIGN_MEMO: dict[tuple, np.ndarray] = {}
#: Designs kept per process.
DESIGN_MEMO_SIZE = 16


def unit_design(
    method: str, num_vars: int, samples: int, seed: int, progress: Progress | None = None
) -> np.ndarray:
    """SALib's unit design (read-only), kept per process and on disk (:mod:`.design_cache`).

    ``progress`` advances by the fraction of the design drawn after each chunk (by 1 on a
    hit; its detail: the method) and is checked for a cancel, SciPy's import included;
    ``unit_design.cache_clear()`` empties the per-process memo."""
    drawn: list[float] = []

    def chunk_done(fraction: float) -> None:
        drawn.append(fraction)
        if progress is not None:
            progress.advance(fraction, method)

    def draw() -> np.ndarray:
        if progress is not None and method == "sobol":  # ~1 s the first time
            progress.wait_for(resolve, "scipy.stats")
        return draw_unit_design(method, num_vars, samples, seed, chunk_done)

    key = (method, num_vars, samples, seed)
    design = _DESIGN_MEMO.get(key)
    if design is None:
        design = cached_design(
            design_key(method, num_vars, samples, seed, M_HARMONICS),
            (design_rows(method, num_vars, samples), num_vars),
            draw,
        )
        design.setflags(write=False)
        while len(_DESIGN_MEMO) >= DESIGN_MEMO_SIZE:
            del _DESIGN_MEMO[next(iter(_DESIGN_MEMO))]
        _DESIGN_MEMO[key] = design
    if not drawn and progress is not None:  # read back whole
        progress.advance(1.0, method)
    return design


unit_design.cache_clear = _DESIGN_MEMO.clear  # type: ignore[attr-defined]


def scaled_design(problem: Problem, method: str, samples: int, seed: int) -> np.ndarray:
    """The design of ``problem``: unit design scaled as SALib scales it."""
    unit = unit_design(method, problem.num_vars, samples, seed)
    return unit * (problem.upper - problem.lower) + problem.lower


def montecarlo_design(num_vars: int, samples: int, seed: int) -> np.ndarray:
    """N independent uniform points of the unit cube, ``default_rng(seed).random((N, D))``."""
    return np.random.default_rng(seed).random((samples, num_vars))


def independent_rows(method: str, rows: int, num_vars: int) -> np.ndarray:
    """Indices of the rows of ``method``'s design (``rows`` of them) that are independent
    uniform points of the cube: a Saltelli design's A and B rows (the first and last of
    every block of D + 2), every row of a Monte-Carlo or PCE design. eFAST's search
    curves have none (they correlate the inputs): a ``ValueError``."""
    if method == "sobol":
        blocks = np.arange(rows).reshape(-1, num_vars + 2)
        return np.sort(np.concatenate([blocks[:, 0], blocks[:, -1]]))
    if method in ("montecarlo", "pce"):
        return np.arange(rows)
    raise ValueError(f"{method}'s rows are not independent uniform points")


#: Link-rows (design rows × links) per kernel call of :func:`evaluate`: ~10-30 ms.
EVALUATION_CHUNK_LINK_ROWS = 1 << 20


def evaluate(
    problem: Problem,
    unit: np.ndarray,
    robot,
    theta_rad,
    omega_rad_s,
    alpha_rad_s2,
    progress: Progress | None = None,
    detail: str = "",
):
    """Joint torques (S, n) of every row of the unit design ``unit`` scaled to ``problem``,
    bit-identical to the torques of :func:`scaled_design` (rows are independent).

    Batched kernel calls of ``EVALUATION_CHUNK_LINK_ROWS / n`` rows; ``progress`` (if any)
    advances by the fraction done (with ``detail``) after each, and may raise
    :class:`~planar_tui.errors.Cancelled`."""
    from planar_tui.kernels.sensitivity_model import design_torques

    arguments = (
        problem.lower,
        problem.upper,
        np.ascontiguousarray(robot.arrays()[2], dtype=np.float64),
        float(robot.gravity_m_s2),
        np.asarray(theta_rad, dtype=np.float64),
        np.asarray(omega_rad_s, dtype=np.float64),
        np.asarray(alpha_rad_s2, dtype=np.float64),
    )
    rows = unit.shape[0]
    step = max(256, EVALUATION_CHUNK_LINK_ROWS // problem.n_links)
    torques = np.empty((rows, problem.n_links))
    for start in range(0, rows, step):
        stop = min(rows, start + step)
        chunk = unit[start:stop]
        if start == 0 and progress is not None:  # may load the kernel: ~0.2 s
            torques[start:stop] = progress.wait_for(design_torques, chunk, *arguments)
        else:
            torques[start:stop] = design_torques(chunk, *arguments)
        if progress is not None:
            progress.advance((stop - start) / max(rows, 1), detail)
    return torques


def analyse(
    method: str,
    outputs: np.ndarray,
    num_vars: int,
    seed: int,
    progress: Progress | None = None,
    detail: str = "",
) -> np.ndarray:
    """(4, n, D) indices S1, S1 half-width, ST, ST half-width of every torque; ``progress``
    (if any) advances by the fraction done after each chunk of the analysis."""
    on_chunk = None if progress is None else (lambda fraction: progress.advance(fraction, detail))
    if method == "sobol":
        if progress is not None:  # the bootstrap draw: ~0.7 s at N = 2**18, then cached
            n_base = outputs.shape[0] // (num_vars + 2)
            progress.wait_for(sobol_bootstrap_counts, n_base, seed)
        return sobol_indices(outputs, num_vars, seed, on_chunk=on_chunk)
    return efast_indices(outputs, num_vars, seed, M_HARMONICS, on_chunk=on_chunk)


def point_indices(method: str, outputs: np.ndarray, num_vars: int) -> np.ndarray:
    """(4, n, D): the S1 and ST of :func:`analyse` (the same numbers) without its bootstrap,
    their half-widths NaN (not computed); 0 for an output that does not vary over the rows.

    For indices at many times (the motion job's every recorded time), where a bootstrap
    at each would cost more than the model runs."""
    from planar_tui.kernels.sensitivity_estimators import sobol_point

    outputs = np.asarray(outputs, dtype=np.float64)
    result = np.zeros((4, outputs.shape[1], num_vars))
    result[[1, 3]] = np.nan
    varying = np.ptp(outputs, axis=0) > 0
    if varying.any():
        chosen = np.ascontiguousarray(outputs[:, varying])
        if method == "sobol":
            point = sobol_point(chosen, num_vars)
        else:
            point = efast_point_indices(chosen, num_vars, M_HARMONICS)
        result[0, varying], result[2, varying] = point
    return result


def default_efast_samples(sobol_samples: int, num_vars: int) -> int:
    """eFAST N per input matching the Sobol' cost N (D + 2) in model runs (> 4 M²)."""
    return max(sobol_samples * (num_vars + 2) // num_vars, EFAST_MIN_SAMPLES)

r"""Sample robots, integrate them all (CPU or CUDA), take the outputs, the band and indices.

The inputs and designs are the sensitivity package's (:func:`~planar_tui.sensitivity.engine.build_problem`,
:func:`~planar_tui.sensitivity.engine.unit_design`, SALib's Sobol'/eFAST designs, cached);
Monte Carlo adds ``default_rng(seed).random((N, D))``. The band is taken over independent
uniform robots only (:meth:`Design.band_rows`): the Monte-Carlo rows, else the Sobol' design's
A and B rows; eFAST's search-curve rows are not such robots (with few samples per input
every complementary input runs at the same low frequency, so the inputs are correlated:
0.50 between every pair at D = 4, N = 128), so a job whose only method is ``efast`` also
integrates N Monte-Carlo robots for its band (:func:`design_methods`). Every row of every
design is one robot; all of them are integrated together (on the CPU by the lane-batched
RK4 of :mod:`kernels.motion_lanes`, :data:`~kernels.motion_lanes.LANES` robots per SIMD
block, equal to the scalar :func:`kernels.rk4.rk4_integrate` to round-off; or by
:mod:`kernels.motion_cuda`), in calls of about
:data:`~planar_tui.dynamics.simulate.CHUNK_SECONDS` for progress and cancel (sized by the
simulate job's :func:`~planar_tui.dynamics.simulate.next_chunk_steps`), stopping at every
recorded step to take the outputs: the relative joint angles
:math:`\theta_i` and the tip :math:`(x, y) = \sum_i l_i(\cos\phi_i, \sin\phi_i)`,
:math:`\phi_i = \sum_{j\le i}\theta_j`.
"""

from __future__ import annotations

import itertools
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from planar_tui.dynamics import simulate
from planar_tui.progress import Progress
from planar_tui.sensitivity.engine import independent_rows, unit_design
from planar_tui.sensitivity.engine import montecarlo_design as montecarlo_design  # re-export
from planar_tui.sensitivity.pce import pce_unit_design

#: Robots per CPU kernel call at most (a call then stays well under a second per step).
CPU_BLOCK_ROBOTS = 4096
#: Percentiles of the band.
PERCENTILES = (5.0, 50.0, 95.0)


#: The methods whose rows are independent uniform robots (:meth:`Design.band_rows`).
BAND_METHODS = ("montecarlo", "sobol", "pce")


@dataclass(frozen=True)
class Design:
    """Every robot of a job: the unit design (S, D), and which rows each method owns."""

    unit: np.ndarray
    rows: dict[str, slice]

    @property
    def samples(self) -> int:
        return self.unit.shape[0]

    def independent_rows(self, method: str) -> np.ndarray:
        """Rows (global indices) of ``method``'s independent uniform robots
        (:func:`~planar_tui.sensitivity.engine.independent_rows`: Sobol' A and B rows)."""
        rows = np.arange(self.samples)[self.rows[method]]
        return rows[independent_rows(method, len(rows), self.unit.shape[1])]

    def band_rows(self) -> np.ndarray:
        """Rows of independent uniform robots for the band: the Monte-Carlo rows, else the
        Sobol' design's A and B rows (2N).

        The A and B rows are the two halves of N points of one scrambled Sobol' sequence
        in 2D dimensions (:func:`~planar_tui.sensitivity.engine.unit_design`): each point is
        uniform on the cube with independent coordinates, the points themselves stratified
        (randomized quasi-Monte Carlo, not independent draws), which keeps the mean
        unbiased and the inputs uncorrelated (|r| below 0.1 at D = 4, N = 128 and at
        D = 12, N = 256). eFAST's rows never serve: its search curves correlate the
        inputs (:func:`design_methods` adds Monte-Carlo rows instead); a design without
        Monte-Carlo or Sobol' rows is a ``ValueError``."""
        if "montecarlo" in self.rows:
            return np.arange(self.samples)[self.rows["montecarlo"]]
        if "pce" in self.rows:  # a scrambled Sobol' sequence in D dimensions: uniform robots
            return np.arange(self.samples)[self.rows["pce"]]
        if "sobol" in self.rows:
            return self.independent_rows("sobol")
        raise ValueError(f"no independent uniform rows for the band among {tuple(self.rows)}")


def design_methods(methods: Sequence[str]) -> tuple[str, ...]:
    """The designs a job integrates: ``methods``, then ``montecarlo`` (N more robots, drawn
    as the Monte-Carlo method draws them, for the band only) when neither ``montecarlo``
    nor ``sobol`` is among them (eFAST alone: its rows are not independent robots)."""
    if any(method in BAND_METHODS for method in methods):
        return tuple(methods)
    return (*methods, "montecarlo")


def build_design(
    methods: Sequence[str],
    num_vars: int,
    samples: int,
    seed: int,
    progress: Progress | None,
    pce_samples: int = 0,
) -> Design:
    """The designs of :func:`design_methods` of ``methods`` stacked, in that order (sampling
    stage of ``progress``, one unit per design); the PCE's has ``pce_samples`` rows."""
    parts, rows, start = [], {}, 0
    for method in design_methods(methods):
        if method in ("montecarlo", "pce"):
            if method == "pce":
                part = pce_unit_design(num_vars, pce_samples, seed)
            else:
                part = montecarlo_design(num_vars, samples, seed)
            if progress is not None:
                progress.advance(1.0, method)
        else:
            part = unit_design(method, num_vars, samples, seed, progress)
        parts.append(part)
        rows[method] = slice(start, start + len(part))
        start += len(part)
    return Design(np.concatenate(parts), rows)


def tip_position(lengths_m: np.ndarray, theta_rad: np.ndarray) -> np.ndarray:
    r"""(S, 2) tip positions :math:`\sum_i l_i(\cos\phi_i, \sin\phi_i)` of (S, n) lengths
    and relative angles."""
    phi = np.cumsum(theta_rad, axis=1)
    return np.stack(
        [(lengths_m * np.cos(phi)).sum(axis=1), (lengths_m * np.sin(phi)).sum(axis=1)], axis=1
    )


def output_names(n_links: int, outputs: Sequence[str]) -> tuple[str, ...]:
    """Column stems of the outputs: ``theta1_rad`` … ``thetan_rad`` and/or ``tip_x_m``, ``tip_y_m``."""
    names: list[str] = []
    if "angles" in outputs:
        names += [f"theta{i}_rad" for i in range(1, n_links + 1)]
    if "tip" in outputs:
        names += ["tip_x_m", "tip_y_m"]
    return tuple(names)


def output_labels(names: Sequence[str]) -> tuple[str, ...]:
    """Short row labels for tables and plots: ``θ1``…, ``tip x``, ``tip y``."""
    return tuple(
        f"θ{name[5:-4]}" if name.startswith("theta") else name[:-2].replace("_", " ")
        for name in names
    )


def take_outputs(
    lengths_m: np.ndarray, theta_rad: np.ndarray, outputs: Sequence[str]
) -> np.ndarray:
    """(S, n_out) outputs of (S, n) angles, in :func:`output_names` order."""
    columns = []
    if "angles" in outputs:
        columns.append(theta_rad)
    if "tip" in outputs:
        columns.append(tip_position(lengths_m, theta_rad))
    return np.concatenate(columns, axis=1)


def band_statistics(values: np.ndarray) -> np.ndarray:
    """(5, n_out) mean, standard deviation (``ddof = 1``; 0 for one robot), 5th, 50th and
    95th percentile over the rows of (S, n_out) values."""
    std = values.std(axis=0, ddof=1) if len(values) > 1 else np.zeros(values.shape[1])
    return np.vstack([values.mean(axis=0), std, np.percentile(values, PERCENTILES, axis=0)])


def lane_ranges(robots: int, parts: int, lanes: int) -> list[tuple[int, int]]:
    """``[0, robots)`` cut into at most ``parts`` ranges of whole blocks of ``lanes`` robots
    (the last block may be short), as even as whole blocks allow: a block is the same robots
    in any range, so the ranges' results are one call's, bit for bit."""
    blocks = -(-robots // lanes)
    parts = max(1, min(parts, blocks))
    cuts = [min(robots, blocks * k // parts * lanes) for k in range(parts + 1)]
    return [(a, b) for a, b in itertools.pairwise(cuts) if a < b]


def run_lanes(kernel, params, gravity_m_s2, torque_Nm, theta_rad, omega_rad_s, step_s, n_steps):
    """``kernel`` (:func:`kernels.motion_lanes.rk4_lanes` or
    :func:`~kernels.motion_lanes.rk4_lanes_general`, serial over its blocks, GIL released)
    on every robot of ``params`` (S, 3, n) in place, the blocks shared among numba's threads
    (``numba.get_num_threads()``) as Python threads, a range of whole blocks each
    (:func:`lane_ranges`)."""
    import numba

    from planar_tui.kernels.motion_lanes import LANES

    def part(robots: tuple[int, int]) -> None:
        a, b = robots
        kernel(
            params[a:b], gravity_m_s2, torque_Nm, theta_rad[a:b], omega_rad_s[a:b], step_s, n_steps
        )

    ranges = lane_ranges(params.shape[0], numba.get_num_threads(), LANES)
    if len(ranges) == 1:
        part(ranges[0])
        return
    from concurrent.futures import ThreadPoolExecutor

    with ThreadPoolExecutor(max_workers=len(ranges)) as pool:
        list(pool.map(part, ranges))


class CpuRobots:
    """The robots on the CPU: parameters (S, 3, n) and states, the lane-batched
    :func:`kernels.motion_lanes.rk4_lanes` (chains of
    :data:`~kernels.motion_lanes.FUSED_LINKS` links: the fused step) or
    :func:`~kernels.motion_lanes.rk4_lanes_general` (others: the fused step never compiled)
    in calls of at most :data:`CPU_BLOCK_ROBOTS` robots, on numba's threads (:func:`run_lanes`)."""

    device = "cpu"

    def __init__(self, params, theta_rad, omega_rad_s, gravity_m_s2, torque_Nm):
        self.params = params
        self.theta = theta_rad
        self.omega = omega_rad_s
        self.gravity_m_s2 = float(gravity_m_s2)
        self.torque = torque_Nm
        samples = params.shape[0]
        self.blocks = [
            (start, min(samples, start + CPU_BLOCK_ROBOTS))
            for start in range(0, samples, CPU_BLOCK_ROBOTS)
        ]

    def advance(self, block: tuple[int, int], step_s: float, n_steps: int) -> None:
        from planar_tui.kernels.motion_lanes import FUSED_LINKS, rk4_lanes, rk4_lanes_general

        a, b = block
        run_lanes(
            rk4_lanes if self.params.shape[2] == FUSED_LINKS else rk4_lanes_general,
            self.params[a:b],
            self.gravity_m_s2,
            self.torque,
            self.theta[a:b],
            self.omega[a:b],
            step_s,
            n_steps,
        )

    def angles(self) -> np.ndarray:
        return self.theta


class CudaRobots:
    """The robots on a CUDA GPU (:class:`kernels.motion_cuda.CudaBatch`), one block."""

    device = "cuda"

    def __init__(self, batch):
        self.batch = batch
        self.blocks = [(0, batch.samples)]

    def advance(self, block: tuple[int, int], step_s: float, n_steps: int) -> None:
        self.batch.advance(step_s, n_steps)

    def angles(self) -> np.ndarray:
        return self.batch.angles()


def make_robots(device, problem, design, rod_inertias, robot, theta0_rad, omega0_rad_s, torque_Nm):
    """``(robots, params)``: the integrator of ``device`` (``cpu``/``cuda``) holding every
    design row's robot at the initial state, and the (S, 3, n) parameters (made on the host
    too: the tip needs the lengths)."""
    from planar_tui.kernels.motion_rk4 import design_parameters

    inertias = np.ascontiguousarray(robot.arrays()[2])
    unit = np.ascontiguousarray(design.unit)
    params = design_parameters(unit, problem.lower, problem.upper, inertias, rod_inertias)
    samples = design.samples
    theta = np.repeat(np.asarray(theta0_rad, dtype=np.float64)[None, :], samples, axis=0)
    omega = np.repeat(np.asarray(omega0_rad_s, dtype=np.float64)[None, :], samples, axis=0)
    torque = np.ascontiguousarray(torque_Nm, dtype=np.float64)
    if device == "cuda":
        from planar_tui.kernels.motion_cuda import CudaBatch

        batch = CudaBatch(
            unit,
            problem.lower,
            problem.upper,
            inertias,
            rod_inertias,
            theta,
            omega,
            robot.gravity_m_s2,
            torque,
        )
        return CudaRobots(batch), params
    return CpuRobots(params, theta, omega, robot.gravity_m_s2, torque), params


def integrate(
    robots,
    step_s: float,
    stops: Sequence[int],
    on_stop: Callable[[int, np.ndarray], None],
    progress: Progress | None = None,
) -> None:
    """Advance every robot from step 0 through the sorted global step indices ``stops``
    (0 first), calling ``on_stop(k, angles)`` at each. Calls of ``n`` steps of one block of
    robots are sized by :func:`~planar_tui.dynamics.simulate.next_chunk_steps` (no step
    cap) from the slowest block's last call; ``progress`` counts robot-steps and is
    checked after each call."""

    done = 0
    steps = 1
    on_stop(0, robots.angles())
    for stop in stops[1:]:
        while done < stop:
            n_steps = min(steps, stop - done)
            slowest = 0.0
            for block in robots.blocks:
                started = time.perf_counter()
                robots.advance(block, step_s, n_steps)
                slowest = max(slowest, time.perf_counter() - started)
                if progress is not None:
                    t_s = (done + n_steps) * step_s
                    progress.advance((block[1] - block[0]) * n_steps, f"t = {t_s:.4g} s")
            done += n_steps
            steps = simulate.next_chunk_steps(n_steps, slowest, stops[-1] - done)
        on_stop(stop, robots.angles())

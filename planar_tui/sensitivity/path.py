r"""Joint torques along a prescribed rest-to-rest path, for every robot of a design.

The path is the quintic joint interpolation from the posture :math:`\theta_0` to
:math:`\theta_1` in T seconds, at rest at both ends (zero speed and acceleration):

.. math:: \theta(t) = \theta_0 + (\theta_1 - \theta_0)\,s(\tau),\quad \tau = t/T,\quad
          s = 10\tau^3 - 15\tau^4 + 6\tau^5,

:math:`\dot\theta = (\theta_1-\theta_0)\,s'/T`, :math:`\ddot\theta = (\theta_1-\theta_0)\,s''/T^2`
with :math:`s' = 30\tau^2(1-\tau)^2`, :math:`s'' = 60\tau(1-\tau)(1-2\tau)`, sampled at
:math:`t_k = kT/K`, k = 0 … K. At every state, each robot's torques are the batched inverse
dynamics of :func:`~planar_tui.sensitivity.engine.evaluate`. The path's summary outputs,
per joint j: the peak :math:`\max_k |\tau_j(t_k)|` and the RMS
:math:`\sqrt{\frac1T\int_0^T \tau_j^2\,dt}` (trapezoidal rule on the samples). The job's
path outputs, their variances over independent uniform runs (the aggregation's weights)
and its ``path`` and ``path_aggregated`` tables live here too (:func:`path_tables`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from planar_tui.csvio import CsvTable
from planar_tui.progress import Progress

if TYPE_CHECKING:
    import numpy as np

    from planar_tui.sensitivity.results import Analysis


@dataclass(frozen=True)
class PathSpec:
    """A quintic rest-to-rest joint path from the posture to ``to_deg`` in ``duration_s``,
    sampled at ``steps + 1`` times (:func:`~planar_tui.sensitivity.path.quintic_path`)."""

    to_deg: tuple[float, ...]
    duration_s: float
    steps: int


@dataclass(frozen=True)
class JointPath:
    """Times (K + 1,) and joint angles, speeds, accelerations (K + 1, n) of a path."""

    t_s: np.ndarray
    theta_rad: np.ndarray
    omega_rad_s: np.ndarray
    alpha_rad_s2: np.ndarray


def quintic_path(theta0_rad, theta1_rad, duration_s: float, steps: int) -> JointPath:
    """The rest-to-rest quintic path from ``theta0_rad`` to ``theta1_rad`` (each (n,)) in
    ``duration_s``, sampled at ``steps + 1`` equally spaced times (both ends included)."""
    import numpy as np

    start = np.asarray(theta0_rad, dtype=np.float64)
    delta = np.asarray(theta1_rad, dtype=np.float64) - start
    t = np.linspace(0.0, duration_s, steps + 1)
    tau = (t / duration_s)[:, None]
    s = tau**3 * (10.0 - 15.0 * tau + 6.0 * tau**2)
    ds = 30.0 * tau**2 * (1.0 - tau) ** 2
    dds = 60.0 * tau * (1.0 - tau) * (1.0 - 2.0 * tau)
    return JointPath(t, start + delta * s, delta * ds / duration_s, delta * dds / duration_s**2)


def path_torques(problem, unit, robot, path: JointPath, progress: Progress | None = None):
    """Torques (S, K + 1, n) of every design row (``unit`` scaled to ``problem``) at every
    state of ``path``; ``progress`` (if any) advances by 1 / (K + 1) per state."""
    import numpy as np

    from planar_tui.sensitivity.engine import evaluate

    states = len(path.t_s)
    torques = np.empty((unit.shape[0], states, problem.n_links))
    for k in range(states):
        torques[:, k] = evaluate(
            problem, unit, robot, path.theta_rad[k], path.omega_rad_s[k], path.alpha_rad_s2[k]
        )
        if progress is not None:
            progress.advance(1.0 / states, f"path state {k + 1}/{states}")
    return torques


def peak_and_rms(torques: np.ndarray, t_s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Peak |τ| and RMS τ (each (S, n)) of torques (S, K + 1, n) sampled at ``t_s``."""
    import numpy as np

    peak = np.abs(torques).max(axis=1)
    weights = _trapezoid_weights(t_s)
    rms = np.sqrt(np.einsum("skn,k->sn", torques**2, weights) / (t_s[-1] - t_s[0]))
    return peak, rms


def _trapezoid_weights(t_s: np.ndarray) -> np.ndarray:
    """Weights w with Σ w_k f(t_k) the trapezoidal rule on the samples ``t_s``."""
    import numpy as np

    gaps = np.diff(t_s)
    weights = np.zeros(len(t_s))
    weights[:-1] += gaps / 2.0
    weights[1:] += gaps / 2.0
    return weights


def path_outputs(problem, unit, robot, theta_rad, path: PathSpec, progress: Progress):
    """Model outputs (S, 2n + (K+1) n) along the path: peak |τ_j|, RMS τ_j, then every
    torque at every step (step-major)."""
    import numpy as np

    states = quintic_path(theta_rad, np.radians(path.to_deg), path.duration_s, path.steps)
    torques = path_torques(problem, unit, robot, states, progress)
    peak, rms = peak_and_rms(torques, states.t_s)
    return np.concatenate([peak, rms, torques.reshape(len(unit), -1)], axis=1)


def path_variances(method: str, values, extra, unit, n: int):
    """``(variances ((K+1) n,), runs)``: the path torques' variances over ``method``'s
    independent uniform runs (Sobol': the A and B rows; PCE: every run) and the model runs
    the method made; eFAST's over the outputs ``extra`` of its N Monte-Carlo rows, which
    count among its runs."""
    from planar_tui.sensitivity.engine import independent_rows

    runs = len(unit)
    if extra is not None:
        return extra[:, 2 * n :].var(axis=0), runs + len(extra)
    rows = independent_rows(method, len(values), unit.shape[1])
    return values[rows, 2 * n :].var(axis=0), runs


def path_labels(n: int, symbol: str = "τ") -> tuple[str, ...]:
    """Row labels of the peak and RMS outputs: ``peak|τ1|`` … ``RMS τn`` (``symbol``: the
    effort's, ``F`` for prismatic actuators' forces)."""
    return (
        *(f"peak|{symbol}{j}|" for j in range(1, n + 1)),
        *(f"RMS {symbol}{j}" for j in range(1, n + 1)),
    )


def effort_names(n: int, effort: str = "tau", unit: str = "Nm") -> tuple[str, ...]:
    """The per-step efforts' column names: ``tau1_Nm`` … (``force1_N`` … for prismatic
    actuators: ``effort = "force"``, ``unit = "N"``), as the path jobs' CSV."""
    return tuple(f"{effort}{j}_{unit}" for j in range(1, n + 1))


def path_context(posture: str, path: PathSpec) -> str:
    """A path table's title: where from, where to, in how long."""
    to = ", ".join(f"{a:g}" for a in path.to_deg)
    return f"path {posture} → [{to}] deg in {path.duration_s:g} s"


def path_tables(
    along: list[Analysis],
    path: PathSpec,
    n: int,
    variances: Mapping[str, Any],
    names: Sequence[str] | None = None,
) -> dict[str, Any]:
    """The ``path`` table: the indices of every effort at every step of the path, shaped
    like the motion indices CSV (``output, t_s, parameter, method, …``; ``names``: the n
    efforts' names, :func:`effort_names`, the torques by default); the ``path_aggregated``
    table: each actuator's effort over the path and all efforts together (Gamboa et al.
    2014), weighted by the efforts' variances over independent uniform runs
    (``variances``: method -> (((K+1) n,) step-major, runs): :func:`path_variances`)."""
    import numpy as np

    from planar_tui.sensitivity.aggregate import aggregated_indices
    from planar_tui.sensitivity.results import (
        AGGREGATED_HEADER,
        Analysis,
        aggregated_rows,
        sensitivity_percent,
        time_indices_table,
    )

    steps = path.steps + 1
    t_s = np.linspace(0.0, path.duration_s, steps)
    names = tuple(names or effort_names(n))
    everything = "all torques" if names[0].startswith("tau") else "all forces"
    per_time = []
    rows = []
    for a in along:
        trajectory = a.indices[:, 2 * n :].reshape(4, steps, n, -1)
        loo = None if a.loo_error is None else a.loo_error[2 * n :].reshape(steps, n)
        defined = None if a.defined is None else a.defined[2 * n :].reshape(steps, n)
        for k in range(steps):
            indices = trajectory[:, k]
            per_time.append(
                Analysis(
                    a.method,
                    a.posture,
                    float(t_s[k]),
                    a.names,
                    indices,
                    sensitivity_percent(indices, "ST"),
                    names,
                    runs=a.runs,
                    loo_error=None if loo is None else loo[k],
                    defined=None if defined is None else defined[k],
                )
            )
        variance, runs = variances[a.method]
        weights = variance.reshape(steps, n)
        groups = [(name, trajectory[[0, 2], :, j], weights[:, j]) for j, name in enumerate(names)]
        groups.append(
            (everything, trajectory[[0, 2]].reshape(2, steps * n, -1), weights.reshape(-1))
        )
        for label, indices, weight in groups:
            first, total = aggregated_indices(indices, weight)
            rows += aggregated_rows(label, a.names, a.method, first, total, runs)
    per_time.sort(key=lambda a: a.speed_rad_s)
    return {
        "path": time_indices_table(per_time, names),
        "path_aggregated": CsvTable(AGGREGATED_HEADER, rows),
    }

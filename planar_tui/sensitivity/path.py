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
:math:`\sqrt{\frac1T\int_0^T \tau_j^2\,dt}` (trapezoidal rule on the samples).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from planar_tui.progress import Progress


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
    peak = np.abs(torques).max(axis=1)
    weights = _trapezoid_weights(t_s)
    rms = np.sqrt(np.einsum("skn,k->sn", torques**2, weights) / (t_s[-1] - t_s[0]))
    return peak, rms


def _trapezoid_weights(t_s: np.ndarray) -> np.ndarray:
    """Weights w with Σ w_k f(t_k) the trapezoidal rule on the samples ``t_s``."""
    gaps = np.diff(t_s)
    weights = np.zeros(len(t_s))
    weights[:-1] += gaps / 2.0
    weights[1:] += gaps / 2.0
    return weights

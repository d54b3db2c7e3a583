r"""Two small NumPy minimisers for the isotropic-posture search (no SciPy import).

* :func:`levenberg_marquardt`: :math:`\min_x \|r(x)\|^2` by damped Gauss-Newton steps
  :math:`(J^TJ + \lambda\,\mathrm{diag}(J^TJ))\,\delta = -J^Tr` with a central-difference
  Jacobian; :math:`\lambda` shrinks ×0.3 after a successful step and grows ×10 after a
  failed one (Marquardt 1963).
* :func:`nelder_mead`: the simplex method (Nelder & Mead 1965; reflection 1, expansion 2,
  contraction ½, shrink ½) for a possibly non-smooth f, here the condition number itself.

Both are deterministic. ``tests/test_sensitivity_postures.py`` checks the postures they
find against ``scipy.optimize`` (an independent implementation).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np


def _jacobian(residual, x: np.ndarray, r0: np.ndarray) -> np.ndarray:
    """Central differences, step ``1e-7 max(1, |x_i|)`` (truncation error ~1e-14)."""
    jac = np.empty((r0.size, x.size))
    for i in range(x.size):
        h = 1e-7 * max(1.0, abs(x[i]))
        up, down = x.copy(), x.copy()
        up[i] += h
        down[i] -= h
        jac[:, i] = (residual(up) - residual(down)) / (2.0 * h)
    return jac


def levenberg_marquardt(
    residual: Callable[[np.ndarray], np.ndarray],
    x0,
    *,
    xtol: float = 1e-14,
    ftol: float = 1e-12,
    max_iterations: int = 200,
) -> np.ndarray:
    """A local minimiser of ``||residual(x)||²`` from ``x0``: stops when a step moves x by
    less than ``xtol`` (relative) or lowers the cost by less than ``ftol`` (relative)."""
    x = np.array(x0, dtype=np.float64)
    r = residual(x)
    cost = float(r @ r)
    damping = 1e-3
    for _ in range(max_iterations):
        if cost < 1e-30:
            break
        jac = _jacobian(residual, x, r)
        gradient = jac.T @ r
        normal = jac.T @ jac
        scale = np.diag(np.diag(normal) + 1e-300)
        while damping < 1e12:
            step = np.linalg.solve(normal + damping * scale, -gradient)
            trial = x + step
            r_trial = residual(trial)
            cost_trial = float(r_trial @ r_trial)
            if cost_trial < cost:
                converged = cost - cost_trial <= ftol * cost
                x, r, cost = trial, r_trial, cost_trial
                damping = max(damping * 0.3, 1e-12)
                break
            damping *= 10.0
        else:
            break  # no descent direction left: a (local) minimum to round-off
        if converged or np.linalg.norm(step) <= xtol * (np.linalg.norm(x) + xtol):
            break
    return x


def nelder_mead(
    f: Callable[[np.ndarray], float],
    x0,
    *,
    initial_step: float = 0.05,
    xtol: float = 1e-10,
    ftol: float = 1e-14,
    max_iterations: int = 4000,
) -> np.ndarray:
    """A local minimiser of ``f`` from ``x0`` (simplex of edge ``initial_step``)."""
    x0 = np.asarray(x0, dtype=np.float64)
    simplex = np.vstack([x0, x0 + initial_step * np.eye(x0.size)])
    values = np.array([f(p) for p in simplex])
    for _ in range(max_iterations):
        order = np.argsort(values, kind="stable")
        simplex, values = simplex[order], values[order]
        spread = np.abs(simplex[1:] - simplex[0]).max()
        if spread <= xtol and values[-1] - values[0] <= ftol:
            break
        centroid = simplex[:-1].mean(axis=0)
        reflected = centroid + (centroid - simplex[-1])
        f_reflected = f(reflected)
        if f_reflected < values[0]:
            expanded = centroid + 2.0 * (centroid - simplex[-1])
            f_expanded = f(expanded)
            if f_expanded < f_reflected:
                simplex[-1], values[-1] = expanded, f_expanded
            else:
                simplex[-1], values[-1] = reflected, f_reflected
        elif f_reflected < values[-2]:
            simplex[-1], values[-1] = reflected, f_reflected
        else:
            inside = f_reflected >= values[-1]
            target = simplex[-1] if inside else reflected
            contracted = centroid + 0.5 * (target - centroid)
            f_contracted = f(contracted)
            if f_contracted < min(f_reflected, values[-1]):
                simplex[-1], values[-1] = contracted, f_contracted
            else:
                simplex[1:] = simplex[0] + 0.5 * (simplex[1:] - simplex[0])
                values[1:] = [f(p) for p in simplex[1:]]
    return simplex[int(np.argmin(values))]

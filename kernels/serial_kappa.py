"""The dexterity κ of the serial n-link arm's tip Jacobian, row by row of a trajectory.

With relative joint angles :math:`\\theta_j`, absolute link angles
:math:`\\varphi_k = \\sum_{j \\le k} \\theta_j` and link lengths :math:`l_k`, the tip
:math:`x = \\sum_k l_k \\cos\\varphi_k`, :math:`y = \\sum_k l_k \\sin\\varphi_k`,
:math:`\\varphi = \\varphi_n` has the Jacobian columns

.. math:: J_{:, j} = \\Big(-\\sum_{k \\ge j} l_k \\sin\\varphi_k,\\
          \\sum_{k \\ge j} l_k \\cos\\varphi_k,\\ L\\Big)^T

(the last row only for the pose, :math:`L` the characteristic length weighing
:math:`\\dot\\varphi` in the twist :math:`(\\dot x, \\dot y, L\\dot\\varphi)`). κ is the
2-norm condition number :math:`\\sigma_1 / \\sigma_m` over the task's :math:`m` (2 or 3)
singular values, :math:`\\infty` where :math:`J` has rank below :math:`m` (fewer joints than
:math:`m`, or :math:`\\sigma_m \\le \\sigma_1 \\max(m, n)\\, \\epsilon`: numpy's
``matrix_rank`` tolerance).
"""

import numpy as np

from ._jit import kernel


@kernel
def tip_jacobian(lengths_m, theta_rad, length_m, out):
    """Fill ``out`` ((2, n), or (3, n) for the pose with its last row ``length_m``) with the
    tip Jacobian at the relative joint angles ``theta_rad`` (n,)."""
    n = lengths_m.shape[0]
    x = np.empty(n)
    y = np.empty(n)
    phi = 0.0
    for k in range(n):
        phi += theta_rad[k]
        x[k] = lengths_m[k] * np.cos(phi)
        y[k] = lengths_m[k] * np.sin(phi)
    sx = 0.0
    sy = 0.0
    for j in range(n - 1, -1, -1):
        sx += x[j]
        sy += y[j]
        out[0, j] = -sy
        out[1, j] = sx
        if out.shape[0] == 3:
            out[2, j] = length_m


@kernel
def tip_kappa(lengths_m, theta_rad, length_m, kappa_out):
    """κ of each row of ``theta_rad`` (rows, n) into ``kappa_out`` (rows,): of the position
    Jacobian (2 x n) where ``length_m <= 0``, of the pose Jacobian (3 x n) weighted by
    ``length_m`` otherwise; NaN where the row's angles are not all finite (a diverged
    integration, which the job then refuses)."""
    n = lengths_m.shape[0]
    m = 3 if length_m > 0.0 else 2
    jac = np.empty((m, n))
    for row in range(theta_rad.shape[0]):
        if n < m:
            kappa_out[row] = np.inf
            continue
        if not np.all(np.isfinite(theta_rad[row])):
            kappa_out[row] = np.nan
            continue
        tip_jacobian(lengths_m, theta_rad[row], length_m, jac)
        sigma = np.linalg.svd(jac, full_matrices=False)[1]
        if sigma[m - 1] <= sigma[0] * max(m, n) * np.finfo(np.float64).eps:
            kappa_out[row] = np.inf
        else:
            kappa_out[row] = sigma[0] / sigma[m - 1]

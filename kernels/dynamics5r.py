r"""Inverse dynamics of the five-bar by the NOC: the RR-leg kernel of
:mod:`kernels.dynamics3rrr` with two legs meeting at a point platform.

The independent coordinates are the end-effector joint :math:`X = P = (x, y)`; both legs'
platform points are :math:`P` itself (:math:`q_i = 0`, so :math:`r_i = 0` and the
Jacobian rows reduce to :math:`J_{\theta,i} = e(\psi_i)^T/(l_{1,i}s_i)`,
:math:`J_{\psi,i} = -e(\theta_i)^T/(l_{2,i}s_i)`); the "platform" is the end mass
:math:`m_P` at :math:`P` (no inertia), contributing :math:`(m_P\ddot x, m_P(\ddot y + g))`
to :math:`F`; the torques solve the 2x2 :math:`A^T\tau = F`, :math:`\det A = 0` being the
five-bar's type II singularity (the distal links aligned).
"""

import numpy as np

from .dynamics3rrr import LEG_COLUMNS, LEG_QX, LEG_QY, solve_rr_path


def solve_fivebar_path(legs, body, pose, rate, acceleration, singular_relative):
    """:func:`kernels.dynamics3rrr.solve_rr_path` for (2, :data:`LEG_COLUMNS`) leg rows
    with zero platform points and (n, 2) end-effector states; ``ValueError`` otherwise."""
    legs = np.asarray(legs, dtype=np.float64)
    if legs.shape != (2, LEG_COLUMNS) or np.any(legs[:, LEG_QX : LEG_QY + 1] != 0.0):
        raise ValueError("a five-bar has two legs meeting at the point P (q_i = 0)")
    if np.shape(pose)[1:] != (2,):
        raise ValueError("a five-bar's states are (n, 2): x, y")
    return solve_rr_path(legs, body, pose, rate, acceleration, singular_relative)

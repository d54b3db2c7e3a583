r"""The actuator efforts of many robots of one family along one sampled path: the
sensitivity study's hot path (thousands of robots, each a design row, on the same platform
states).

Each robot r is the single-robot kernel of its family, unchanged (so its efforts are the
same numbers as one call of that kernel for that robot): the RR legs of
:func:`kernels.dynamics3rrr.rr_path_dynamics` (the 3-RRR, and the five-bar with a point
platform), the RPR legs of :func:`kernels.dynamics3rpr.rpr_path_dynamics`, the PRR legs of
:func:`kernels.dynamics3prr.prr_path_dynamics`; each solves, at every platform state
:math:`(X, \dot X, \ddot X)_k`, the NOC's :math:`A^T\tau = F` (their docstrings hold the
equations). Robots run in parallel (``prange``); a robot whose path fails at some sample
(no closure, a limit, a singularity) gets NaN efforts at every sample.
"""

import numpy as np
from numba import prange

from ._jit import kernel
from .dynamics3prr import prr_path_dynamics
from .dynamics3rpr import rpr_path_dynamics
from .dynamics3rrr import OK, rr_path_dynamics

#: Leg families: the single-robot kernel each robot runs.
RR_LEGS, RPR_LEGS, PRR_LEGS = range(3)


@kernel(parallel=True)
def robots_path_efforts(family, legs, body, pose, rate, acceleration, singular_relative, effort):
    """Efforts ``effort`` (R, n, d) of R robots of one ``family`` (:data:`RR_LEGS`,
    :data:`RPR_LEGS`, :data:`PRR_LEGS`) with leg rows ``legs`` (R, d, columns) and body
    entries ``body`` (R, entries), at the states ``pose``, ``rate``, ``acceleration``
    (n, pose dimension; SI); NaN for every sample of a robot whose path fails somewhere.
    Returns whether each robot's path failed (R,)."""
    robots = legs.shape[0]
    n, d = effort.shape[1], effort.shape[2]
    failed = np.zeros(robots, dtype=np.bool_)
    for r in prange(robots):
        coordinate = np.empty((n, d))
        coordinate_rate = np.empty((n, d))
        coordinate_acceleration = np.empty((n, d))
        status = np.empty(n, dtype=np.int64)
        closure = np.empty(n)
        arguments = (legs[r], body[r], pose, rate, acceleration, singular_relative)
        outputs = (coordinate, coordinate_rate, coordinate_acceleration, effort[r])
        if family == RR_LEGS:
            rr_path_dynamics(*arguments, *outputs, status, closure)
        elif family == RPR_LEGS:
            rpr_path_dynamics(*arguments, *outputs, status, closure)
        else:
            prr_path_dynamics(*arguments, *outputs, status, closure)
        for k in range(n):
            if status[k] != OK:
                failed[r] = True
        if failed[r]:
            effort[r] = np.nan
    return failed

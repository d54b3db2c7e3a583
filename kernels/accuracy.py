"""Certified enclosures of a parallel robot's pose error under actuator and geometric errors,
by a Krawczyk-type operator.

Every leg of the robots here is a *distance constraint*: leg ``i`` joins a point
:math:`B_i` fixed to its actuated chain to the platform point :math:`C_i = p + R(\\varphi)
c_i` (the five-bar: :math:`C_i = p`, its tip) at a distance :math:`\\ell_i`,

.. math:: f_i(x, q, g) = \\tfrac12 \\left(|C_i - B_i|^2 - \\ell_i^2\\right) = 0, \\qquad
          x = (p, \\varphi),

with :math:`q` the actuated coordinates and :math:`g` the geometry. A robot with errors
:math:`\\Delta q, \\Delta g` within their bounds, built to reach the nominal pose
:math:`x` with the nominal :math:`q(x)` of the working mode, stands at :math:`x + \\Delta
x` with :math:`G(\\Delta x) = F(x + \\Delta x, q + \\Delta q, g + \\Delta g) = 0`. With
:math:`d_i = C_i - B_i` and :math:`s_i = R(\\varphi) c_i` of that robot at :math:`x`, a
pose error moves :math:`d_i` by :math:`\\Delta d_i = \\Delta p + (R(\\Delta\\varphi) -
I)\\,s_i`, and since :math:`f_i` is quadratic in :math:`d_i`, *exactly*

.. math:: G_i(\\Delta x) = G_i(0) + J_{0,i}\\,\\Delta x + N_i(\\Delta x), \\qquad
          N_i = d_i \\cdot (R(\\Delta\\varphi) - I - \\Delta\\varphi E)\\,s_i
          + \\tfrac12 |\\Delta d_i|^2,

:math:`J_0` with rows :math:`(d_{ix}, d_{iy}, d_i \\cdot E s_i)` (:math:`E` the quarter
turn) and :math:`N` the remainder, of second order. The residual is, by the mean-value
theorem (and :math:`F(x, q, g) = 0`), :math:`G_i(0) \\in [-\\rho_i, \\rho_i]` with
:math:`\\rho_i = \\sum_k |\\partial f_i / \\partial (q, g)_k|\\,\\delta_k` over the hull
of the box's poses and every perturbed robot (a robot's kernel computes :math:`\\rho_i`,
:math:`J_0` and :math:`s_i` as intervals over that hull; the legs' errors are independent,
so the bound is sharp to first order).

**Certificate** (:func:`krawczyk`): with :math:`C` the inverse of the midpoint of
:math:`J_0` and a candidate box :math:`D` of pose errors, the Krawczyk-type operator

.. math:: T(D) = -C\\,\\big([-\\rho, \\rho] + N(D)\\big) + (I - C J_0)\\,D

encloses :math:`\\Delta x - C\\,G(\\Delta x)` for every :math:`\\Delta x \\in D` and every
perturbed robot. If :math:`T(D) \\subset \\operatorname{int} D`, that map sends
:math:`D` into itself, so (Brouwer) every perturbed robot has a pose :math:`x + \\Delta x`
with :math:`\\Delta x \\in D`, and every such pose lies in :math:`T(D)`, off
:math:`D`'s boundary; scaling the errors by :math:`s \\in [0, 1]` shrinks their bounds, so
the test holds all along, and the pose the robot reaches from the nominal one as its errors
grow cannot leave :math:`D`. The remainder of the linearisation is bounded, not neglected.
:math:`D` starts from the linear estimate :math:`|C|\\rho`, inflated; a candidate that
fails is widened (epsilon inflation) up to ``ATTEMPTS`` times, then the box is *not
certified* (near a singularity, where :math:`J_0` is nearly singular or the remainder
dominates, or a box too wide). A proof is tightened by :math:`D \\leftarrow T(D) \\cap D`.
"""

import math

import numpy as np

from ._jit import kernel
from .dexterity import IN
from .interval import down, iadd, imul, isincos, isqr, isub, up
from .path_certify_rr import platform_offset

#: Rows of boxes a thread certifies with one set of leg scratch arrays (:func:`leg_scratch`).
BLOCK_ROWS = 64
#: Candidates tried per box before it is given up (not certified).
ATTEMPTS = 12
#: Contractions :math:`D \leftarrow T(D) \cap D` after the proof.
TIGHTEN = 3
#: First candidate: the linear estimate times this, plus ``FLOOR``.
START = 1.25
#: Epsilon inflation of a failed candidate, relative to its width.
INFLATE = 0.25
#: Absolute inflation (cm, rad): a zero estimate still gets a box with an interior.
FLOOR = 1e-12
#: A candidate wider than this (cm, rad) is given up.
WIDEST = 1e3


@kernel
def mag(lo, hi):
    """:math:`\\max |X|`."""
    return max(abs(lo), abs(hi))


@kernel
def widen(lo, hi, t):
    """:math:`X + [-t, t]`."""
    return iadd(lo, hi, -t, t)


@kernel
def pose_offsets(boxes, i, q, n, r_lo, r_hi):
    """Row ``i`` of the pose boxes ``boxes`` (``x_lo, x_hi, y_lo, y_hi, phi_lo, phi_hi``):
    the enclosures of :math:`R(\\varphi) c_i` over its orientations written to rows
    ``0 .. n-1`` of ``r_lo, r_hi`` (``q`` (n, 2) the :math:`c_i` in the platform's frame),
    and ``trig = (s_lo, s_hi, c_lo, c_hi)``, the enclosures of :math:`\\sin\\varphi,
    \\cos\\varphi` (:func:`kernels.interval.isincos`)."""
    trig = isincos(boxes[i, 4], boxes[i, 5])
    for leg in range(n):
        r_lo[leg, 0], r_hi[leg, 0], r_lo[leg, 1], r_hi[leg, 1] = platform_offset(
            q[leg, 0], q[leg, 1], *trig
        )
    return trig


@kernel
def joint_box(xlo, xhi, ylo, yhi, leg, r_lo, r_hi):
    """The box ``(cx_lo, cx_hi, cy_lo, cy_hi)`` of leg ``leg``'s platform joint
    :math:`C_i = p + R(\\varphi) c_i` over the (x, y) box and the offsets' enclosure."""
    cx_lo, cx_hi = iadd(xlo, xhi, r_lo[leg, 0], r_hi[leg, 0])
    cy_lo, cy_hi = iadd(ylo, yhi, r_lo[leg, 1], r_hi[leg, 1])
    return cx_lo, cx_hi, cy_lo, cy_hi


@kernel
def joint_terms(leg, errors, trig, w_lo, w_hi, r_lo, r_hi):
    """Leg ``leg``'s platform offset :math:`s_i = R(\\varphi)(c_i + \\Delta c_i)`: its
    row of ``r_lo, r_hi`` (the enclosure of :math:`R(\\varphi) c_i`, :func:`pose_offsets`)
    widened for :math:`\\Delta c_i` (each coordinate in the platform's frame within
    ``errors[2]``), and, with its row of ``w`` (:math:`p - B_i`) written before, ``(dx, dy,
    joints)``: the enclosure of :math:`d_i = w_i + s_i` and the joints' share of
    :math:`\\rho_i`, :math:`t\\,(|d_{ix}| + |d_{iy}|) + t_c\\,|R(\\varphi)^T d_i|_1` (the
    base joint's coordinates within :math:`t` = ``errors[1]``, the platform joint's within
    :math:`t_c` = ``errors[2]``). ``errors`` = ``(actuator, t, t_c)``, ``trig`` the
    enclosures of :math:`\\sin\\varphi, \\cos\\varphi` over the box's orientations."""
    t, tc = errors[1], errors[2]
    s_lo, s_hi, c_lo, c_hi = trig
    spread = up(up(tc * up(mag(c_lo, c_hi) + mag(s_lo, s_hi))) + 1e-10)  # and round-off
    r_lo[leg, 0], r_hi[leg, 0] = widen(r_lo[leg, 0], r_hi[leg, 0], spread)
    r_lo[leg, 1], r_hi[leg, 1] = widen(r_lo[leg, 1], r_hi[leg, 1], spread)
    dx = iadd(w_lo[leg, 0], w_hi[leg, 0], r_lo[leg, 0], r_hi[leg, 0])
    dy = iadd(w_lo[leg, 1], w_hi[leg, 1], r_lo[leg, 1], r_hi[leg, 1])
    local_x = iadd(*imul(c_lo, c_hi, *dx), *imul(s_lo, s_hi, *dy))  # R^T d
    local_y = isub(*imul(c_lo, c_hi, *dy), *imul(s_lo, s_hi, *dx))
    size = up(mag(*dx) + mag(*dy))
    joints = up(t * size)
    joints = up(joints + up(tc * up(mag(*local_x) + mag(*local_y))))
    return dx, dy, joints


@kernel
def jacobian(w_lo, w_hi, r_lo, r_hi, n, j_lo, j_hi):
    """:math:`J_0` (module docstring): leg ``i``'s row :math:`(d_{ix}, d_{iy}, d_i \\cdot E
    s_i)`, :math:`d_i = w_i + s_i`, ``w`` the enclosure of :math:`p - B_i` and ``r`` of
    :math:`s_i` over the box and every perturbed robot ((n, 2) each); ``n = 2``: a
    platform-less robot (``r`` about zero, no :math:`\\varphi` column)."""
    for i in range(n):
        sx_lo, sx_hi, sy_lo, sy_hi = r_lo[i, 0], r_hi[i, 0], r_lo[i, 1], r_hi[i, 1]
        dx_lo, dx_hi = iadd(w_lo[i, 0], w_hi[i, 0], sx_lo, sx_hi)
        dy_lo, dy_hi = iadd(w_lo[i, 1], w_hi[i, 1], sy_lo, sy_hi)
        j_lo[i, 0], j_hi[i, 0] = dx_lo, dx_hi
        j_lo[i, 1], j_hi[i, 1] = dy_lo, dy_hi
        if n == 3:
            j_lo[i, 2], j_hi[i, 2] = isub(
                *imul(dy_lo, dy_hi, sx_lo, sx_hi), *imul(dx_lo, dx_hi, sy_lo, sy_hi)
            )


@kernel
def inverse(a, n):
    """The inverse of the 2 x 2 or 3 x 3 matrix ``a`` by cofactors (a float matrix: any
    :math:`C` is valid in :math:`K`), ``None`` when it is numerically singular."""
    out = np.empty((n, n))
    if n == 2:
        det = a[0, 0] * a[1, 1] - a[0, 1] * a[1, 0]
        scale = abs(a[0, 0] * a[1, 1]) + abs(a[0, 1] * a[1, 0])
        if not (abs(det) > 1e-12 * scale):
            return out, False
        out[0, 0], out[0, 1] = a[1, 1] / det, -a[0, 1] / det
        out[1, 0], out[1, 1] = -a[1, 0] / det, a[0, 0] / det
        return out, True
    scale = 0.0
    for i in range(3):
        for j in range(3):
            i1, i2 = (i + 1) % 3, (i + 2) % 3
            j1, j2 = (j + 1) % 3, (j + 2) % 3
            out[j, i] = a[i1, j1] * a[i2, j2] - a[i1, j2] * a[i2, j1]
            scale += abs(a[i1, j1] * a[i2, j2]) + abs(a[i1, j2] * a[i2, j1])
    det = a[0, 0] * out[0, 0] + a[0, 1] * out[1, 0] + a[0, 2] * out[2, 0]
    if not (abs(det) > 1e-12 * scale * (abs(a[0, 0]) + abs(a[0, 1]) + abs(a[0, 2]))):
        return out, False
    return out / det, True


@kernel
def remainder(w_lo, w_hi, r_lo, r_hi, d_lo, d_hi, n, out_lo, out_hi):
    """:math:`N_i(D) = d_i \\cdot (R(\\Delta\\varphi) - I - \\Delta\\varphi E)\\,s_i +
    \\tfrac12 |\\Delta d_i|^2` over the pose errors ``[d_lo, d_hi]`` (module docstring),
    with :math:`|\\cos t - 1| \\le t^2 / 2` and :math:`|\\sin t - t| \\le |t|^3 / 6`."""
    s_lo, s_hi, c_lo, a = 0.0, 0.0, 1.0, 0.0
    if n == 3:
        s_lo, s_hi, c_lo, _ = isincos(d_lo[2], d_hi[2])
        a = max(abs(d_lo[2]), abs(d_hi[2]))
    k_lo, k_hi = min(down(c_lo - 1.0), -up(0.5 * up(a * a))), 0.0  # cos - 1
    e = up(up(up(a * a) * a) / 6.0)  # |sin - t|
    for i in range(n):
        sx_lo, sx_hi, sy_lo, sy_hi = r_lo[i, 0], r_hi[i, 0], r_lo[i, 1], r_hi[i, 1]
        gx = isub(*imul(k_lo, k_hi, sx_lo, sx_hi), *imul(s_lo, s_hi, sy_lo, sy_hi))
        gy = iadd(*imul(s_lo, s_hi, sx_lo, sx_hi), *imul(k_lo, k_hi, sy_lo, sy_hi))
        qx = isub(*imul(k_lo, k_hi, sx_lo, sx_hi), *imul(-e, e, sy_lo, sy_hi))
        qy = iadd(*imul(-e, e, sx_lo, sx_hi), *imul(k_lo, k_hi, sy_lo, sy_hi))
        dx = iadd(w_lo[i, 0], w_hi[i, 0], sx_lo, sx_hi)
        dy = iadd(w_lo[i, 1], w_hi[i, 1], sy_lo, sy_hi)
        moved_x = iadd(d_lo[0], d_hi[0], *gx)
        moved_y = iadd(d_lo[1], d_hi[1], *gy)
        half = iadd(*isqr(*moved_x), *isqr(*moved_y))
        lo, hi = iadd(*imul(*dx, *qx), *imul(*dy, *qy))
        out_lo[i], out_hi[i] = iadd(lo, hi, down(0.5 * half[0]), up(0.5 * half[1]))


@kernel
def operator(c, m_lo, m_hi, w_lo, w_hi, r_lo, r_hi, linear, d_lo, d_hi, n, k_lo, k_hi):
    """``[k_lo, k_hi]`` = :math:`T(D)` (module docstring): ``m`` the interval matrix
    :math:`I - C J_0`, ``linear`` the bounds of :math:`|C|\\rho`."""
    n_lo = np.empty(n)
    n_hi = np.empty(n)
    remainder(w_lo, w_hi, r_lo, r_hi, d_lo, d_hi, n, n_lo, n_hi)
    for a in range(n):
        lo, hi = -linear[a], linear[a]
        for b in range(n):
            lo, hi = iadd(lo, hi, *imul(-c[a, b], -c[a, b], n_lo[b], n_hi[b]))
            lo, hi = iadd(lo, hi, *imul(m_lo[a, b], m_hi[a, b], d_lo[b], d_hi[b]))
        k_lo[a], k_hi[a] = lo, hi


@kernel
def krawczyk(w_lo, w_hi, r_lo, r_hi, rho, n, bound):
    """Whether the Krawczyk test (module docstring) proves a pose error enclosure for the
    box, writing the bounds of :math:`|\\Delta x|, |\\Delta y|` (cm) and, ``n = 3``,
    :math:`|\\Delta\\varphi|` (rad) to ``bound``; ``inf`` where not proved."""
    bound[:] = math.inf
    j_lo = np.empty((n, n))
    j_hi = np.empty((n, n))
    jacobian(w_lo, w_hi, r_lo, r_hi, n, j_lo, j_hi)
    if not (np.all(np.isfinite(j_lo)) and np.all(np.isfinite(j_hi))):
        return False
    c, regular = inverse(0.5 * (j_lo + j_hi), n)
    if not regular:
        return False
    linear = np.zeros(n)
    m_lo = np.empty((n, n))
    m_hi = np.empty((n, n))
    for a in range(n):
        for b in range(n):
            linear[a] = up(linear[a] + up(abs(c[a, b]) * rho[b]))
            lo, hi = (1.0, 1.0) if a == b else (0.0, 0.0)
            for k in range(n):
                lo, hi = isub(lo, hi, *imul(c[a, k], c[a, k], j_lo[k, b], j_hi[k, b]))
            m_lo[a, b], m_hi[a, b] = lo, hi
    d_lo = np.empty(n)
    d_hi = np.empty(n)
    for a in range(n):
        d_hi[a] = up(START * linear[a]) + FLOOR
        d_lo[a] = -d_hi[a]
    k_lo = np.empty(n)
    k_hi = np.empty(n)
    for _ in range(ATTEMPTS):
        operator(c, m_lo, m_hi, w_lo, w_hi, r_lo, r_hi, linear, d_lo, d_hi, n, k_lo, k_hi)
        if np.all(k_lo > d_lo) and np.all(k_hi < d_hi):
            for _ in range(TIGHTEN):
                d_lo[:] = np.maximum(d_lo, k_lo)
                d_hi[:] = np.minimum(d_hi, k_hi)
                operator(c, m_lo, m_hi, w_lo, w_hi, r_lo, r_hi, linear, d_lo, d_hi, n, k_lo, k_hi)
            for a in range(n):
                bound[a] = max(abs(max(d_lo[a], k_lo[a])), abs(min(d_hi[a], k_hi[a])))
            return True
        for a in range(n):
            width = up(k_hi[a] - k_lo[a])
            d_lo[a] = down(min(d_lo[a], k_lo[a]) - INFLATE * width) - FLOOR
            d_hi[a] = up(max(d_hi[a], k_hi[a]) + INFLATE * width) + FLOOR
            if not (d_hi[a] - d_lo[a] < WIDEST):
                return False
    return False


@kernel
def leg_scratch(n):
    """The legs' terms of one box, filled by a robot's leg function and read by
    :func:`settle`: ``w_lo, w_hi, r_lo, r_hi`` (n, 2) and :math:`\\rho` (n,). A leg
    that closes (``IN``) writes all of its row, so the arrays serve box after box."""
    return np.zeros((n, 2)), np.zeros((n, 2)), np.zeros((n, 2)), np.zeros((n, 2)), np.zeros(n)


@kernel
def block_rows(block, count):
    """The rows ``start, stop`` of block ``block`` of :data:`BLOCK_ROWS` among ``count``."""
    start = block * BLOCK_ROWS
    return start, min(count, start + BLOCK_ROWS)


@kernel
def settle(state, w_lo, w_hi, r_lo, r_hi, rho, n, verdict, bound, i):
    """Row ``i``'s verdict ``state`` and, where every leg closes (``IN``) and
    :func:`krawczyk` proves it, the bounds of its pose error in ``bound[i]``; ``inf``
    elsewhere."""
    verdict[i] = state
    bound[i, :] = math.inf
    if state == IN:
        krawczyk(w_lo, w_hi, r_lo, r_hi, rho, n, bound[i])

"""Certified enclosures of the condition number κ of a parallel robot's Jacobian over a box.

A robot's velocity equations read :math:`A\\,t = B\\,\\dot q` with :math:`t` the platform
twist :math:`(\\dot x, \\dot y, L\\dot\\varphi)` (or :math:`(\\dot x, \\dot y)` for the
five-bar), :math:`\\dot q` the actuated joint rates and :math:`B = \\mathrm{diag}(b_i)`; the
Jacobian is :math:`J = A^{-1} B` and its inverse :math:`M = J^{-1} = B^{-1} A` has rows
:math:`a_i / b_i`. Since :math:`\\kappa(J) = \\kappa(M) = \\sigma_{max}(M) / \\sigma_{min}(M)`, no matrix is
inverted: a robot's kernel encloses each :math:`a_i` and :math:`b_i` over an (x, y) box (its
points in the working mode's workspace), :func:`set_row` divides them (a :math:`b_i`
enclosure holding 0, a type I singularity, leaves the row unbounded) and
:func:`kappa_bounds` encloses κ.

**Singular-value bounds** (:func:`kappa_bounds`): with :math:`M \\in [M_c - R, M_c + R]`
entrywise, Weyl's inequality for singular values gives :math:`|\\sigma_k(M) -
\\sigma_k(M_c)| \\le \\|M - M_c\\|_2 \\le \\|R\\|_2 \\le s_R = \\min(\\|R\\|_F,
\\sqrt{\\|R\\|_1 \\|R\\|_\\infty})`. The midpoint's singular values are computed in
floating point (one-sided Jacobi, :func:`extreme_singular_values`, backward stable: exact for a matrix within :math:`c\\,n\\,u\\,
\\|M_c\\|` of :math:`M_c`), so the slack :math:`s = s_R +` ``EIG_RELATIVE``
:math:`\\|M_c\\|_F` covers that error too. Then

.. math:: \\frac{\\sigma_{max}(M_c) - s}{\\sigma_{min}(M_c) + s} \\le \\kappa \\le
          \\frac{\\sigma_{max}(M_c) + s}{\\sigma_{min}(M_c) - s}

(upper :math:`\\infty` when :math:`\\sigma_{min}(M_c) \\le s`: the box may hold a type II
singularity). Near a type I singularity (:math:`b_i \\to 0`) :math:`M` is unbounded,
but :math:`\\sigma_{max} \\ge \\max_i |M_i|` and :math:`\\sigma_{min} \\le \\min_i |M_i|`
(a row's norm is :math:`|M^T e_i|`) bound κ below by the ratio of the row norms
(:func:`set_norm`). The bounds tighten linearly with the width of the :math:`M` enclosure, so
bisection converges to the point value.
"""

import math

import numpy as np

from ._jit import kernel
from .interval import down, iadd, imul, isub, up

#: Relative slack on the midpoint matrix's computed eigenvalues (times its Frobenius norm).
EIG_RELATIVE = 1e-12

#: Verdicts of a box in the working mode: some leg cannot close within its limits at any
#: point (``OUT``), every leg closes within them at every point (``IN``), neither proved.
OUT = 0
UNSURE = 1
IN = 2


@kernel
def idiv(alo, ahi, blo, bhi):
    """:math:`X / Y`; unbounded when :math:`Y` may hold 0."""
    if blo <= 0.0 <= bhi:
        return -math.inf, math.inf
    q1 = alo / blo
    q2 = alo / bhi
    q3 = ahi / blo
    q4 = ahi / bhi
    return down(min(min(q1, q2), min(q3, q4))), up(max(max(q1, q2), max(q3, q4)))


@kernel
def set_row(m_lo, m_hi, i, k, a_lo, a_hi, b_lo, b_hi):
    """Entry ``(i, k)`` of :math:`M = B^{-1} A`: the enclosure of :math:`a_{ik} / b_i`."""
    lo, hi = idiv(a_lo, a_hi, b_lo, b_hi)
    m_lo[i, k] = lo
    m_hi[i, k] = hi


@kernel
def set_norm(norms, i, sq_lo, sq_hi, b_lo, b_hi):
    """Bounds of row ``i``'s 2-norm :math:`|a_i| / |b_i|` from an enclosure of
    :math:`|a_i|^2` and of :math:`b_i` (upper ``inf`` when :math:`b_i` may vanish)."""
    big = max(abs(b_lo), abs(b_hi))
    small = 0.0 if b_lo <= 0.0 <= b_hi else min(abs(b_lo), abs(b_hi))
    norms[i, 0] = down(down(math.sqrt(max(sq_lo, 0.0))) / big) if big > 0.0 else math.inf
    norms[i, 1] = up(up(math.sqrt(sq_hi)) / small) if small > 0.0 else math.inf


@kernel
def combine(state, leg_verdict):
    """The box's verdict after one more leg's (``OUT`` wins, then ``UNSURE``)."""
    if state == OUT or leg_verdict == OUT:
        return OUT
    if state == UNSURE or leg_verdict == UNSURE:
        return UNSURE
    return IN


@kernel
def meet(a_lo, a_hi, b_lo, b_hi):
    """:math:`X \\cap Y` of two enclosures of one quantity."""
    return max(a_lo, b_lo), min(a_hi, b_hi)


@kernel
def extreme_singular_values(a, n):
    """``(sigma_max, sigma_min)`` of the ``n`` x ``n`` matrix ``a`` (overwritten) by
    one-sided Jacobi (Hestenes): plane rotations orthogonalise its columns pairwise until
    every pair's cosine is below ``1e-15``; the singular values are the column norms
    (backward stable, with high relative accuracy)."""
    for _ in range(64):
        worst = 0.0
        for p in range(n - 1):
            for q in range(p + 1, n):
                alpha = 0.0
                beta = 0.0
                gamma = 0.0
                for i in range(n):
                    alpha += a[i, p] * a[i, p]
                    beta += a[i, q] * a[i, q]
                    gamma += a[i, p] * a[i, q]
                if gamma == 0.0 or alpha == 0.0 or beta == 0.0:
                    continue
                worst = max(worst, abs(gamma) / math.sqrt(alpha * beta))
                zeta = (beta - alpha) / (2.0 * gamma)
                t = math.copysign(1.0, zeta) / (abs(zeta) + math.sqrt(1.0 + zeta * zeta))
                c = 1.0 / math.sqrt(1.0 + t * t)
                s = c * t
                for i in range(n):
                    ap = a[i, p]
                    aq = a[i, q]
                    a[i, p] = c * ap - s * aq
                    a[i, q] = s * ap + c * aq
        if worst <= 1e-15:
            break
    sigma_max = 0.0
    sigma_min = math.inf
    for j in range(n):
        norm = 0.0
        for i in range(n):
            norm += a[i, j] * a[i, j]
        sigma_max = max(sigma_max, math.sqrt(norm))
        sigma_min = min(sigma_min, math.sqrt(norm))
    return sigma_max, sigma_min


@kernel
def slope_term(n_lo, n_hi, da, db, b_lo, b_hi, d):
    """:math:`\\partial m(X)\\,[-d, d]` for the entry :math:`m = a / b` (natural
    enclosure ``n``) along one direction: :math:`\\partial m = (\\partial a - m\\,\\partial
    b) / b`, ``da``, ``db`` (lo, hi) enclosures of :math:`\\partial a`, :math:`\\partial b`."""
    g_lo, g_hi = idiv(*isub(*da, *imul(n_lo, n_hi, *db)), b_lo, b_hi)
    return imul(g_lo, g_hi, -d, d)


@kernel
def mean_value(m_lo, m_hi, row, k, c_lo, c_hi, b_lo, b_hi, da_x, da_y, db_x, db_y, dx, dy):
    """Meet entry ``(row, k)`` of :math:`M` (natural: ``m_lo, m_hi``) with its mean-value
    form :math:`m(c) + \\partial_x m(X)\\,(X - c_x) + \\partial_y m(X)\\,(Y - c_y)`,
    :math:`\\partial m = (\\partial a - m\\,\\partial b) / b`; ``c`` the entry at the
    centre, ``dx``, ``dy`` bounds of :math:`|X - c_x|`, :math:`|Y - c_y|`."""
    n_lo = m_lo[row, k]
    n_hi = m_hi[row, k]
    v_lo, v_hi = iadd(
        *slope_term(n_lo, n_hi, da_x, db_x, b_lo, b_hi, dx),
        *slope_term(n_lo, n_hi, da_y, db_y, b_lo, b_hi, dy),
    )
    lo, hi = meet(n_lo, n_hi, *iadd(c_lo, c_hi, v_lo, v_hi))
    m_lo[row, k] = lo
    m_hi[row, k] = hi


@kernel
def kappa_bounds(m_lo, m_hi, n, norms):
    """``(kappa_lo, kappa_hi)`` enclosing :math:`\\kappa(M)` for every :math:`M` in the
    ``n`` x ``n`` interval matrix ``[m_lo, m_hi]`` whose row norms lie in ``norms`` (n, 2)
    (module docstring); ``kappa_hi = inf`` when an entry is unbounded."""
    rows_lo = 1.0  # sigma_max >= the largest row norm, sigma_min <= the smallest
    smallest = math.inf
    largest = 0.0
    for i in range(n):
        smallest = min(smallest, norms[i, 1])
        largest = max(largest, norms[i, 0])
    if smallest < math.inf and largest < math.inf:
        rows_lo = max(1.0, down(largest / smallest))
    elif largest == math.inf:
        rows_lo = math.inf
    mid = np.empty((n, n))
    col = np.zeros(n)
    row = np.zeros(n)
    frobenius = 0.0
    for i in range(n):
        for j in range(n):
            lo = m_lo[i, j]
            hi = m_hi[i, j]
            if not (math.isfinite(lo) and math.isfinite(hi)):
                return rows_lo, math.inf
            c = 0.5 * (lo + hi)
            d = up(max(hi - c, c - lo))
            mid[i, j] = c
            row[i] = up(row[i] + d)
            col[j] = up(col[j] + d)
            frobenius = up(frobenius + up(d * d))
    spread = up(min(math.sqrt(frobenius), math.sqrt(up(row.max() * col.max()))))
    norm = 0.0
    for i in range(n):
        for j in range(n):
            norm += mid[i, j] * mid[i, j]
    sigma_max, sigma_min = extreme_singular_values(mid, n)
    slack = up(up(spread + EIG_RELATIVE * math.sqrt(norm)) + 5e-324)
    kappa_hi = math.inf
    low = down(sigma_min - slack)
    if low > 0.0:
        kappa_hi = up(up(up(sigma_max + slack) / low))
    kappa_lo = max(rows_lo, down(down(down(sigma_max - slack) / up(sigma_min + slack))))
    return kappa_lo, kappa_hi

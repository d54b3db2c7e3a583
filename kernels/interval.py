"""Rigorous interval arithmetic on ``(lo, hi)`` float64 pairs, compiled with Numba.

An interval :math:`X = [\\underline{x}, \\overline{x}]` is passed as two floats and every
operation returns a ``(lo, hi)`` tuple. Results are widened outward by at least one ulp
(:func:`down` / :func:`up`, at least as far as ``np.nextafter``; applied twice for
``sin``/``cos``/``sqrt``, whose libm results are faithful to within one ulp), so that the
enclosure property

.. math:: x \\in X,\\; y \\in Y \\;\\Rightarrow\\; x \\circ y \\in X \\circ Y

holds for the real result even though every float operation rounds to nearest
(Moore, Kearfott & Cloud 2009, ch. 3; paper B, section 3). ``sin`` and ``cos`` take the
extrema inside the interval into account; the test for an interior extremum is widened
by a few ulps so that it errs towards the (always valid) answer ``±1``.

All functions are scalar and allocation free, meant to be called from other kernels.

Domain: bounded, non-empty intervals, ``lo <= hi`` with both bounds finite floats (every
interval the workspace kernels form). On that domain every result holds the exact real
result and is itself a non-empty set of reals: ``lo <= hi``, ``lo < +inf`` and
``hi > -inf``. A bound whose value overflows is rounded outward past the largest float
:math:`M` (``hi = +inf``, ``lo = -inf``); a lower bound that overflows upwards becomes
:math:`M` (not ``+inf``, which would leave an interval holding no real number), an upper
bound that overflows downwards :math:`-M`; so ``iadd(M, M, M, M) = (M, inf)`` and
``isqr(1.4e154, 1.5e154) = (M, inf)``. Inputs outside the domain are not checked: an empty
input (``lo > hi``) gives an unspecified, possibly non-empty result, and an unbounded input
may give NaN bounds (``inf - inf``, ``0 * inf``) or results that are not enclosures.

Only what the workspace kernels use is here: sine and cosine come together, of an interval
(:func:`isincos`, :func:`isincos_ends`) or of a point (:func:`psincos`).
"""

import math

from ._jit import kernel

_TWO_PI = 2.0 * math.pi


#: 2**-52: |v| * _REL >= ulp(v) for every normal v; _TINY = the smallest subnormal.
_REL = 2.220446049250313e-16
_TINY = 5e-324
#: The largest finite float M.
_MAX = 1.7976931348623157e308


@kernel
def down(value):
    """A float below ``value``: at most ``np.nextafter(value, -inf)`` (one or two ulps down);
    ``-inf`` stays, ``+inf`` (an overflowed lower bound) becomes the largest float.

    :math:`v - (|v| 2^{-52} + 2^{-1074})` rounded to nearest: :math:`|v| 2^{-52} \\ge
    \\mathrm{ulp}(v)`, so the result is a float strictly below ``v``. Two multiply-adds
    instead of a libm ``nextafter`` call per bound make the kernels twice as fast. At
    ``-inf`` the same expression gives ``-inf - inf = -inf``: no branch needed.
    """
    if value > _MAX:  # +inf: a lower bound that overflowed; the real value is >= M
        return _MAX
    return value - (abs(value) * _REL + _TINY)


@kernel
def up(value):
    """A float above ``value``: at least ``np.nextafter(value, inf)``; ``+inf`` stays
    (``inf + inf``), ``-inf`` (an overflowed upper bound) becomes minus the largest float
    (see :func:`down`)."""
    if value < -_MAX:  # -inf: an upper bound that overflowed; the real value is <= -M
        return -_MAX
    return value + (abs(value) * _REL + _TINY)


@kernel
def iadd(alo, ahi, blo, bhi):
    """:math:`X + Y = [\\underline{x}+\\underline{y}, \\overline{x}+\\overline{y}]`."""
    return down(alo + blo), up(ahi + bhi)


@kernel
def isub(alo, ahi, blo, bhi):
    """:math:`X - Y = [\\underline{x}-\\overline{y}, \\overline{x}-\\underline{y}]`."""
    return down(alo - bhi), up(ahi - blo)


@kernel
def iadd_scalar(alo, ahi, c):
    """:math:`X + c` for a float ``c`` (exact as a real number)."""
    return down(alo + c), up(ahi + c)


@kernel
def iscale(alo, ahi, c):
    """:math:`c X` for a float ``c``."""
    if c >= 0.0:
        return down(c * alo), up(c * ahi)
    return down(c * ahi), up(c * alo)


@kernel
def imul(alo, ahi, blo, bhi):
    """:math:`X Y = [\\min, \\max]` of the four endpoint products."""
    p1 = alo * blo
    p2 = alo * bhi
    p3 = ahi * blo
    p4 = ahi * bhi
    lo = min(min(p1, p2), min(p3, p4))
    hi = max(max(p1, p2), max(p3, p4))
    return down(lo), up(hi)


@kernel
def isqr(alo, ahi):
    """:math:`X^2 = \\{x^2 : x \\in X\\}` (not ``X * X``: no dependency effect)."""
    if alo >= 0.0:
        return down(alo * alo), up(ahi * ahi)
    if ahi <= 0.0:
        return down(ahi * ahi), up(alo * alo)
    m = max(-alo, ahi)
    return 0.0, up(m * m)


@kernel
def isqrt(alo, ahi):
    """:math:`\\sqrt{X \\cap [0, \\infty)}` (the empty part of the domain is dropped)."""
    lo = 0.0 if alo <= 0.0 else max(0.0, down(down(math.sqrt(alo))))
    hi = 0.0 if ahi <= 0.0 else up(up(math.sqrt(ahi)))
    return lo, hi


@kernel
def widen(c, w):
    """The interval :math:`[c - w, c + w]` rounded out (exactly ``(c, c)`` when ``w`` is 0)."""
    if w == 0.0:
        return c, c
    return down(c - w), up(c + w)


@kernel
def grown_box(xlo, xhi, ylo, yhi, grow):
    """The box grown by ``grow`` on every side, rounded out (as it is when ``grow`` is 0)."""
    if grow == 0.0:
        return xlo, xhi, ylo, yhi
    return down(xlo - grow), up(xhi + grow), down(ylo - grow), up(yhi + grow)


@kernel
def _clamp_unit(lo, hi):
    return max(-1.0, down(down(lo))), min(1.0, up(up(hi)))


@kernel
def isincos(alo, ahi):
    """``(sin X, cos X)`` as ``(slo, shi, clo, chi)``, sharing one search for the extrema.

    The multiples :math:`j\\pi/2` that may lie in X are ``j = ceil((lo - s) 2/pi) ..
    floor((hi + s) 2/pi)`` with a slack ``s`` of a few ulps (errs towards including):
    ``j mod 4 = 0, 1, 2, 3`` are the maxima of cos, of sin, the minima of cos, of sin.
    """
    return isincos_ends(alo, ahi, math.sin(alo), math.sin(ahi), math.cos(alo), math.cos(ahi))


@kernel
def isincos_ends(alo, ahi, s1, s2, c1, c2):
    """:func:`isincos` given the libm values at the ends, ``s1 = sin(alo)``,
    ``s2 = sin(ahi)``, ``c1 = cos(alo)``, ``c2 = cos(ahi)``: the same result bit for bit,
    for callers that keep those values (a bisection computes each end once, at the split
    that makes it, for both halves)."""
    # a full turn holds every extremum; the test also keeps the multiples counted below
    # within int64 (a wider interval's would overflow), not only a shortcut
    if ahi - alo >= _TWO_PI:
        return -1.0, 1.0, -1.0, 1.0
    slo, shi = _clamp_unit(min(s1, s2), max(s1, s2))
    clo, chi = _clamp_unit(min(c1, c2), max(c1, c2))
    slack = 4.0 * (abs(alo) + abs(ahi) + 1.0) * 2.220446049250313e-16
    jlo = math.ceil((alo - slack) * (2.0 / math.pi) - 1e-15)
    jhi = math.floor((ahi + slack) * (2.0 / math.pi) + 1e-15)
    if jhi - jlo >= 3:
        return -1.0, 1.0, -1.0, 1.0
    for j in range(jlo, jhi + 1):
        quadrant = j % 4
        if quadrant == 0:
            chi = 1.0
        elif quadrant == 1:
            shi = 1.0
        elif quadrant == 2:
            clo = -1.0
        else:
            slo = -1.0
    return slo, shi, clo, chi


@kernel
def psincos(t):
    """``(sin t, cos t)`` of a float as enclosing intervals ``(slo, shi, clo, chi)``."""
    slo, shi = _clamp_unit(math.sin(t), math.sin(t))
    clo, chi = _clamp_unit(math.cos(t), math.cos(t))
    return slo, shi, clo, chi

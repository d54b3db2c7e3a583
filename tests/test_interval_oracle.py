"""The sine and cosine enclosures the certified workspaces use (``psincos``, ``isincos``,
``isincos_ends``) and the outward rounding under them, against an exact oracle.

The oracle is independent of the kernels: the range of :math:`\\sin` and :math:`\\cos` over
a float interval :math:`[a, b]` is the set of their values at :math:`a`, :math:`b` and at
every multiple :math:`j\\pi/2` inside (the only critical points), evaluated with mpmath at
300 bits (the multiples found with a 300-bit :math:`\\pi`, so that huge arguments are
reduced exactly). The intervals straddle every multiple of :math:`\\pi/2` in
:math:`[-4\\pi, 4\\pi]` and some huge ones, end on either side of each (the float nearest
the multiple and a few ulps off), are nearly :math:`2\\pi` wide, or are huge. Each result
must hold the exact range (outward rounding) and be tight: a few ulps wider than the exact
range at most, or exactly :math:`\\pm 1` where a multiple lies within the kernels' slack of
the interval (erring towards including an extremum is allowed, nothing else).
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from planar_tui.kernels import interval as iv

PREC_BITS = 300


def exact_ranges(a: float, b: float):
    """``(sin_lo, sin_hi, cos_lo, cos_hi)`` of the real interval ``[a, b]`` as mpf, and the
    multiples ``j`` of pi/2 in it (``None`` when it is at least 2 pi wide)."""
    with mpmath.workprec(PREC_BITS):
        lo, hi = mpmath.mpf(a), mpmath.mpf(b)
        if hi - lo >= 2 * mpmath.pi:
            return (-1, 1, -1, 1), None
        half_pi = mpmath.pi / 2
        multiples = range(int(mpmath.ceil(lo / half_pi)), int(mpmath.floor(hi / half_pi)) + 1)
        sines = [mpmath.sin(lo), mpmath.sin(hi)]
        cosines = [mpmath.cos(lo), mpmath.cos(hi)]
        for j in multiples:  # the extremum of sin or cos at j pi/2 (j mod 4: cos 1, sin 1, ...)
            (cosines, sines, cosines, sines)[j % 4].append(mpmath.mpf((1, 1, -1, -1)[j % 4]))
        return (min(sines), max(sines), min(cosines), max(cosines)), list(multiples)


def multiple_nearby(a: float, b: float, parity: int) -> bool:
    """Whether a multiple ``j pi/2`` with ``j % 2 == parity`` (odd: extrema of sin; even: of
    cos) lies within a generous slack of ``[a, b]`` (where ``±1`` is allowed)."""
    slack = 16.0 * (abs(a) + abs(b) + 1.0) * 2.0**-52
    _, multiples = exact_ranges(a - slack, b + slack)
    return multiples is None or any(j % 2 == parity for j in multiples)


def ulps(value) -> float:
    """The spacing of floats at ``value`` (at least the smallest subnormal)."""
    return math.ulp(float(value))


#: How far a bound may lie outside the exact range: libm's error (an ulp) and two outward
#: roundings of up to two ulps each, with room.
TIGHT_ULPS = 8


def check_sin_cos(result, a: float, b: float) -> None:
    """``result = (slo, shi, clo, chi)`` holds the exact ranges over ``[a, b]`` and is tight."""
    exact, _ = exact_ranges(a, b)
    names = ("sin lo", "sin hi", "cos lo", "cos hi")
    for index, (bound, truth) in enumerate(zip(result, exact, strict=True)):
        below = index % 2 == 0
        where = f"{names[index]} of [{a!r}, {b!r}]: {bound!r} vs {mpmath.nstr(truth, 20)}"
        assert -1.0 <= bound <= 1.0, where
        assert (bound <= truth) if below else (bound >= truth), "not an enclosure: " + where
        distance = abs(mpmath.mpf(bound) - truth)
        if distance <= TIGHT_ULPS * ulps(truth) + 1e-323:
            continue
        # wider than a few ulps: allowed only as an extremum the slack errs towards
        parity = 1 if index < 2 else 0
        assert bound == (-1.0 if below else 1.0), "not tight: " + where
        assert multiple_nearby(a, b, parity), "an extremum that is not near: " + where


def nearest_float_to_multiple(j: int) -> float:
    with mpmath.workprec(PREC_BITS):
        return float(j * mpmath.pi / 2)


def steps(value: float, n: int) -> float:
    """The float ``n`` floats above ``value`` (below it for negative ``n``)."""
    direction = math.inf if n > 0 else -math.inf
    for _ in range(abs(n)):
        value = float(np.nextafter(value, direction))
    return value


#: Every multiple of pi/2 in [-4 pi, 4 pi], and huge ones (2**20 and 10**12 quarter turns;
#: at 10**12 + 30 and + 85 the product (m - slack) * fl(2/pi) of the float m nearest the
#: multiple rounds above j, so only the slack keeps the extremum: found by a search over
#: 15 000 multiples at five scales, where the kernels missed none).
MULTIPLES = [*range(-8, 9), 2**20 + 1, -(2**20) - 2, 10**12 + 3, 10**12, 10**12 + 30, 10**12 + 85]


def straddling(j: int) -> list[tuple[float, float]]:
    """Intervals about ``m``, the float nearest ``j pi/2``: across it, ending at it or a few
    floats before it, starting at it or a few floats after it, from either side."""
    m = nearest_float_to_multiple(j)
    near = [steps(m, n) for n in (-3, -1, 0, 1, 3)]
    reach = [0.3, 1e-9 * max(1.0, abs(m))]
    cases = []
    for end in near:
        for width in reach:
            cases += [(end - width, end), (end, end + width)]
    cases += [(near[0], near[-1]), (near[1], near[3]), (m, m), (m - 1.2, m + 0.4)]
    return [(min(lo, hi), max(lo, hi)) for lo, hi in cases]


def multiple_id(j: int) -> str:
    return f"j={j}"


@pytest.mark.parametrize("j", MULTIPLES, ids=multiple_id)
def test_isincos_holds_the_exact_range_about_each_multiple_of_half_pi(j):
    for a, b in straddling(j):
        check_sin_cos(iv.isincos(a, b), a, b)


@pytest.mark.parametrize("j", MULTIPLES, ids=multiple_id)
def test_isincos_ends_is_isincos_given_the_libm_ends(j):
    """The bisection's entry point: bit for bit :func:`isincos` given ``sin``/``cos`` of the
    ends, so the same enclosure."""
    for a, b in straddling(j):
        ends = (math.sin(a), math.sin(b), math.cos(a), math.cos(b))
        result = iv.isincos_ends(a, b, *ends)
        assert result == iv.isincos(a, b)
        check_sin_cos(result, a, b)


@pytest.mark.parametrize("start", [-7.0, -math.pi, -1.0, 0.0, 0.4, 3.0, 1e6, -123456.789])
@pytest.mark.parametrize("short_by", [0.05, 1e-6, 1e-12, 0.0, -1e-9])
def test_isincos_of_intervals_near_a_full_turn_wide(start, short_by):
    """``2 pi - short_by`` wide: one extremum may be missing (short) or none (a full turn)."""
    a = start
    b = start + 2.0 * math.pi - short_by
    check_sin_cos(iv.isincos(a, b), a, b)


@pytest.mark.parametrize(
    "a, b",
    [
        (1e17, 1e17),
        (1e17, steps(1e17, 1)),  # 16 wide: more than a turn
        (-1e300, -1e300),
        (1e300, steps(1e300, 1)),
        (-1e300, 1e300),  # the width test keeps the multiples' count (an int64) in range
        (-1e20, 1e20),
        (1e19, 3e19),
        (2.0**60, 2.0**60),
        (0.0, 0.0),
        (-5e-324, 5e-324),
        (-1e-300, 1e-300),
        (1e-300, 2e-300),
    ],
)
def test_isincos_of_huge_and_tiny_arguments(a, b):
    check_sin_cos(iv.isincos(a, b), a, b)


def test_isincos_exact_extrema_of_known_intervals():
    """The interior extrema are exactly ±1; the other bounds the ends' values (the issue's
    mutants: sin([1.4, 1.7]) must reach 1, cos([-0.1, 0.1]) too)."""
    slo, shi, clo, chi = iv.isincos(1.4, 1.7)
    assert shi == 1.0 and clo < math.cos(1.7) and chi > math.cos(1.4) and chi < 0.2
    slo, shi, clo, chi = iv.isincos(-0.1, 0.1)
    assert chi == 1.0 and slo < -0.09 and shi < 0.1 and clo < math.cos(0.1)
    assert iv.isincos(3.0, 3.5)[2] == -1.0  # cos's minimum at pi
    assert iv.isincos(4.5, 4.8)[0] == -1.0  # sin's minimum at 3 pi/2
    assert iv.isincos(0.0, 7.0) == (-1.0, 1.0, -1.0, 1.0)
    assert iv.isincos(0.2, 1.3) == pytest.approx(
        (math.sin(0.2), math.sin(1.3), math.cos(1.3), math.cos(0.2)), abs=1e-15
    )


@pytest.mark.parametrize(
    "t",
    [
        0.0,
        1e-300,
        5e-324,
        0.1,
        1.0,
        -2.5,
        math.pi / 2,
        math.pi,
        3 * math.pi / 2,
        2 * math.pi,
        1e6 + 0.123,
        1e17,
        -1e300,
        *(nearest_float_to_multiple(j) for j in range(-8, 9)),
    ],
)
def test_psincos_holds_the_exact_value_of_a_point(t):
    """Outward rounding: the libm value alone, exact only by chance, would miss it."""
    slo, shi, clo, chi = iv.psincos(t)
    with mpmath.workprec(PREC_BITS):
        for lo, hi, truth in ((slo, shi, mpmath.sin(t)), (clo, chi, mpmath.cos(t))):
            assert -1.0 <= lo <= truth <= hi <= 1.0
            assert hi - lo <= 2 * TIGHT_ULPS * ulps(truth) + 1e-323
            if truth not in (-1, 0, 1):  # an inexact float result is strictly widened
                assert lo < truth < hi


def test_psincos_widens_a_rounded_value_but_stays_within_the_unit_interval():
    """sin(pi/2 as a float) rounds to exactly 1: the upper bound is 1, not above it."""
    slo, shi, clo, chi = iv.psincos(math.pi / 2)
    assert shi == 1.0 and slo < 1.0
    slo, shi, clo, chi = iv.psincos(math.pi)
    assert clo == -1.0 and chi > -1.0
    assert slo < math.sin(math.pi) < shi  # 1.22e-16: widened by about an ulp each way
    assert shi - slo < 1e-31


@pytest.mark.parametrize(
    "value", [1.0, 1.5, 1.9999999999999998, 2.0, 3.0, -1.0, -1.5, 1e-300, 1e300, 5e-324, 0.0]
)
def test_down_and_up_move_one_or_two_floats(value):
    """The outward rounding is strict and tight: one or two floats, never more."""
    assert steps(value, -2) <= iv.down(value) <= steps(value, -1)
    assert steps(value, 1) <= iv.up(value) <= steps(value, 2)


def products(x, y):
    return [p * q for p in x for q in y]


#: (function, its arguments, the exact (lo, hi) from the end points as mpf): 300-bit sums and
#: products of floats are exact.
ARITHMETIC = [
    (iv.iadd, (0.1, 0.2, 0.3, 0.7), lambda a, b, c, d: (a + c, b + d)),
    (iv.isub, (0.1, 0.2, 0.3, 0.7), lambda a, b, c, d: (a - d, b - c)),
    *(
        (
            iv.imul,
            args,
            lambda a, b, c, d: (min(products((a, b), (c, d))), max(products((a, b), (c, d)))),
        )
        for args in [
            (-0.3, 0.2, 0.7, 1.1),
            (-0.3, -0.2, -1.1, 0.7),
            (0.3, 0.5, -1.1, -0.7),
            (0.3, 0.5, 0.7, 1.1),
            (-0.5, -0.3, -1.1, -0.7),
            (-0.5, 0.3, -1.1, 0.7),
        ]
    ),
    (iv.iadd_scalar, (0.3, 0.7, 1.7), lambda a, b, c: (a + c, b + c)),
    (iv.iadd_scalar, (0.3, 0.7, -1.7), lambda a, b, c: (a + c, b + c)),
    *(
        (iv.iscale, (0.3, 0.7, c), lambda a, b, c: (min(a * c, b * c), max(a * c, b * c)))
        for c in (1.7, -1.7, 0.0, -0.0)
    ),
    *(
        (iv.isqr, x, lambda a, b: (0 if a < 0 < b else min(a * a, b * b), max(a * a, b * b)))
        for x in [(0.3, 0.7), (-0.7, -0.3), (-0.3, 0.7), (-0.7, 0.3), (0.0, 0.0)]
    ),
]


@pytest.mark.parametrize(
    "function, args, exact", ARITHMETIC, ids=lambda v: getattr(v, "__name__", None)
)
def test_arithmetic_is_enclosing_and_tight(function, args, exact):
    """Each bound is the exact bound of the real result (mpmath at 300 bits) rounded outward
    by one to three floats: enclosing, and no wider."""
    lo, hi = function(*args)
    with mpmath.workprec(PREC_BITS):
        true_lo, true_hi = exact(*(mpmath.mpf(v) for v in args))
    assert mpmath.mpf(lo) <= true_lo and true_hi <= mpmath.mpf(hi)
    assert lo >= steps(float(true_lo), -3) and hi <= steps(float(true_hi), 3)
    if function is iv.isqr and args[0] < 0.0 < args[1]:
        assert lo == 0.0  # the square of an interval across zero starts at zero exactly


@pytest.mark.parametrize(
    "x", [(0.3, 0.7), (2.0, 3.0), (-1.0, 2.0), (-2.0, 0.0), (0.0, 4.0), (0.0, 0.01), (1e-6, 0.05)]
)
def test_square_root_is_enclosing_and_tight(x):
    """Up to four floats a side (two outward roundings of a correctly rounded sqrt); the
    negative part of the domain is dropped."""
    lo, hi = iv.isqrt(*x)
    with mpmath.workprec(PREC_BITS):
        true_lo, true_hi = mpmath.sqrt(max(x[0], 0.0)), mpmath.sqrt(max(x[1], 0.0))
    assert mpmath.mpf(lo) <= true_lo and true_hi <= mpmath.mpf(hi)
    assert lo >= steps(float(true_lo), -4) and hi <= steps(float(true_hi), 4)
    assert lo >= 0.0 and (hi == 0.0) == (x[1] <= 0.0)


@settings(deadline=None, max_examples=300)
@given(
    st.floats(min_value=-50.0, max_value=50.0),
    st.floats(min_value=0.0, max_value=7.0),
)
@example(-1.0, 1.0 - 8.7e-303)
@example(1.5707963267948966, 0.0)
def test_isincos_holds_the_exact_range_of_random_intervals(a, width):
    b = a + width
    check_sin_cos(iv.isincos(a, b), a, b)

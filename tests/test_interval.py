"""Interval arithmetic kernels against mpmath.iv (an independent, rigorous oracle)."""

from __future__ import annotations

import math
import re
from pathlib import Path

import mpmath
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from planar_tui.kernels import interval as iv

mpmath.iv.prec = 200  # oracle far more precise than float64

finite = st.floats(min_value=-1e6, max_value=1e6, allow_nan=False, allow_infinity=False)


@st.composite
def intervals(draw, values=finite):
    a, b = draw(values), draw(values)
    return (min(a, b), max(a, b))


def contains(result, exact) -> bool:
    """``result`` (float pair) contains the mpmath interval ``exact``."""
    lo, hi = result
    return mpmath.mpf(lo) <= exact.a and exact.b <= mpmath.mpf(hi)


def mpi(pair):
    return mpmath.iv.mpf([pair[0], pair[1]])


BINARY = [
    (iv.iadd, lambda x, y: x + y),
    (iv.isub, lambda x, y: x - y),
    (iv.imul, lambda x, y: x * y),
]


@settings(deadline=None, max_examples=300)
@given(intervals(), intervals())
def test_binary_operations_enclose_the_exact_range(x, y):
    for op, exact in BINARY:
        assert contains(op(*x, *y), exact(mpi(x), mpi(y))), op.__name__


@settings(deadline=None, max_examples=300)
@given(intervals(), finite)
def test_scalar_operations_and_square_enclose(x, c):
    assert contains(iv.iadd_scalar(*x, c), mpi(x) + mpmath.mpf(c))
    assert contains(iv.iscale(*x, c), mpi(x) * mpmath.mpf(c))
    assert contains(iv.isqr(*x), mpi(x) ** 2)


@pytest.mark.slow
@settings(deadline=None, max_examples=300)
@given(intervals(st.floats(min_value=0.0, max_value=1e6)))
def test_sqrt_encloses(x):
    assert contains(iv.isqrt(*x), mpmath.iv.sqrt(mpi(x)))


def test_dependency_effect_of_the_papers_example():
    # paper B eq. (11): x - x^2 on [0, 1] by natural extension gives [-1, 1]
    lo, hi = iv.isub(0.0, 1.0, *iv.isqr(0.0, 1.0))
    assert lo <= -1.0 and hi >= 1.0 and lo > -1.0 - 1e-12 and hi < 1.0 + 1e-12


@pytest.mark.parametrize("value", [0.0, 1.0, -1.0, 1e-310, -5e-324, 1e300, 2.0**-1022])
def test_outward_rounding_moves_strictly(value):
    assert iv.down(value) < value < iv.up(value)


@settings(deadline=None, max_examples=1000)
@given(st.floats(min_value=-1e300, max_value=1e300))
def test_outward_rounding_is_at_least_one_ulp(value):
    """down/up go at least as far as np.nextafter (the arithmetic form is just faster)."""
    assert iv.down(value) <= np.nextafter(value, -np.inf)
    assert iv.up(value) >= np.nextafter(value, np.inf)
    assert iv.down(value) >= value - 4 * abs(value) * 2.0**-52 - 1e-323


# --- edges of the domain (issue 12, part 5) ------------------------------------------------

M = np.finfo(np.float64).max


def is_real_interval(result) -> bool:
    """A non-empty set of reals: no NaN, lo <= hi, lo below +inf and hi above -inf."""
    lo, hi = result
    return lo <= hi and lo < math.inf and hi > -math.inf


@pytest.mark.parametrize(
    "op, args, expected_lo",
    [
        (iv.iadd, (M, M, M, M), M),
        (iv.isqr, (1.4e154, 1.5e154), M),
        (iv.imul, (1e200, 2e200, 1e200, 3e200), M),
        (iv.isub, (M, M, -M, -M), M),
        (iv.iscale, (M, M, 2.0), M),
        (iv.iadd_scalar, (M, M, M), M),
    ],
)
def test_a_lower_bound_that_overflows_becomes_the_largest_float(op, args, expected_lo):
    """The issue's bug: a lower bound rounding to +inf stayed +inf, (inf, inf) holds no real."""
    lo, hi = op(*args)
    assert (lo, hi) == (expected_lo, math.inf)


@pytest.mark.parametrize(
    "op, args",
    [
        (iv.iadd, (-M, -M, -M, -M)),
        (iv.isub, (-M, -M, M, M)),
        (iv.imul, (-2e200, -1e200, 1e200, 3e200)),
        (iv.iscale, (M, M, -2.0)),
    ],
)
def test_an_upper_bound_that_overflows_downwards_becomes_minus_the_largest_float(op, args):
    assert op(*args) == (-math.inf, -M)


def test_down_and_up_at_the_infinities():
    assert iv.down(math.inf) == M and iv.down(-math.inf) == -math.inf
    assert iv.up(-math.inf) == -M and iv.up(math.inf) == math.inf
    assert iv.down(M) < M and iv.up(-M) > -M


#: Every float magnitude, the huge ones (products and squares overflow) and the tiny
#: (subnormal results) over-represented.
any_finite = st.one_of(
    st.floats(allow_nan=False, allow_infinity=False),
    st.floats(min_value=1e150, max_value=M).flatmap(lambda v: st.sampled_from([v, -v])),
    st.floats(min_value=-1e-300, max_value=1e-300),
    st.sampled_from([M, -M, 1.4e154, 1.5e154, -1.4e154, 5e-324, -5e-324, 0.0, -0.0]),
)


@pytest.mark.slow
@settings(deadline=None, max_examples=400)
@given(intervals(any_finite), intervals(any_finite), any_finite)
def test_operations_over_every_float_enclose_and_stay_real(x, y, c):
    """Against mpmath's interval arithmetic over the whole float range, overflow included."""
    for op, exact in BINARY:
        result = op(*x, *y)
        assert is_real_interval(result) and contains(result, exact(mpi(x), mpi(y))), op.__name__
    for result, exact in (
        (iv.iadd_scalar(*x, c), mpi(x) + mpmath.mpf(c)),
        (iv.iscale(*x, c), mpi(x) * mpmath.mpf(c)),
        (iv.isqr(*x), mpi(x) ** 2),
    ):
        assert is_real_interval(result) and contains(result, exact)
    if x[1] >= 0.0:
        result = iv.isqrt(*x)
        assert is_real_interval(result)
        assert contains(result, mpmath.iv.sqrt(mpmath.iv.mpf([max(x[0], 0.0), x[1]])))


# --- ITF1788 (IEEE 1788 test suite), bounded cases ------------------------------------------

ITF1788 = Path(__file__).parent / "data" / "itf1788" / "elem-subset.itl"
ITF_OPS = {"add": iv.iadd, "sub": iv.isub, "mul": iv.imul, "sqr": iv.isqr, "sqrt": iv.isqrt}


def _itf_number(text: str) -> float:
    text = text.strip()
    if text.lower() in ("inf", "-inf"):
        return float(text)
    return float.fromhex(text) if "0x" in text.lower() else float(text)


def _itf_interval(text: str) -> tuple[float, float]:
    text = text.strip()
    if text == "[entire]":
        return (-math.inf, math.inf)
    lo, hi = text.strip("[]").split(",")
    return (_itf_number(lo), _itf_number(hi))


def itf_cases():
    """``(op, inputs, expected)`` for every ``op [a,b] ... = [c,d];`` line of the subset."""
    cases = []
    pattern = re.compile(r"^\s*(\w+)\s+((?:\[[^\]]*\]\s*)+)=\s*(\[[^\]]*\])\s*;")
    for line in ITF1788.read_text(encoding="utf-8").splitlines():
        match = pattern.match(line)
        if match:
            inputs = [_itf_interval(t + "]") for t in match.group(2).split("]") if t.strip()]
            cases.append((match.group(1), inputs, _itf_interval(match.group(3))))
    return cases


def _ulps_below(value: float, n: int) -> float:
    """``n`` floats below ``value`` (below -M: -inf)."""
    with np.errstate(over="ignore"):
        for _ in range(n):
            value = np.nextafter(value, -np.inf)
    return value


def test_itf1788_subset_is_read_whole():
    cases = itf_cases()
    assert len(cases) == 71  # every case line of the file
    assert {op for op, _, _ in cases} == set(ITF_OPS)


@pytest.mark.parametrize("case", itf_cases(), ids=lambda c: c[0])
def test_itf1788_bounded_cases_are_enclosed_within_a_few_ulps(case):
    """Each result holds the suite's tightest enclosure and is at most 6 ulps wider per
    bound (the outward rounding moves one to four)."""
    op, inputs, (lo, hi) = case
    got_lo, got_hi = ITF_OPS[op](*(bound for pair in inputs for bound in pair))
    assert is_real_interval((got_lo, got_hi))
    assert got_lo <= lo and hi <= got_hi
    assert got_lo >= _ulps_below(lo, 6) and -got_hi >= _ulps_below(-hi, 6)

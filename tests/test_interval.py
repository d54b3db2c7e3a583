"""Interval arithmetic kernels against mpmath.iv (an independent, rigorous oracle)."""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from planar_tui.kernels import interval as iv

mpmath.iv.prec = 200  # oracle far more precise than float64

finite = st.floats(min_value=-1e6, max_value=1e6, allow_nan=False, allow_infinity=False)
angles = st.floats(min_value=-50.0, max_value=50.0, allow_nan=False)


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


@settings(deadline=None, max_examples=300)
@given(intervals(st.floats(min_value=0.0, max_value=1e6)))
def test_sqrt_encloses(x):
    assert contains(iv.isqrt(*x), mpmath.iv.sqrt(mpi(x)))


@settings(deadline=None, max_examples=500)
@given(intervals(angles))
def test_sin_cos_enclose_including_interior_extrema(x):
    assert contains(iv.isin(*x), mpmath.iv.sin(mpi(x)))
    assert contains(iv.icos(*x), mpmath.iv.cos(mpi(x)))


@settings(deadline=None, max_examples=300)
@given(intervals(angles), st.floats(min_value=0.0, max_value=1.0))
def test_sin_cos_contain_point_values_and_are_tight(x, t):
    point = x[0] + t * (x[1] - x[0])
    slo, shi = iv.isin(*x)
    clo, chi = iv.icos(*x)
    assert slo <= math.sin(point) <= shi
    assert clo <= math.cos(point) <= chi
    # no more than a few ulps wider than the true range (not a blanket [-1, 1])
    exact = mpmath.iv.sin(mpi(x))
    assert float(exact.a) - slo <= 1e-15 + 4e-16 * abs(slo)
    assert shi - float(exact.b) <= 1e-15 + 4e-16 * abs(shi)


def test_sin_cos_known_values():
    lo, hi = iv.isin(0.0, math.pi)  # max 1 at pi/2 inside, min 0 at the ends
    assert hi == 1.0 and -1e-15 < lo <= 0.0
    lo, hi = iv.icos(-0.1, 0.1)
    assert hi == 1.0 and lo < math.cos(0.1)
    assert iv.icos(0.0, 7.0) == (-1.0, 1.0)


def test_dependency_effect_of_the_papers_example():
    # paper B eq. (11): x - x^2 on [0, 1] by natural extension gives [-1, 1]
    lo, hi = iv.isub(0.0, 1.0, *iv.isqr(0.0, 1.0))
    assert lo <= -1.0 and hi >= 1.0 and lo > -1.0 - 1e-12 and hi < 1.0 + 1e-12


def test_hull_intersection_width_midpoint():
    assert iv.ihull(0.0, 1.0, 2.0, 3.0) == (0.0, 3.0)
    lo, hi = iv.iintersect(0.0, 1.0, 2.0, 3.0)
    assert lo > hi  # empty
    assert iv.iintersect(0.0, 2.0, 1.0, 3.0) == (1.0, 2.0)
    assert iv.iwidth(1.0, 3.5) >= 2.5
    assert iv.imid(1.0, 3.0) == 2.0
    assert iv.icontains(1.0, 3.0, 3.0) and not iv.icontains(1.0, 3.0, 3.0000001)


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

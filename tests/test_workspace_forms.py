"""Interval forms of the 3-RRR leg constraints, the exact leg test and the union area."""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from planar_tui.kernels import workspace3rrr
from planar_tui.kernels.workspace_arc import (
    BOUNDARY,
    INSIDE,
    OUTSIDE,
    arc_distance_range,
    classify_box,
    limits_array,
)
from planar_tui.kernels.workspace_union import union_area

from planar_tui.workspace.rrr.robot import Robot3RRR

PAPER = Robot3RRR()  # a = 120, b = 40, l1 = l2 = 30 cm (paper B, Table 2)
FORMS = (
    workspace3rrr.NATURAL,
    workspace3rrr.MEAN_VALUE,
    workspace3rrr.SLOPE,
    workspace3rrr.NATURAL_EXPANDED,
)


def params(phi_rad: float) -> np.ndarray:
    return workspace3rrr.parameter_vector(
        30.0, 30.0, PAPER.leg_offsets_cm(phi_rad), 120.0, 40.0, phi_rad
    )


def exact_f(leg: int, x: float, y: float, theta: float, phi: float) -> mpmath.mpf:
    """|C_i - B_i|^2 - l2^2 from eqs. (17)-(20) in 50-digit arithmetic (independent code)."""
    mpmath.mp.dps = 50
    a, b, l1, l2 = (mpmath.mpf(v) for v in (120, 40, 30, 30))
    x, y, th, ph = (mpmath.mpf(v) for v in (x, y, theta, phi))
    base = [(0, 0), (a, 0), (a / 2, a * mpmath.sqrt(3) / 2)][leg]
    c, s = mpmath.cos(ph), mpmath.sin(ph)
    platform = [
        (x, y),
        (x + b * c, y + b * s),
        (x + b * c / 2 - b * s, y + b * s / 2 + b * c),
    ][leg]
    bx = base[0] + l1 * mpmath.cos(th)
    by = base[1] + l1 * mpmath.sin(th)
    return (platform[0] - bx) ** 2 + (platform[1] - by) ** 2 - l2**2


@st.composite
def box_and_point(draw):
    x0 = draw(st.floats(0.0, 100.0))
    y0 = draw(st.floats(-10.0, 90.0))
    t0 = draw(st.floats(-7.0, 7.0))
    wx = draw(st.floats(1e-6, 20.0))
    wy = draw(st.floats(1e-6, 20.0))
    wt = draw(st.floats(1e-6, 3.0))
    u = draw(st.tuples(*(st.floats(0.0, 1.0),) * 3))
    phi = draw(st.sampled_from([0.0, math.pi / 6, 1.0]))
    leg = draw(st.integers(0, 2))
    box = (x0, x0 + wx, y0, y0 + wy, t0, t0 + wt)
    point = (x0 + u[0] * wx, y0 + u[1] * wy, t0 + u[2] * wt)
    return leg, phi, box, point


@pytest.mark.slow
@settings(deadline=None, max_examples=300)
@given(box_and_point())
def test_every_form_encloses_the_exact_value_at_points_of_the_box(case):
    leg, phi, box, point = case
    p = params(phi)
    value = exact_f(leg, *point, phi)
    for form in FORMS:
        lo, hi = workspace3rrr.leg_enclosure(form, leg, *box, p)
        assert lo <= value <= hi, (form, lo, float(value), hi)


@settings(deadline=None, max_examples=100)
@given(box_and_point())
def test_expanded_eqs_22_23_equal_the_compact_form_at_points(case):
    leg, phi, _, (x, y, t) = case
    p = params(phi)
    lo, hi = workspace3rrr.natural_expanded(leg, x, x, y, y, t, t, p)
    value = float(exact_f(leg, x, y, t, phi))
    assert lo - 1e-9 * (1 + abs(value)) <= value <= hi + 1e-9 * (1 + abs(value))
    assert hi - lo < 1e-9 * (1e4 + abs(value))


# paper B eq. (24): f3 over x in [38, 38.25], y in [14.5, 14.75], theta3 in [260, 280] deg,
# phi = pi/6. The printed enclosures do not reproduce (see docs/workspace.md).
EXAMPLE = (38.0, 38.25, 14.5, 14.75, math.radians(260.0), math.radians(280.0))


def example_true_range():
    xs = np.linspace(EXAMPLE[0], EXAMPLE[1], 41)
    ys = np.linspace(EXAMPLE[2], EXAMPLE[3], 41)
    ts = np.linspace(EXAMPLE[4], EXAMPLE[5], 401)
    x, y, t = np.meshgrid(xs, ys, ts, indexing="ij")
    p = params(math.pi / 6)
    f = (x + p[6] - 30 * np.cos(t)) ** 2 + (y + p[7] - 30 * np.sin(t)) ** 2 - 900
    return f.min(), f.max()


def test_worked_example_eq_24():
    p = params(math.pi / 6)
    true_lo, true_hi = example_true_range()
    assert true_lo == pytest.approx(-306.0, abs=0.1) and true_hi == pytest.approx(225.5, abs=0.1)
    widths = {}
    for form in FORMS:
        lo, hi = workspace3rrr.leg_enclosure(form, 2, *EXAMPLE, p)
        assert lo <= true_lo and true_hi <= hi
        widths[form] = hi - lo
    # the expanded eq. (23) gives [-836.3, 712.7] (the paper prints [-787.4, 663.8])
    lo, hi = workspace3rrr.leg_enclosure(workspace3rrr.NATURAL_EXPANDED, 2, *EXAMPLE, p)
    assert lo == pytest.approx(-836.34, abs=0.01) and hi == pytest.approx(712.72, abs=0.01)
    # refinement narrows the paper's natural extension; slope is at most mean-value here
    assert widths[workspace3rrr.MEAN_VALUE] < widths[workspace3rrr.NATURAL_EXPANDED]
    assert widths[workspace3rrr.SLOPE] <= widths[workspace3rrr.MEAN_VALUE]


def test_mean_value_and_slope_overestimation_is_second_order():
    """Excess width over the true range shrinks ~4x when the box halves (ratio of 2 would
    be first order, the natural extension's behaviour)."""
    p = params(0.0)
    for form in (workspace3rrr.MEAN_VALUE, workspace3rrr.SLOPE):
        excess = []
        for w in (0.8, 0.4, 0.2):
            box = (40.0, 40.0 + w, 20.0, 20.0 + w, 1.0, 1.0 + w / 10)
            lo, hi = workspace3rrr.leg_enclosure(form, 0, *box, p)
            x, y, t = np.meshgrid(*(np.linspace(box[2 * i], box[2 * i + 1], 41) for i in range(3)))
            f = (x + p[2] - 30 * np.cos(t)) ** 2 + (y + p[3] - 30 * np.sin(t)) ** 2 - 900
            excess.append((hi - lo) - (f.max() - f.min()))
        assert 3.5 < excess[0] / excess[1] < 4.5 and 3.5 < excess[1] / excess[2] < 4.5, excess


# -- exact leg-wise test --------------------------------------------------------------------


@settings(deadline=None, max_examples=200)
@given(
    st.floats(-80.0, 80.0),
    st.floats(-80.0, 80.0),
    st.floats(-4.0, 4.0),
    st.floats(0.05, 6.0),
)
def test_arc_distance_range_matches_dense_sampling(px, py, tlo, span):
    dmin, dmax = arc_distance_range(px, py, 30.0, tlo, tlo + span)
    t = np.linspace(tlo, tlo + span, 20001)
    d = np.hypot(px - 30 * np.cos(t), py - 30 * np.sin(t))
    step = 30 * span / 20000
    assert d.min() - step <= dmin <= d.min() + 1e-9
    assert d.max() - 1e-9 <= dmax <= d.max() + step


def test_classify_box_agrees_with_points_inside():
    p = params(0.0)
    limits = limits_array(np.radians([[20, 70], [110, 160], [245, 295]]))
    rng = np.random.default_rng(7)
    seen = set()
    for _ in range(400):
        x0, y0 = rng.uniform(20, 60), rng.uniform(0, 30)
        w = rng.uniform(0.05, 3.0)
        label = classify_box(x0, x0 + w, y0, y0 + w, p, limits)
        seen.add(label)
        xs, ys = rng.uniform(x0, x0 + w, 30), rng.uniform(y0, y0 + w, 30)
        ok = []
        for x, y in zip(xs, ys, strict=True):
            feasible = True
            for leg in range(3):
                dmin, dmax = arc_distance_range(
                    x + p[2 + 2 * leg], y + p[3 + 2 * leg], 30.0, *limits[leg]
                )
                feasible &= dmin <= 30.0 <= dmax
            ok.append(feasible)
        if label == INSIDE:
            assert all(ok)
        if label == OUTSIDE:
            assert not any(ok)
    assert seen == {INSIDE, OUTSIDE, BOUNDARY}


# -- union area ------------------------------------------------------------------------------


@settings(deadline=None, max_examples=100)
@given(st.lists(st.tuples(*(st.integers(0, 30),) * 4), min_size=1, max_size=40))
def test_union_area_equals_brute_force_rasterisation(rects):
    grid = np.zeros((30, 30), dtype=bool)
    rows = []
    for a, b, c, d in rects:
        x0, x1, y0, y1 = min(a, b), max(a, b), min(c, d), max(c, d)
        grid[x0:x1, y0:y1] = True
        rows.append((x0 * 0.5, x1 * 0.5, y0 * 0.5, y1 * 0.5))
    assert union_area(np.array(rows, dtype=np.float64)) == pytest.approx(grid.sum() * 0.25)


def test_union_area_of_duplicates_and_nested_boxes():
    boxes = np.array([[0, 1, 0, 1], [0, 1, 0, 1], [0.25, 0.5, 0.25, 0.5], [2, 3, 0, 2.0]])
    assert union_area(boxes) == pytest.approx(3.0)
    assert union_area(np.zeros((0, 4))) == 0.0


def test_unique_rows_equals_numpy_unique():
    from planar_tui.workspace.paving.boxes import unique_rows

    rng = np.random.default_rng(5)
    boxes = rng.integers(0, 3, (500, 4)).astype(np.float64) * 0.5
    np.testing.assert_array_equal(unique_rows(boxes), np.unique(boxes, axis=0))
    assert unique_rows(np.zeros((0, 4))).shape == (0, 4)


def test_unique_rows_of_grid_cells_equals_numpy_unique():
    """The grid path (:func:`planar_tui.workspace.paving.boxes._unique_grid_cells`): cells of one
    grid in any order and repeated, as a bisection keeps them; and the near-grids it must
    hand to the sort (rows that round to one cell, mixed sizes, too many cells)."""
    from planar_tui.workspace.paving import boxes as module

    rng = np.random.default_rng(7)
    width, height = 120 / 1024, 120 / 512
    i = rng.integers(0, 40, 3000)
    j = rng.integers(0, 25, 3000)
    x_lo, y_lo = 13.0 + i * width, -4.0 + j * height
    cells = np.column_stack([x_lo, x_lo + width, y_lo, y_lo + height])
    assert module._unique_grid_cells(cells) is not None  # the grid path is taken
    np.testing.assert_array_equal(module.unique_rows(cells), np.unique(cells, axis=0))
    near = cells.copy()
    near[5, 0:2] += 2.0**-30  # same width, off the grid: rounds to its old cell
    near = np.vstack([near, cells[5]])  # ... which another row holds
    assert np.all(near[:, 1] - near[:, 0] == width)  # so only the cell check can refuse
    assert module._unique_grid_cells(near) is None
    np.testing.assert_array_equal(module.unique_rows(near), np.unique(near, axis=0))
    mixed = np.vstack([cells[:10], [[0.0, 2 * width, 0.0, height]]])
    assert module._unique_grid_cells(mixed) is None
    np.testing.assert_array_equal(module.unique_rows(mixed), np.unique(mixed, axis=0))
    far = np.array([[0.0, 1e-3, 0.0, 1e-3], [100.0, 100.001, 100.0, 100.001]])
    assert module._unique_grid_cells(far) is None  # 10^10 cells: sorted instead
    np.testing.assert_array_equal(module.unique_rows(far), np.unique(far, axis=0))

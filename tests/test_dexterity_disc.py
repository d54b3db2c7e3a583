"""The largest certified dexterous disc, about a centre and over all centres, against the
independent float reference of :mod:`tests.test_dexterity` (κ by central finite differences
of an inverse kinematics built by circle intersection).

Checks: every point of a fine grid in the disc of the certified lower radius is dexterous;
some grid point no farther than the upper radius (plus one grid step) is not; the radius
over all centres brackets a grid estimate (each dexterous grid point's distance to the
nearest non-dexterous one, the largest of them). Each check fails when the κ enclosure the
paving sees is shrunk by 1 % (:func:`shrunk`), or the disc's radius grown by 1 %.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial import cKDTree

import tests.test_dexterity as base
from planar_tui.workspace.paving import disc
from tests.test_dexterity import FIVEBAR, TABLE3, fivebar_legs, rrr_legs, run, shrunk
from tests.test_dexterity_prismatic import (
    PRR,
    RPR,
    patched,
    prr_actuators,
    prr_modes,
    rpr_actuators,
)

#: A centre of the Table-3 robot's dexterous region (κ ≤ 4, elbow 1 -1 1).
CENTRE = (36.0, 9.5)


def grid_points(centre, radius, step_cm):
    """The points of a grid of step ``step_cm`` (through ``centre``) in the closed disc."""
    n = int(np.ceil(radius / step_cm))
    offsets = np.arange(-n, n + 1) * step_cm
    x, y = np.meshgrid(centre[0] + offsets, centre[1] + offsets)
    x, y = x.ravel(), y.ravel()
    inside = np.hypot(x - centre[0], y - centre[1]) <= radius
    return x[inside], y[inside]


def dexterous_at(legs, length_cm, kappa_max, x, y):
    valid, kappa = base.kappa_reference(legs, x, y, length_cm)  # patched for a prismatic
    return valid & (kappa <= kappa_max)


def check_lower(legs, length_cm, kappa_max, centre, radius, step_cm):
    """Every grid point of the disc of the lower radius is dexterous."""
    x, y = grid_points(centre, radius, step_cm)
    good = dexterous_at(legs, length_cm, kappa_max, x, y)
    assert good.all(), f"{np.count_nonzero(~good)} points of the certified disc not dexterous"


def check_upper(legs, length_cm, kappa_max, centre, radius, step_cm):
    """Some grid point no farther than ``radius + step_cm`` is not dexterous."""
    x, y = grid_points(centre, radius + step_cm, step_cm)
    good = dexterous_at(legs, length_cm, kappa_max, x, y)
    assert not good.all(), "the disc of the upper radius holds no point that is not dexterous"


def grid_largest_radius(outcome, legs, length_cm, step_cm):
    """The grid estimate of the largest dexterous disc over all centres: the largest
    distance from a dexterous grid point to the nearest non-dexterous one."""
    xlo, xhi = outcome.boxes[:, 0].min() - 1.0, outcome.boxes[:, 1].max() + 1.0
    ylo, yhi = outcome.boxes[:, 2].min() - 1.0, outcome.boxes[:, 3].max() + 1.0
    x, y = np.meshgrid(np.arange(xlo, xhi, step_cm), np.arange(ylo, yhi, step_cm))
    x, y = x.ravel(), y.ravel()
    good = dexterous_at(legs, length_cm, outcome.kappa_max, x, y)
    bad = np.column_stack([x[~good], y[~good]])
    distance, _ = cKDTree(bad).query(np.column_stack([x[good], y[good]]))
    return float(distance.max())


def check_discs_about_a_grid(outcome, extent, legs, length_cm, step_cm):
    """About every centre of a grid of step ``step_cm``, the points of the certified disc
    (the centre and 16 directions at a third, two thirds and all of the lower radius) are
    dexterous."""
    xlo, xhi = outcome.boxes[:, 0].min(), outcome.boxes[:, 1].max()
    ylo, yhi = outcome.boxes[:, 2].min(), outcome.boxes[:, 3].max()
    x, y = np.meshgrid(np.arange(xlo, xhi, step_cm), np.arange(ylo, yhi, step_cm))
    centres = np.column_stack([x.ravel(), y.ravel()])
    lo, hi = disc.radius_bounds(outcome, extent, centres)
    assert (lo <= hi).all()
    centres, lo = centres[lo > 0], lo[lo > 0]
    angle = np.linspace(0.0, 2 * np.pi, 16, endpoint=False)
    ring = np.concatenate([[0.0], *(f * np.ones(16) for f in (1 / 3, 2 / 3, 1.0))])
    turn = np.concatenate([[0.0], angle, angle, angle])
    px = centres[:, :1] + lo[:, None] * ring * np.cos(turn)
    py = centres[:, 1:] + lo[:, None] * ring * np.sin(turn)
    good = dexterous_at(legs, length_cm, outcome.kappa_max, px.ravel(), py.ravel())
    assert good.all(), f"{np.count_nonzero(~good)} points of certified discs not dexterous"
    return len(centres)


def table3(tmp_path, extra=""):
    centre = f"circle_centre_cm = [{CENTRE[0]}, {CENTRE[1]}]\n"
    return run(tmp_path, TABLE3.format(precision=0.2, kappa=4, extra=centre + extra))


@pytest.fixture(scope="module")
def table3_run(tmp_path_factory):
    return table3(tmp_path_factory.mktemp("disc"))


def test_the_disc_about_the_centre_against_the_grid(table3_run):
    job, result = table3_run
    found = result.dexterity.disc
    assert found.centre_cm == CENTRE
    assert 0.5 < found.radius_lo_cm <= found.radius_hi_cm < found.radius_lo_cm + 0.5
    legs = rrr_legs(job)
    check_lower(legs, 25.0, 4.0, CENTRE, found.radius_lo_cm, 0.01)
    check_upper(legs, 25.0, 4.0, CENTRE, found.radius_hi_cm, 0.01)


def test_the_largest_disc_over_all_centres_against_the_grid(table3_run):
    job, result = table3_run
    found, legs = result.dexterity.disc, rrr_legs(job)
    check_lower(legs, 25.0, 4.0, found.best_centre_cm, found.best_lo_cm, 0.01)
    estimate = grid_largest_radius(result.dexterity, legs, 25.0, 0.02)
    assert found.best_lo_cm <= estimate + 0.02 <= found.best_hi_cm + 0.04
    assert found.best_hi_cm - found.best_lo_cm < 0.3  # and it is not vacuous


def test_the_summary_has_the_disc_columns(table3_run):
    _, result = table3_run
    header, (row,) = result.table.header, result.table.rows
    cells = dict(zip(header, row, strict=True))
    assert list(header)[-9:] == [*disc.HEADER, "seconds"]
    assert cells["dexterous_circle_centre_x_cm"] == CENTRE[0]
    lo, hi = cells["dexterous_disc_radius_lo_cm"], cells["dexterous_disc_radius_hi_cm"]
    assert 0.0 < lo <= hi
    assert "largest dexterous disc r ∈ [" in result.summary


def test_the_discs_about_a_grid_of_centres_are_dexterous(table3_run):
    job, result = table3_run
    extent = result.outcome.extent_cm
    assert check_discs_about_a_grid(result.dexterity, extent, rrr_legs(job), 25.0, 0.05) > 5000


def test_a_shrunk_enclosure_certifies_discs_that_are_not_dexterous(tmp_path, monkeypatch):
    shrunk(monkeypatch, 1.0, 0.99)
    job, result = table3(tmp_path)
    extent = result.outcome.extent_cm
    with pytest.raises(AssertionError, match="not dexterous"):
        check_discs_about_a_grid(result.dexterity, extent, rrr_legs(job), 25.0, 0.05)


def test_a_radius_grown_by_one_percent_fails(table3_run):
    job, result = table3_run
    found = result.dexterity.disc
    with pytest.raises(AssertionError, match="not dexterous"):
        check_lower(rrr_legs(job), 25.0, 4.0, CENTRE, 1.01 * found.radius_hi_cm, 0.01)


def test_the_five_bar_disc_against_the_grid(tmp_path):
    centre = (0.0, 60.0)
    extra = f"singularity_free_circle = [{centre[0]}, {centre[1]}]\n"
    job, result = run(tmp_path, FIVEBAR.format(precision=0.25, kappa=3, extra=extra))
    found, legs = result.dexterity.disc, fivebar_legs(job)
    assert found.radius_lo_cm > 0.0
    check_lower(legs, None, 3.0, centre, found.radius_lo_cm, 0.05)
    check_upper(legs, None, 3.0, centre, found.radius_hi_cm, 0.05)
    check_lower(legs, None, 3.0, found.best_centre_cm, found.best_lo_cm, 0.05)


def test_boxes_distance_is_exact():
    rng = np.random.default_rng(1)
    lo = rng.uniform(-10, 10, (300, 2))
    size = 2.0 ** rng.integers(-4, 3, (300, 1)) * rng.choice([1.0, 2.0], (300, 2))
    boxes = np.column_stack([lo[:, 0], lo[:, 0] + size[:, 0], lo[:, 1], lo[:, 1] + size[:, 1]])
    points = rng.uniform(-15, 15, (200, 2))
    dx = np.maximum(np.maximum(boxes[None, :, 0] - points[:, None, 0], 0.0), 0.0)
    dx = np.maximum(dx, points[:, None, 0] - boxes[None, :, 1])
    dy = np.maximum(boxes[None, :, 2] - points[:, None, 1], points[:, None, 1] - boxes[None, :, 3])
    brute = np.hypot(dx, np.maximum(dy, 0.0)).min(axis=1)
    assert np.array_equal(disc.boxes_distance(points, boxes), brute)


@pytest.mark.parametrize("robot", ["rpr", "prr"])
def test_the_prismatic_robots_discs_against_the_grid(tmp_path, monkeypatch, robot):
    job, result = run(tmp_path, (RPR if robot == "rpr" else PRR).format(precision=0.5))
    actuators = rpr_actuators(job) if robot == "rpr" else prr_actuators(job, prr_modes(job))
    patched(monkeypatch, actuators)
    outcome, kappa_max = result.dexterity, result.dexterity.kappa_max
    found = outcome.disc
    assert found.best_lo_cm > 0.0
    check_lower(None, 25.0, kappa_max, found.best_centre_cm, found.best_lo_cm, 0.05)
    check_discs_about_a_grid(outcome, result.outcome.extent_cm, None, 25.0, 0.25)


def test_an_unreachable_centre_is_refused_in_one_line(cli, tmp_path):
    path = tmp_path / "d.toml"
    extra = "circle_centre_cm = [0, 0]\n"
    path.write_text(TABLE3.format(precision=0.5, kappa=4, extra=extra), encoding="utf-8")
    result = cli("workspace", path, "--out-dir", tmp_path)
    assert result.exit_code == 2, result.output
    assert result.output.startswith("error: ") and result.output.count("\n") == 1
    assert "workspace.circle_centre_cm: (0, 0) cm is not reachable" in result.output
    assert not (tmp_path / "ws.csv").exists()


def test_a_centre_without_kappa_max_or_singularities_is_still_refused(cli, tmp_path):
    path = tmp_path / "d.toml"
    text = TABLE3.format(precision=0.5, kappa=4, extra="circle_centre_cm = [36, 9.5]\n")
    text = text.replace("kappa_max = 4\n", "").replace("elbow = [1, -1, 1]\n", "")
    path.write_text(text, encoding="utf-8")
    result = cli("workspace", path, "--out-dir", tmp_path)
    assert result.exit_code == 2, result.output
    assert "circle_centre_cm: is set without singularities = true" in result.output

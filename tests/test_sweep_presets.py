"""The bundled sweep presets: every point valid, and a few points of each study checked
against independent values (paper B's exact area, symmetry in the orientation, and the
closed-form gravity torques of the 2R robot for the tolerance crossover)."""

from __future__ import annotations

import pytest

from planar_tui.presets import load_preset
from planar_tui.resources import resolve_preset
from planar_tui.sweep.points import make_points
from planar_tui.sweep.service import run_sweep
from planar_tui.sweep.spec import parse_sweeps

#: Paper B, Table 3: the exact area of the constant-orientation workspace at phi = 0.
PAPER_B_AREA_CM2 = 106.750
G = 9.81


def sweep_points(name: str, k: int = 1):
    sweeps = parse_sweeps(load_preset(resolve_preset(name)))
    sweep = sweeps[k - 1]
    return sweep, make_points(sweep)


def rows_by_value(run, path: str) -> dict:
    header = list(run.table.header)
    return {row[header.index(path)]: dict(zip(header, row, strict=True)) for row in run.table.rows}


@pytest.mark.parametrize(
    ("name", "sweeps", "points"),
    [
        ("sweep-3rrr-orientation", 1, 25),
        ("sweep-3rrr-design", 1, 21),
        ("sweep-tolerance-crossover", 3, 20),
    ],
)
def test_every_point_of_the_bundled_sweeps_is_valid(name, sweeps, points):
    preset = load_preset(resolve_preset(name))
    found = parse_sweeps(preset)
    assert len(found) == sweeps
    assert all(len(make_points(sweep)) == points for sweep in found)


def test_orientation_study_brackets_paper_b_and_is_symmetric():
    sweep, points = sweep_points("sweep-3rrr-orientation")
    chosen = [p for p in points if p.values[0] in (-30.0, 0.0, 30.0)]
    rows = rows_by_value(run_sweep(sweep, points=chosen), "orientation_deg")
    at_zero = rows[0.0]
    assert at_zero["area_geometric_cm2"] == pytest.approx(PAPER_B_AREA_CM2, abs=1e-3)
    assert at_zero["area_inside_cm2"] <= PAPER_B_AREA_CM2 <= at_zero["area_kept_cm2"]
    # the base and platform are equilateral and the limits symmetric: A(phi) = A(-phi)
    assert rows[30.0]["area_geometric_cm2"] == pytest.approx(
        rows[-30.0]["area_geometric_cm2"], rel=1e-12
    )
    assert rows[30.0]["area_geometric_cm2"] > 1.5 * PAPER_B_AREA_CM2


def test_design_study_includes_paper_b_at_equal_links():
    sweep, points = sweep_points("sweep-3rrr-design")
    (equal,) = [p for p in points if p.values == (30.0, 30.0)]
    assert all(p + d == 60.0 for p, d in (point.values for point in points))
    (row,) = rows_by_value(run_sweep(sweep, points=[equal]), "robot3rrr.proximal_cm").values()
    assert row["area_geometric_cm2"] == pytest.approx(PAPER_B_AREA_CM2, abs=1e-3)
    assert row["area_inside_cm2"] <= PAPER_B_AREA_CM2 <= row["area_kept_cm2"]


def test_crossover_study_matches_the_2r_gravity_torques_closed_form():
    """At the singular posture (theta = 0) the Coriolis terms vanish (they go with
    sin theta2), so tau1 = g((m1/2 + m2) l1 + m2 l2/2), tau2 = g m2 l2/2. To first order a
    uniform tolerance +-d on p adds (dtau/dp · d)²/3 to the variance: the masses' share is
    sum_m (dtau/dm)² dm² / (sum_l (dtau/dl)² dl² + sum_m (dtau/dm)² dm²)."""
    sweep, points = sweep_points("sweep-tolerance-crossover", 1)
    robot = sweep.job.robot
    (l1, l2), (m1, m2) = robot.lengths_m, robot.masses_kg
    slopes = {  # torque: (d tau/d lengths, d tau/d masses)
        1: ((G * (m1 / 2 + m2), G * m2 / 2), (G * l1 / 2, G * (l1 + l2 / 2))),
        2: ((0.0, G * m2 / 2), (0.0, G * l2 / 2)),
    }
    chosen = [p for p in points if p.values[0] in (1.0, 3.0, 4.0, 10.0)]
    rows = rows_by_value(run_sweep(sweep, points=chosen), "tolerance_mass_g")
    for tolerance_g, row in rows.items():
        for torque, (by_length, by_mass) in slopes.items():
            lengths = sum(a * a for a in by_length) * 1e-3**2
            masses = sum(a * a for a in by_mass) * (tolerance_g * 1e-3) ** 2
            expected = 100 * masses / (lengths + masses)
            assert row[f"tau{torque}_masses_percent"] == pytest.approx(expected, abs=0.01)
            halfwidth = row[f"tau{torque}_sobol_halfwidth_max"]
            assert 0 < halfwidth < 0.1
    # the crossover lies between 3 and 4 g for both torques (closed form: 3.24 and 3.72 g)
    for torque in (1, 2):
        assert (
            rows[3.0][f"tau{torque}_masses_percent"] < 50 < rows[4.0][f"tau{torque}_masses_percent"]
        )

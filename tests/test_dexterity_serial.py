"""The serial arm's κ (the simulate job's ``kappa`` and ``kappa_pose`` columns) against
references written here: the tip Jacobian by central finite differences of a forward
kinematics of its own (numpy's SVD for κ), and the 2-link arm's closed form.

Closed form (2 links, lengths l1, l2, relative angle θ2): the columns of the position
Jacobian are the tip vector turned a quarter (squared norm l1² + l2² + 2 l1 l2 cos θ2) and
the second link turned a quarter (l2²), det J = l1 l2 sin θ2, so with σ1² + σ2² = ‖J‖²_F and
σ1 σ2 = |det J|

    κ + 1/κ = (l1² + 2 l2² + 2 l1 l2 cos θ2) / (l1 l2 |sin θ2|),

independent of θ1. With l1 = l2, θ2 = 90°: κ + 1/κ = 3, κ = (3 + √5)/2 (the golden ratio
squared); with l1 = √2 l2, θ2 = 135°: κ = 1 (the isotropic posture); θ2 = 0: singular.
"""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest
from planar_tui.kernels.serial_kappa import tip_kappa

from planar_tui.batch import prepare_jobs, run_job
from planar_tui.presets import load_preset


def tip_pose(lengths, theta):
    """The tip ``(x, y, φ)`` of the arm at relative angles ``theta`` (..., n), written
    independently of the kernels: each link's absolute angle summed explicitly."""
    theta = np.asarray(theta, dtype=float)
    x = np.zeros(theta.shape[:-1])
    y = np.zeros(theta.shape[:-1])
    angle = np.zeros(theta.shape[:-1])
    for k, length in enumerate(lengths):
        angle = angle + theta[..., k]
        x = x + length * np.cos(angle)
        y = y + length * np.sin(angle)
    return np.stack([x, y, angle], axis=-1)


def kappa_reference(lengths, theta, length_m=None, step=1e-6):
    """κ of the tip Jacobian by central differences of :func:`tip_pose` (the pose's third
    row scaled by ``length_m`` where given)."""
    theta = np.asarray(theta, dtype=float)
    n = theta.shape[-1]
    columns = []
    for j in range(n):
        move = np.zeros(n)
        move[j] = step
        columns.append((tip_pose(lengths, theta + move) - tip_pose(lengths, theta - move)) / 2)
    jac = np.stack(columns, axis=-1) / step  # (..., 3, n)
    jac = jac[..., :2, :] if length_m is None else jac * np.array([1, 1, length_m])[:, None]
    sigma = np.linalg.svd(jac, compute_uv=False)
    m = jac.shape[-2]
    if n < m:
        return np.full(theta.shape[:-1], np.inf)
    return sigma[..., 0] / sigma[..., m - 1]


def kernel_kappa(lengths, theta, length_m=None):
    theta = np.ascontiguousarray(np.atleast_2d(theta), dtype=float)
    out = np.empty(len(theta))
    tip_kappa(np.asarray(lengths, dtype=float), theta, 0.0 if length_m is None else length_m, out)
    return out


def check_against_differences(kappa, lengths, theta, length_m=None):
    expected = kappa_reference(lengths, theta, length_m)
    np.testing.assert_allclose(kappa, expected, rtol=1e-6)


def closed_form(l1, l2, theta2):
    """κ of the 2-link arm (module docstring)."""
    s = (l1 * l1 + 2 * l2 * l2 + 2 * l1 * l2 * math.cos(theta2)) / (l1 * l2 * abs(math.sin(theta2)))
    return 0.5 * (s + math.sqrt(s * s - 4.0))


@pytest.mark.parametrize(
    ("l1", "l2", "theta2_deg", "expected"),
    [
        (0.3, 0.3, 90.0, (3 + math.sqrt(5)) / 2),
        (math.sqrt(2) * 0.2, 0.2, 135.0, 1.0),
        (0.303, 0.214, 40.0, closed_form(0.303, 0.214, math.radians(40.0))),
        (0.303, 0.214, -120.0, closed_form(0.303, 0.214, math.radians(-120.0))),
    ],
)
def test_the_two_link_arm_against_its_closed_form(l1, l2, theta2_deg, expected):
    theta1 = np.radians([0.0, 37.0, -150.0])  # κ does not depend on θ1
    theta = np.column_stack([theta1, np.full(3, math.radians(theta2_deg))])
    np.testing.assert_allclose(kernel_kappa([l1, l2], theta), expected, rtol=1e-12)


def test_random_arms_against_finite_differences():
    rng = np.random.default_rng(7)
    for n in range(2, 8):
        lengths = rng.uniform(0.05, 0.5, n)
        theta = rng.uniform(-math.pi, math.pi, (50, n))
        check_against_differences(kernel_kappa(lengths, theta), lengths, theta)
        if n >= 3:
            for length_m in (0.1, 0.4):
                kappa = kernel_kappa(lengths, theta, length_m)
                check_against_differences(kappa, lengths, theta, length_m)


def test_a_one_percent_error_fails_the_checks():
    lengths, theta = [0.25, 0.2, 0.15], np.radians([[10.0, 50.0, -30.0]])
    with pytest.raises(AssertionError):
        check_against_differences(1.01 * kernel_kappa(lengths, theta), lengths, theta)
    with pytest.raises(AssertionError):
        check_against_differences(
            kernel_kappa([0.3, 0.3], [0.0, 0.5 * math.pi]) * 1.01, [0.3, 0.3], [0.0, 0.5 * math.pi]
        )


def test_singular_postures_are_infinite():
    stretched = np.zeros((1, 4))
    assert kernel_kappa([0.2, 0.2, 0.1, 0.1], stretched)[0] == math.inf
    folded = np.radians([[30.0, 180.0]])
    assert kernel_kappa([0.3, 0.3], folded)[0] == math.inf
    assert kernel_kappa([0.3], [[0.4]])[0] == math.inf  # one joint: no 2-D motion
    assert kernel_kappa([0.3, 0.2], [[0.1, 0.7]], 0.2)[0] == math.inf  # 2 joints, 3-D task


SIMULATE = """
[robot]
lengths_m = [0.303, 0.214, 0.15]
masses_kg = [1.126, 0.796, 0.5]
[[simulate]]
duration_s = 0.05
step_s = 0.001
theta0_deg = [{theta0}]
omega0_deg_s = [40, -90, 60]
every = 5
{extra}output = "sim.csv"
"""


def simulate(tmp_path, theta0="10, 60, -30", extra=""):
    path = tmp_path / "s.toml"
    path.write_text(SIMULATE.format(theta0=theta0, extra=extra), encoding="utf-8")
    (job,) = prepare_jobs(load_preset(path).jobs)
    return job, run_job(job)


def test_the_simulate_csv_has_kappa_per_row(tmp_path):
    job, result = simulate(tmp_path, extra="characteristic_length_cm = 20\n")
    header = list(result.table.header)
    assert header[-2:] == ["kappa", "kappa_pose"]
    rows = list(result.table.rows)
    kappa = np.array([row[-2] for row in rows])
    pose = np.array([row[-1] for row in rows])
    lengths = job.robot.lengths_m
    check_against_differences(kappa, lengths, result.theta_rad)
    check_against_differences(pose, lengths, result.theta_rad, 0.2)


def test_without_the_length_there_is_no_pose_column(tmp_path):
    _, result = simulate(tmp_path)
    assert list(result.table.header)[-2:] == ["energy_J", "kappa"]


def test_a_singular_row_is_written_empty(cli, tmp_path):
    path = tmp_path / "s.toml"
    path.write_text(SIMULATE.format(theta0="0, 0, 0", extra=""), encoding="utf-8")
    result = cli("simulate", path, "--out-dir", tmp_path)
    assert result.exit_code == 0, result.output
    with open(tmp_path / "sim.csv", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    assert rows[0]["kappa"] == ""  # stretched out: singular
    assert all(float(row["kappa"]) >= 1.0 for row in rows[1:])


def test_a_bad_length_is_refused_in_one_line(cli, tmp_path):
    path = tmp_path / "s.toml"
    path.write_text(SIMULATE.format(theta0="0, 0, 0", extra="characteristic_length_cm = -1\n"))
    result = cli("simulate", path, "--out-dir", tmp_path)
    assert result.exit_code == 2, result.output
    assert result.output.startswith("error: ") and result.output.count("\n") == 1
    assert "simulate[1].characteristic_length_cm: is -1" in result.output
    assert not (tmp_path / "sim.csv").exists()

"""Certified paths with ``leg_width_cm``: the interval clearance over time intervals
against dense sampling of exact segment distances (``tests/test_interference.py``'s
reference: elbows by circle intersection, Ericson's segment-segment distance), the first
crossing found by brentq inside ``[first_failure_lo_s, first_failure_hi_s]``, reason
``interference``; a clear path certified; the verdict wrong with the gap enclosure shrunk
by 1 % of the width. The 3-RRR (a compact one whose legs collide over half its
workspace, the platform turning along the path) and the five-bar."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from planar_tui.workspace.path import certify as certify_module
from planar_tui.workspace.path.certify import certify
from planar_tui.workspace.rrr.mechanism import MECHANISM
from planar_tui.workspace.rrr.path import Path3RRRSpec
from planar_tui.workspace.rrr.robot import Robot3RRR
from tests.certified_path_reference import path_poses
from tests.test_interference import WIDTH_CM, link_gap

ROBOT = Robot3RRR(base_side_cm=80, platform_side_cm=40, proximal_cm=30, distal_cm=30)
ELBOW = (1, 1, 1)
FULL = ((-180.0, 180.0),) * 3
#: name: from_pose, to_pose (cm, cm, deg), verdict
PATHS = {
    "clash": ((24.0, 4.0, 0.0), (44.0, 4.0, 4.0), "no"),
    "clear": ((22.0, 4.0, 0.0), (32.0, 5.0, 3.0), "yes"),
}
SAMPLES = 20_000


class Quiet:
    def start(self, *args):
        pass

    def advance(self, *args):
        pass


def gap_at(poses):
    """The reference gap min(d - d_req) and validity at poses (k, 3) (cm, cm, rad)."""
    x, y, phi = poses[:, 0], poses[:, 1], poses[:, 2]
    l1, l2 = ROBOT.proximal_cm, ROBOT.distal_cm
    valid = np.ones(len(x), dtype=bool)
    a_, b_, c_ = [], [], []
    for (ax, ay), (qx, qy), sign in zip(
        ROBOT.base_joints_cm(), ROBOT.platform_points_cm(), ELBOW, strict=True
    ):
        cx = x + np.cos(phi) * qx - np.sin(phi) * qy
        cy = y + np.sin(phi) * qx + np.cos(phi) * qy
        dx, dy = cx - ax, cy - ay
        d = np.hypot(dx, dy)
        along = (l1 * l1 - l2 * l2 + d * d) / (2 * d)
        h = np.sqrt(np.maximum(l1 * l1 - along * along, 0.0))
        valid &= (d < l1 + l2) & (d > abs(l1 - l2))
        b_.append(
            np.stack(
                [ax + along * dx / d - sign * h * dy / d, ay + along * dy / d + sign * h * dx / d],
                axis=-1,
            )
        )
        a_.append(np.stack([np.full(len(x), ax), np.full(len(x), ay)], axis=-1))
        c_.append(np.stack([cx, cy], axis=-1))
    links = [(i, a_[i], b_[i], None) for i in range(3)]
    links += [(i, b_[i], c_[i], i) for i in range(3)]
    return valid, link_gap(links, c_, True)


def certificate_of(name):
    start, stop, _ = PATHS[name]
    spec = Path3RRRSpec(
        from_pose=start,
        to_pose=stop,
        elbow=ELBOW,
        joint_limits_deg=FULL,
        kappa_max=1e6,
        leg_width_cm=WIDTH_CM,
    )
    s = (*start[:2], math.radians(start[2]))
    e = (*stop[:2], math.radians(stop[2]))
    return certify(MECHANISM.path_box_test(ROBOT, spec), s, e, 1.0, 1e6, Quiet()), s, e


def first_crossing(start, stop):
    """The first time the reference gap falls below 0 (brentq after dense sampling)."""
    times = np.linspace(0.0, 1.0, SAMPLES + 1)
    valid, gap = gap_at(path_poses(start, stop, 1.0, times))
    assert valid.all()  # the legs close all along: the only failure is interference
    bad = np.flatnonzero(gap < 0.0)
    if not len(bad):
        return None
    k = int(bad[0])

    def at(t):
        return float(gap_at(path_poses(start, stop, 1.0, np.array([t])))[1][0])

    return brentq(at, times[k - 1], times[k], xtol=1e-12)


def narrow_gaps(monkeypatch):
    """Every gap enclosure a certificate sees moved inwards by 1 % of the width at each
    end (a wrong change the tests must catch)."""
    original = certify_module.with_clearance

    def with_clearance(test, clearance):
        def narrowed(boxes):
            verdict, gap = clearance(boxes)
            shift = 0.01 * WIDTH_CM
            return verdict, np.stack([gap[:, 0] + shift, gap[:, 1] - shift], axis=1)

        return original(test, narrowed)

    monkeypatch.setattr(certify_module, "with_clearance", with_clearance)


def check_job_against_sampling(tmp_path, text, start, stop, verdict):
    """Run the path job of preset ``text`` (a point path ``start`` to ``stop`` in 1 s)
    and check its certificate against ``tests/test_interference.py``'s reference sampled
    densely: the ``verdict``, and a failure's reason and bracket holding the first
    crossing (brentq), at most T/1000 wide."""
    from planar_tui.batch import prepare_jobs, run_job
    from planar_tui.presets import load_preset
    from tests.test_interference import reference

    (tmp_path / "p.toml").write_text(text, encoding="utf-8")
    (job,) = prepare_jobs(load_preset(tmp_path / "p.toml").jobs)
    certificate = run_job(job).certificate
    times = np.linspace(0.0, 1.0, SAMPLES + 1)

    def gap(t):
        poses = path_poses(start, stop, 1.0, np.atleast_1d(t))
        return reference(job, poses[:, 0], poses[:, 1])

    valid, sampled = gap(times)
    assert valid.all()
    assert certificate.certified == verdict
    bad = np.flatnonzero(sampled < 0.0)
    if verdict == "yes":
        assert not len(bad)
        return
    k = int(bad[0])
    t_star = brentq(lambda t: float(gap(t)[1][0]), times[k - 1], times[k], xtol=1e-12)
    assert certificate.reason == "interference"
    assert certificate.failure_lo_s - 1e-9 <= t_star <= certificate.failure_hi_s + 1e-9
    assert certificate.failure_hi_s - certificate.failure_lo_s <= 1e-3


@pytest.mark.parametrize("name", sorted(PATHS))
def test_the_verdict_and_the_first_crossing_against_dense_sampling(name):
    certificate, start, stop = certificate_of(name)
    t_star = first_crossing(start, stop)
    assert certificate.certified == PATHS[name][2]
    if t_star is None:
        assert certificate.failure_lo_s is None
        return
    assert certificate.reason == "interference"
    assert certificate.failure_lo_s - 1e-9 <= t_star <= certificate.failure_hi_s + 1e-9
    assert certificate.failure_hi_s - certificate.failure_lo_s <= 1e-3


def test_a_gap_enclosure_shrunk_by_one_percent_moves_the_first_failure(monkeypatch):
    """Each end of every gap enclosure moved 1 % of the width inwards: the certificate's
    bracket no longer holds the reference's first crossing."""
    narrow_gaps(monkeypatch)
    certificate, start, stop = certificate_of("clash")
    t_star = first_crossing(start, stop)
    inside = certificate.failure_lo_s - 1e-9 <= t_star <= certificate.failure_hi_s + 1e-9
    assert certificate.certified != "no" or not inside


FIVEBAR_PATH = """
[robot5r]
base_separation_cm = 40
proximal_cm = [45, 45]
distal_cm = [55, 55]
joint_limits_deg = [[-180, 180], [-180, 180]]
working_mode = "{mode}"
[[path5r]]
from_pose = {start}
to_pose = {stop}
steps = 10
kappa_max = 1e6
{extra}output = "p.csv"
"""
#: The five-bar's paths: mode, from, to (cm), verdict.
FIVEBAR_PATHS = {
    "clash": ("-+", [2, 6], [2, 18], "no"),
    "clear": ("+-", [2, 30], [20, 50], "yes"),
}


@pytest.mark.parametrize("name", sorted(FIVEBAR_PATHS))
def test_the_five_bar_verdict_and_first_crossing_against_dense_sampling(tmp_path, name):
    mode, start, stop, verdict = FIVEBAR_PATHS[name]
    text = FIVEBAR_PATH.format(
        mode=mode, start=start, stop=stop, extra=f"leg_width_cm = {WIDTH_CM}\n"
    )
    check_job_against_sampling(tmp_path, text, start, stop, verdict)


def test_the_five_bar_check_fails_with_a_shrunk_gap(tmp_path, monkeypatch):
    """The five-bar's dense-sampling check, with every gap enclosure shrunk by 1 % of the
    width at each end: the bracket misses the first crossing (or the verdict changes), an
    assertion on the certificate (not on the reference's sampling)."""
    narrow_gaps(monkeypatch)
    with pytest.raises(AssertionError, match=r"Certificate\("):
        test_the_five_bar_verdict_and_first_crossing_against_dense_sampling(tmp_path, "clash")


def test_the_job_writes_the_interference_certificate_and_exits_0(cli, tmp_path):
    mode, start, stop, _ = FIVEBAR_PATHS["clash"]
    text = FIVEBAR_PATH.format(mode=mode, start=start, stop=stop, extra="leg_width_cm = 6\n")
    (tmp_path / "p.toml").write_text(text, encoding="utf-8")
    result = cli("run", tmp_path / "p.toml", "--out-dir", tmp_path / "out")
    assert result.exit_code == 0, result.output
    written = (tmp_path / "out" / "p-certificate.csv").read_text(encoding="utf-8")
    assert written.splitlines()[1].startswith("no,") and ",interference," in written


def test_leg_width_without_kappa_max_is_one_line_and_exit_2(cli, tmp_path):
    mode, start, stop, _ = FIVEBAR_PATHS["clash"]
    text = FIVEBAR_PATH.format(mode=mode, start=start, stop=stop, extra="leg_width_cm = 6\n")
    text = text.replace("kappa_max = 1e6\n", "")
    (tmp_path / "p.toml").write_text(text, encoding="utf-8")
    result = cli("run", tmp_path / "p.toml", "--out-dir", tmp_path / "out")
    assert result.exit_code == 2
    assert "leg_width_cm: is set without kappa_max" in result.output
    assert len(result.output.strip().splitlines()) == 1


PRISMATIC = {
    "3rpr-clash": (
        "[robot3rpr]\n[[path3rpr]]\nleg_limits_cm = [[5, 100], [5, 100], [5, 100]]\n",
        [29, 50, 0],
        [29, 82, 0],
        "no",
    ),
    "3rpr-clear": (
        "[robot3rpr]\n[[path3rpr]]\nleg_limits_cm = [[5, 100], [5, 100], [5, 100]]\n",
        [21, 21, 0],
        [36, 13, 0],
        "yes",
    ),
    "3prr-clash": (
        "[robot3prr]\n[[path3prr]]\nslider_modes = [1, 1, 1]\n",
        [33, 32, 0],
        [63, 32, 0],
        "no",
    ),
    "3prr-clear": (
        "[robot3prr]\n[[path3prr]]\nslider_modes = [1, 1, 1]\n",
        [29, 14, 0],
        [51, 19, 0],
        "yes",
    ),
}


@pytest.mark.parametrize("name", sorted(PRISMATIC))
def test_the_prismatic_robots_against_dense_sampling(tmp_path, name):
    """The 3-RPR and 3-PRR at φ = 0 along the path (the references of
    ``tests/test_interference.py``: leg lengths, sliders on their lines)."""
    head, start, stop, verdict = PRISMATIC[name]
    text = f"{head}from_pose = {start}\nto_pose = {stop}\nsteps = 10\nkappa_max = 1e6\n"
    text += f'leg_width_cm = {WIDTH_CM}\noutput = "p.csv"\n'
    check_job_against_sampling(tmp_path, text, start, stop, verdict)


@pytest.mark.parametrize("name", ["3rpr-clash", "3prr-clash"])
def test_the_prismatic_check_fails_with_a_shrunk_gap(tmp_path, monkeypatch, name):
    """The dense-sampling check above, with every gap enclosure shrunk by 1 % of the width
    at each end: the bracket misses the first crossing (or the verdict changes)."""
    narrow_gaps(monkeypatch)
    with pytest.raises(AssertionError):
        test_the_prismatic_robots_against_dense_sampling(tmp_path, name)


def test_a_certified_path_reports_its_certificate_to_sweeps_and_optimisations(tmp_path):
    """``path_certified``, ``certified_until_s`` and ``kappa_peak_hi`` among the job's
    figure names, and their values from its certificate CSV's row."""
    from planar_tui.batch import prepare_jobs, run_job
    from planar_tui.presets import load_preset
    from planar_tui.workspace.path.job import figure_names, point_figures

    mode, start, stop, _ = FIVEBAR_PATHS["clash"]
    text = FIVEBAR_PATH.format(mode=mode, start=start, stop=stop, extra="leg_width_cm = 6\n")
    (tmp_path / "p.toml").write_text(text, encoding="utf-8")
    (job,) = prepare_jobs(load_preset(tmp_path / "p.toml").jobs)
    result = run_job(job)
    table = result.extra_tables["certificate"]
    row = dict(zip(table.header, table.rows[0], strict=True))
    found = point_figures(job.job, result)
    assert {"path_certified", "certified_until_s", "kappa_peak_hi"} <= set(figure_names(job.job))
    assert found["path_certified"] == 0.0 and row["certified"] == "no"
    assert found["certified_until_s"] == row["first_failure_lo_s"]
    assert found["kappa_peak_hi"] == row["kappa_peak_hi"]

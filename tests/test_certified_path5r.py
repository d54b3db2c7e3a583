"""Certified paths of the five-bar (``kappa_max`` on ``[[path5r]]``): verdicts, brackets
and the largest κ against dense sampling of the reference of
:mod:`tests.certified_path_reference`, a 1 % shrunk κ enclosure caught, and the job's
certificate CSV."""

from __future__ import annotations

import csv

import numpy as np
import pytest

from planar_tui.workspace.fivebar.mechanism import MECHANISM
from planar_tui.workspace.fivebar.path import Path5RSpec
from planar_tui.workspace.fivebar.robot import Robot5R
from planar_tui.workspace.path.certify import certify
from tests.certified_path_reference import Legs, check_certificate, shrink_kappa

ROBOT = Robot5R(working_mode="+-")
#: name: from_pose, to_pose (cm), kappa_max, verdict
PATHS = {
    "certified": ((0, 60), (10, 65), 5.0, "yes"),
    "kappa": ((0, 60), (0, 95), 2.0, "no"),
    "joint_limit": ((0, 60), (60, 20), 50.0, "no"),
    "leg": ((0, 120), (0, 60), 50.0, "no"),
}
LEGS = Legs(
    bases=np.array(ROBOT.base_joints_cm()),
    points=np.zeros((2, 2)),
    l1=np.array(ROBOT.proximal_cm),
    l2=np.array(ROBOT.distal_cm),
    elbow=np.array(ROBOT.elbows, dtype=float),
    limits=np.array(ROBOT.limits_rad),
    length_cm=0.0,
)


class Quiet:
    def start(self, *args):
        pass

    def advance(self, *args):
        pass


def check(name, samples=20_000):
    start, stop, kappa_max, verdict = PATHS[name]
    spec = Path5RSpec(from_pose=start, to_pose=stop, elbow=ROBOT.elbows, kappa_max=kappa_max)
    test = MECHANISM.path_box_test(ROBOT, spec)
    certificate = certify(test, start, stop, 1.0, kappa_max, Quiet())
    check_certificate(certificate, LEGS, start, stop, kappa_max, verdict, name, samples)


@pytest.mark.parametrize("name", ["certified", "kappa"])
def test_the_verdict_brackets_and_peak_match_dense_sampling(name):
    check(name)


@pytest.mark.slow
@pytest.mark.parametrize("name", ["joint_limit", "leg"])
def test_the_failures_at_a_joint_limit_and_out_of_reach(name):
    check(name)


@pytest.mark.parametrize("name", ["certified", "kappa"])
def test_a_kappa_enclosure_shrunk_by_one_percent_is_caught(monkeypatch, name):
    shrink_kappa(monkeypatch, MECHANISM)
    with pytest.raises(AssertionError):
        check(name, samples=2000)


def test_the_job_writes_its_certificate(cli, tmp_path):
    preset = tmp_path / "f.toml"
    preset.write_text(
        '[robot5r]\nworking_mode = "+-"\n\n[[path5r]]\nfrom_pose = [0, 60]\n'
        'to_pose = [10, 65]\nsteps = 10\nkappa_max = 5\noutput = "f.csv"\n',
        encoding="utf-8",
    )
    result = cli("run", preset, "--out-dir", tmp_path / "out")
    assert result.exit_code == 0, result.output
    with open(tmp_path / "out" / "f-certificate.csv", newline="") as handle:
        (row,) = list(csv.DictReader(handle))
    assert row["certified"] == "yes"
    assert row["first_failure_lo_s"] == row["first_failure_hi_s"] == row["reason"] == ""
    assert 1.9 < float(row["kappa_peak_lo"]) <= float(row["kappa_peak_hi"]) < 1.93

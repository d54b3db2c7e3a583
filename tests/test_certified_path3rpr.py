"""Certified paths of the 3-RPR (``kappa_max`` on ``[[path3rpr]]``): verdicts, brackets and
the largest κ against dense sampling of an independent reference (leg lengths in closed
form, κ by finite differences, the first crossing by brentq), a 1 % shrunk κ enclosure
caught, and the job's certificate CSV."""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest

from planar_tui.workspace.path.certify import certify
from planar_tui.workspace.paving.dexterity import circumradius_cm
from planar_tui.workspace.rpr.mechanism import MECHANISM
from planar_tui.workspace.rpr.path import Path3RPRSpec
from planar_tui.workspace.rpr.robot import Robot3RPR
from tests.certified_path_reference import PrismaticLegs, check_certificate, shrink_kappa

ROBOT = Robot3RPR()
LIMITS = ((20.0, 80.0),) * 3
#: name: from_pose, to_pose (cm, cm, deg), kappa_max, verdict
PATHS = {
    "certified": ((40, 21, 40), (45, 25, 45), 10.0, "yes"),
    "kappa": ((40, 21, 40), (20, 21, 40), 4.5, "no"),
    "joint_limit": ((40, 21, 40), (20, 21, 40), 50.0, "no"),
}
LEGS = PrismaticLegs(
    bases=np.array(ROBOT.base_joints_cm),
    points=np.array(ROBOT.platform_points_cm),
    limits=np.array(LIMITS),
    length_cm=circumradius_cm(ROBOT.platform_points_cm),
)


class Quiet:
    def start(self, *args):
        pass

    def advance(self, *args):
        pass


def check(name, samples=20_000):
    start, stop, kappa_max, verdict = PATHS[name]
    spec = Path3RPRSpec(from_pose=start, to_pose=stop, leg_limits_cm=LIMITS, kappa_max=kappa_max)
    test = MECHANISM.path_box_test(ROBOT, spec)
    s = (start[0], start[1], math.radians(start[2]))
    e = (stop[0], stop[1], math.radians(stop[2]))
    certificate = certify(test, s, e, 1.0, kappa_max, Quiet())
    check_certificate(certificate, LEGS, s, e, kappa_max, verdict, name, samples)


@pytest.mark.parametrize("name", ["certified", "kappa", "joint_limit"])
def test_the_verdict_brackets_and_peak_match_dense_sampling(name):
    check(name)


@pytest.mark.parametrize("name", ["certified", "kappa"])
def test_a_kappa_enclosure_shrunk_by_one_percent_is_caught(monkeypatch, name):
    shrink_kappa(monkeypatch, MECHANISM)
    with pytest.raises(AssertionError):
        check(name, samples=2000)


def test_the_job_writes_its_certificate(cli, tmp_path):
    preset = tmp_path / "r.toml"
    preset.write_text(
        "[robot3rpr]\n\n[[path3rpr]]\nfrom_pose = [40, 21, 40]\nto_pose = [20, 21, 40]\n"
        "steps = 10\nleg_limits_cm = [[20, 80], [20, 80], [20, 80]]\nkappa_max = 50\n"
        'output = "r.csv"\n',
        encoding="utf-8",
    )
    result = cli("run", preset, "--out-dir", tmp_path / "out")
    assert result.exit_code == 0, result.output
    with open(tmp_path / "out" / "r-certificate.csv", newline="") as handle:
        (row,) = list(csv.DictReader(handle))
    assert row["certified"] == "no" and row["reason"] == "joint_limit"

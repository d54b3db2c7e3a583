"""Certified paths of the 3-PRR (``kappa_max`` on ``[[path3prr]]``): verdicts, brackets and
the largest κ against dense sampling of an independent reference (the sliders' strokes in
closed form, κ by finite differences, the first crossing by brentq), a 1 % shrunk κ
enclosure caught, and the job's certificate CSV."""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest

from planar_tui.workspace.path.certify import certify
from planar_tui.workspace.paving.dexterity import circumradius_cm
from planar_tui.workspace.prr.mechanism import MECHANISM
from planar_tui.workspace.prr.path import Path3PRRSpec
from planar_tui.workspace.prr.robot import Robot3PRR
from tests.certified_path_reference import SliderLegs, check_certificate, shrink_kappa

ROBOT = Robot3PRR()
MODES = (1, 1, 1)
#: name: from_pose, to_pose (cm, cm, deg), kappa_max, verdict
PATHS = {
    "certified": ((40, 25, 0), (42, 27, 5), 10.0, "yes"),
    "kappa": ((40, 25, 30), (20, 10, 30), 50.0, "no"),
    "joint_limit": ((40, 25, 30), (40, 60, 30), 50.0, "no"),
    "leg": ((40, 25, -30), (42, 27, 5), 50.0, "no"),
}
ANGLES = np.radians(ROBOT.slider_angles_deg)
LEGS = SliderLegs(
    origins=np.array(ROBOT.slider_points_cm),
    directions=np.column_stack([np.cos(ANGLES), np.sin(ANGLES)]),
    strokes=np.array(ROBOT.strokes_cm),
    distal=np.array(ROBOT.distal_cm, dtype=float),
    modes=np.array(MODES, dtype=float),
    points=np.array(ROBOT.platform_points_cm),
    length_cm=circumradius_cm(ROBOT.platform_points_cm),
)


class Quiet:
    def start(self, *args):
        pass

    def advance(self, *args):
        pass


def check(name, samples=20_000):
    start, stop, kappa_max, verdict = PATHS[name]
    spec = Path3PRRSpec(from_pose=start, to_pose=stop, slider_modes=MODES, kappa_max=kappa_max)
    test = MECHANISM.path_box_test(ROBOT, spec)
    s = (start[0], start[1], math.radians(start[2]))
    e = (stop[0], stop[1], math.radians(stop[2]))
    certificate = certify(test, s, e, 1.0, kappa_max, Quiet())
    check_certificate(certificate, LEGS, s, e, kappa_max, verdict, name, samples)


@pytest.mark.parametrize("name", ["certified", "kappa", "joint_limit", "leg"])
def test_the_verdict_brackets_and_peak_match_dense_sampling(name):
    check(name)


@pytest.mark.parametrize("name", ["certified", "kappa"])
def test_a_kappa_enclosure_shrunk_by_one_percent_is_caught(monkeypatch, name):
    shrink_kappa(monkeypatch, MECHANISM)
    with pytest.raises(AssertionError):
        check(name, samples=2000)


def test_the_job_writes_its_certificate(cli, tmp_path):
    preset = tmp_path / "s.toml"
    preset.write_text(
        "[robot3prr]\n\n[[path3prr]]\nfrom_pose = [40, 25, 30]\nto_pose = [40, 60, 30]\n"
        'steps = 10\nslider_modes = [1, 1, 1]\nkappa_max = 50\noutput = "s.csv"\n',
        encoding="utf-8",
    )
    result = cli("run", preset, "--out-dir", tmp_path / "out")
    assert result.exit_code == 0, result.output
    with open(tmp_path / "out" / "s-certificate.csv", newline="") as handle:
        (row,) = list(csv.DictReader(handle))
    assert row["certified"] == "no" and row["reason"] == "joint_limit"
    assert 0.405 < float(row["first_failure_hi_s"]) < 0.406

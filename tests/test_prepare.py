"""Parsing stays cheap enough for every keystroke of the app's form; the costly rest of
validation (the sensitivity's isotropic posture) runs in ``batch.prepare_jobs``, which the
CLI calls for every job before the first one runs."""

from __future__ import annotations

import time

import pytest

from planar_tui import batch
from planar_tui.errors import PresetError
from planar_tui.presets import parse_preset


def isotropic_document(n_links: int, lengths=None) -> dict:
    return {
        "robot": {
            "lengths_m": lengths or [0.1] * n_links,
            "masses_kg": [0.2] * n_links,
        },
        "sensitivity": {"posture": "isotropic", "methods": ["sobol"], "samples": 8},
    }


def test_parsing_a_250_link_isotropic_preset_solves_no_posture():
    """Parsing (every keystroke in the app) leaves the posture to prepare: well under a
    second (10x the 0.1 s goal; solving it takes seconds)."""
    document = isotropic_document(250)
    parse_preset("warm.toml", isotropic_document(3))  # imports done
    started = time.perf_counter()
    (job,) = parse_preset("big.toml", document).jobs
    assert time.perf_counter() - started < 1.0
    assert not hasattr(job, "prepared")  # solved on run, not per keystroke


def test_prepare_solves_the_posture_and_keeps_the_job():
    (job,) = parse_preset("p.toml", isotropic_document(2, [0.303, 0.214])).jobs
    (ready,) = batch.prepare_jobs([job])
    assert ready.prepared.posture.label == "isotropic"
    assert ready.prepared.posture.condition_number == pytest.approx(1.0, abs=2e-3)
    assert ready.job is job  # the job itself unchanged: settings hold preset keys only


def test_a_robot_without_isotropic_posture_fails_in_prepare_with_the_key():
    (job,) = parse_preset("p.toml", isotropic_document(2, [0.3, 0.3])).jobs
    with pytest.raises(PresetError) as caught:
        batch.prepare_jobs([job])
    assert str(caught.value).startswith(
        "error: p.toml: sensitivity.posture: robot has no isotropic posture: "
        "the minimum condition number is 1.61803 at theta = [0.00, 131.81] deg"
    )


SIMULATE_FIRST = """[robot]
lengths_m = [0.3, 0.3]
masses_kg = [1.0, 1.0]

[simulate]
duration_s = 0.01
step_s = 0.001
output = "first.csv"

[sensitivity]
posture = "isotropic"
methods = ["sobol"]
samples = 8
output = "second.csv"
"""


def test_the_cli_refuses_a_robot_without_isotropic_posture_before_any_job(tmp_path, cli):
    preset = tmp_path / "no-iso.toml"
    preset.write_text(SIMULATE_FIRST)
    result = cli("run", preset, "--out-dir", tmp_path / "out")
    assert result.exit_code == 2
    assert result.stderr.strip() == (
        f"error: {preset}: sensitivity.posture: robot has no isotropic posture: the minimum "
        "condition number is 1.61803 at theta = [0.00, 131.81] deg, above 1 + 0.01 "
        "(isotropy needs l2 = l1/√2) (expected a robot with an isotropic posture)"
    )
    assert not (tmp_path / "out").exists()  # not even the simulate job before it ran

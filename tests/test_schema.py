"""Each preset key is declared once: the declaration drives parsing, dumping, the allowed
keys and the preset reference (docs/reference/presets.md, tests/test_docs_reference.py)."""

from __future__ import annotations

import dataclasses

import pytest

from planar_tui.errors import PresetError
from planar_tui.presets import load_preset
from planar_tui.registry import JOB_KINDS, ROBOT_KINDS
from planar_tui.schema import TableReader, declared_keys, dump_settings, parse_settings
from tests.conftest import PRESETS


def test_every_setting_without_a_key_is_a_derived_value():
    """Settings hold preset keys only: what ``prepare`` resolves (a posture, a circle, a
    device) is the kind's prepared payload (:class:`planar_tui.jobkind.PreparedJob`), never
    a field of the settings."""
    for kind in JOB_KINDS.values():
        keys = dict(declared_keys(kind.settings))
        fields = [f.name for f in dataclasses.fields(kind.settings)]
        assert [name for name in fields if name not in keys] == [], kind.name


@pytest.mark.parametrize("preset_path", sorted(PRESETS.glob("*.toml")), ids=lambda p: p.stem)
def test_dump_then_parse_gives_the_same_settings(preset_path):
    preset = load_preset(preset_path)
    for job in preset.jobs:
        kind = JOB_KINDS[job.kind]
        table = dump_settings(job.spec)
        again = kind.parse(TableReader(preset_path, table, job.kind, kind.keys), job.robot)
        assert again == job.spec
    for name, robot in preset.robots.items():
        model = ROBOT_KINDS[name].model
        table = dump_settings(robot)
        assert (
            parse_settings(model, TableReader(preset_path, table, name, ROBOT_KINDS[name].keys))
            == robot
        )


def test_a_key_is_read_with_the_readers_message(tmp_path):
    path = tmp_path / "p.toml"
    path.write_text(
        "[robot]\nlengths_m = [1.0]\nmasses_kg = [1.0]\n[simulate]\n"
        "duration_s = 1.0\nstep_s = 0.1\nevery = 0\n",
        encoding="utf-8",
    )
    with pytest.raises(PresetError) as error:
        load_preset(path)
    assert str(error.value) == f"error: {path}: simulate.every: is 0 (expected an integer >= 1)"


def test_the_per_link_keys_come_from_the_declarations():
    """What follows the robot when it gains or loses a link (the app resizes these)."""
    from planar_tui.schema import per_link_keys

    expected = {
        "simulate": {"theta0_deg": "list", "omega0_deg_s": "list", "torques_Nm": "list"},
        "torques": {"theta_deg": "rows", "omega_deg_s": "rows", "alpha_deg_s2": "rows"},
        "sensitivity": {"posture": "list"},
        "workspace": {},
        "motion_uncertainty": {"theta0_deg": "list", "omega0_deg_s": "list", "torques_Nm": "list"},
    }
    assert {name: per_link_keys(JOB_KINDS[name].settings) for name in expected} == expected
    for kind in JOB_KINDS.values():  # a kind added later: its per-link keys are its keys
        assert set(per_link_keys(kind.settings)) <= set(kind.keys)

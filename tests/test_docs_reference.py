"""The preset reference page (docs/reference/presets.md) is generated from the keys'
declarations by docs/gen_reference.py: the committed page is that output, so a changed,
added or removed key fails here until the page is regenerated."""

from __future__ import annotations

import importlib.util

from planar_tui.registry import JOB_KINDS, ROBOT_KINDS
from planar_tui.schema import declared_keys
from tests.conftest import REPO


def generator():
    spec = importlib.util.spec_from_file_location(
        "gen_reference", REPO / "docs" / "gen_reference.py"
    )
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_committed_reference_is_the_generated_one():
    gen = generator()
    committed = (REPO / "docs" / "reference" / "presets.md").read_text(encoding="utf-8")
    assert committed == gen.generate(), "stale: run `python docs/gen_reference.py`"


def test_every_declared_key_of_every_registered_kind_has_a_row():
    page = (REPO / "docs" / "reference" / "presets.md").read_text(encoding="utf-8")
    sections = page.split("\n### ")
    classes = {name: kind.model for name, kind in ROBOT_KINDS.items()}
    classes |= {name: kind.settings for name, kind in JOB_KINDS.items()}
    for name, settings in classes.items():
        section = next(s for s in sections if s.startswith(f"{name}\n"))
        for _, key in declared_keys(settings):
            assert f"\n| `{key.name}` | {key.type_doc} |" in section, (name, key.name)


def test_units_and_allowed_values_come_from_the_names_and_the_readers():
    gen = generator()
    assert [gen.unit(n) for n in ("omega0_deg_s", "gravity_m_s2", "precision_cm", "form")] == [
        "deg/s",
        "m/s²",
        "cm",
        "—",
    ]
    keys = dict(declared_keys(JOB_KINDS["workspace"].settings))
    assert gen.allowed(keys["strategy"]) == "`legwise`, `joint`"
    assert gen.allowed(keys["precision_cm"]) == "> 0"
    robot_keys = dict(declared_keys(ROBOT_KINDS["robot"].model))
    assert gen.allowed(robot_keys["masses_kg"]).endswith("as many as `lengths_m`")

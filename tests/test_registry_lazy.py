"""The kind registries (:mod:`planar_tui.registry`): one line per kind, each kind's module
imported when the kind is first looked up."""

import pytest

from planar_tui.jobkind import JobKind, RobotKind
from planar_tui.registry import JOB_KINDS, ROBOT_KINDS, Registry


def test_every_line_names_the_module_declaring_that_kind():
    for name in JOB_KINDS:
        kind = JOB_KINDS[name]
        assert isinstance(kind, JobKind) and kind.name == name
        assert kind.robot_kind in ROBOT_KINDS
    for name in ROBOT_KINDS:
        assert isinstance(ROBOT_KINDS[name], RobotKind) and ROBOT_KINDS[name].name == name
    assert [kind.name for kind in JOB_KINDS.values()] == list(JOB_KINDS)


def test_a_line_naming_the_wrong_module_is_refused():
    wrong = Registry("JOB_KIND", {"simulate": "planar_tui.dynamics.torques"})
    assert "simulate" in wrong and list(wrong) == ["simulate"]  # names: no import needed
    with pytest.raises(RuntimeError, match="named 'torques', not 'simulate'"):
        wrong["simulate"]
    with pytest.raises(KeyError):
        wrong["nothing"]
    assert wrong.get("nothing") is None


def test_names_are_listed_without_importing_and_lookups_are_kept():
    registry = Registry("JOB_KIND", {"torques": "planar_tui.dynamics.torques"})
    assert registry.loaded() == () and len(registry) == 1
    first = registry["torques"]
    assert registry.loaded() == ("torques",) and registry["torques"] is first

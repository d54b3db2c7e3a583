"""The README's recipe for a new parallel robot names real files: for every
robot of the workspace, its subpackage (``__init__.py``, ``robot.py``, ``mechanism.py``,
``job.py``), its kernel in ``kernels/``, its registry lines, its entry in the packages list
and in the import contract that keeps the robots independent, and its app pane; the core
names none of them (``tests/test_new_mechanism.py`` follows the recipe in one file)."""

from __future__ import annotations

import tomllib

import pytest

from planar_tui.registry import JOB_KINDS, ROBOT_KINDS
from tests.conftest import REPO

#: Per robot subpackage: its job kind, robot kind and level kernel's module (``kernels/``).
ROBOTS = {
    "rrr": ("workspace", "robot3rrr", "workspace_arc"),
    "rpr": ("workspace3rpr", "robot3rpr", "workspace3rpr"),
    "prr": ("workspace3prr", "robot3prr", "workspace3prr"),
    "fivebar": ("workspace5r", "robot5r", "workspace5r"),
}
#: The files of a robot's subpackage the recipe names.
SUBPACKAGE_FILES = ("__init__.py", "robot.py", "mechanism.py", "job.py")


def pyproject() -> dict:
    with open(REPO / "pyproject.toml", "rb") as stream:
        return tomllib.load(stream)


@pytest.mark.parametrize("robot", sorted(ROBOTS))
def test_the_recipe_names_each_robots_files(robot):
    job_kind, robot_kind, kernel = ROBOTS[robot]
    package = REPO / "planar_tui" / "workspace" / robot
    for name in SUBPACKAGE_FILES:
        assert (package / name).is_file(), f"{robot}: no {name}"
    assert (REPO / "kernels" / f"{kernel}.py").is_file()
    module = f"planar_tui.workspace.{robot}"
    assert JOB_KINDS._modules[job_kind] == f"{module}.job"
    assert ROBOT_KINDS._modules[robot_kind] == f"{module}.robot"
    assert module in pyproject()["tool"]["setuptools"]["packages"]
    contracts = pyproject()["tool"]["importlinter"]["contracts"]
    independent = [c for c in contracts if c["type"] == "independence"]
    assert any(module in contract["modules"] for contract in independent)


@pytest.mark.parametrize("robot", sorted(ROBOTS))
def test_each_robot_provides_its_mechanism_and_its_tab(robot):
    from planar_tui.workspace.paving.mechanism import Mechanism

    job_kind = JOB_KINDS[ROBOTS[robot][0]]
    mechanism = job_kind.settings.mechanism
    assert isinstance(mechanism, Mechanism)
    assert type(mechanism).__module__ == f"planar_tui.workspace.{robot}.mechanism"
    assert job_kind.tab is not None


def test_the_core_names_no_robot():
    core = REPO / "planar_tui" / "workspace" / "paving"
    for path in core.glob("*.py"):
        lines = path.read_text(encoding="utf-8").splitlines()
        code = [line for line in lines if line.lstrip().startswith(("import ", "from "))]
        for robot in ROBOTS:
            assert not any(f"planar_tui.workspace.{robot}" in line for line in code), path

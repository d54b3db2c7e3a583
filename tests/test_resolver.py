"""One resolver for the ``"module:attr"`` strings: every string a registered kind
declares (its registry line, its tab's pane, its figure function) resolves to what it
names, and ``import_module`` is called in at most two files of the package (the resolver,
and the runtime's warm-up of numba's own modules)."""

from __future__ import annotations

import inspect

import pytest

from planar_tui.jobkind import JobKind, RobotKind, resolve
from planar_tui.registry import JOB_KINDS, ROBOT_KINDS
from tests.conftest import REPO


def declared_strings() -> list[tuple[str, str, str]]:
    """``(kind, what, path)`` of every import path the registered kinds declare."""
    found = []
    for registry, attribute in ((JOB_KINDS, "JOB_KIND"), (ROBOT_KINDS, "ROBOT_KIND")):
        for name, module in registry._modules.items():
            if module is not None:
                found.append((name, "registry line", f"{module}:{attribute}"))
    for name in JOB_KINDS:
        kind = JOB_KINDS[name]
        if kind.tab is not None and kind.tab.pane is not None:
            found.append((name, "tab pane", kind.tab.pane))
        if kind.figure is not None:
            found.append((name, "figure", kind.figure))
    return found


def test_every_kind_declares_strings_to_resolve():
    whats = {what for _, what, _ in declared_strings()}
    assert whats == {"registry line", "tab pane", "figure"}
    assert len(declared_strings()) >= len(JOB_KINDS) + len(ROBOT_KINDS) + 8


@pytest.mark.parametrize(("kind", "what", "path"), declared_strings())
def test_every_declared_string_resolves(kind, what, path):
    found = resolve(path)
    if what == "registry line":
        assert isinstance(found, JobKind | RobotKind) and found.name == kind
    elif what == "tab pane":
        assert inspect.isclass(found) and found.__name__ == path.rsplit(":", 1)[1]
    else:
        assert callable(found)


def test_a_module_path_resolves_to_the_module_and_a_wrong_one_raises():
    import planar_tui.figures.workspace as module

    assert resolve("planar_tui.figures.workspace") is module
    with pytest.raises(AttributeError):
        resolve("planar_tui.figures.workspace:no_such_function")
    with pytest.raises(ImportError):
        resolve("planar_tui.no_such_module:anything")


def test_import_module_is_called_in_at_most_two_files():
    calling = sorted(
        path.relative_to(REPO).as_posix()
        for path in (REPO / "planar_tui").rglob("*.py")
        if "import_module(" in path.read_text(encoding="utf-8")
    )
    assert calling == ["planar_tui/jobkind.py", "planar_tui/runtime.py"]

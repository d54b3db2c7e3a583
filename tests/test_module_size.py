"""No module of the package is over 500 lines, the package being ``planar_tui/`` and the
kernels (``kernels/``, installed as ``planar_tui.kernels``): a module that grows past it
is split by responsibility."""

from __future__ import annotations

from tests.conftest import REPO

#: The rule's bound, in lines.
MAX_LINES = 500


def module_lines() -> dict[str, int]:
    """Lines of every ``.py`` file under ``planar_tui/`` and ``kernels/``, by path."""
    files = [*(REPO / "planar_tui").rglob("*.py"), *(REPO / "kernels").rglob("*.py")]
    return {
        path.relative_to(REPO).as_posix(): len(path.read_text(encoding="utf-8").splitlines())
        for path in files
    }


def test_the_package_and_the_kernels_have_modules_to_count():
    lines = module_lines()
    assert "planar_tui/interop/robot_import.py" in lines
    assert "kernels/dynamics.py" in lines


def test_no_module_is_over_500_lines():
    over = {path: count for path, count in module_lines().items() if count > MAX_LINES}
    assert not over, f"modules over {MAX_LINES} lines (split them by responsibility): {over}"

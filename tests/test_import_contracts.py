"""The layers are enforced: import-linter's contracts (pyproject.toml) hold, they fail on a
violation, and no module of the package takes part in an import cycle."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tomllib

import pytest

from tests.installed_layout import REPO, installed_layout, lint_imports

pytestmark = pytest.mark.slow  # lint-imports in subprocesses


def test_every_import_contract_is_kept(tmp_path):
    result = lint_imports(installed_layout(tmp_path))
    assert result.returncode == 0, result.stdout + result.stderr
    assert "0 broken" in result.stdout


def test_the_checkout_command_checks_every_contract():
    """``python -m tests.installed_layout`` (run by .ci/run in the editable checkout, where
    a bare ``lint-imports`` cannot find ``planar_tui.kernels``) checks every contract of
    pyproject.toml and keeps them all."""
    result = subprocess.run(
        [sys.executable, "-m", "tests.installed_layout"],
        capture_output=True,
        text=True,
        cwd=REPO,
        timeout=180,
    )
    assert result.returncode == 0, result.stdout + result.stderr
    with open(REPO / "pyproject.toml", "rb") as stream:
        contracts = tomllib.load(stream)["tool"]["importlinter"]["contracts"]
    assert f"Contracts: {len(contracts)} kept, 0 broken." in result.stdout
    assert result.stdout.count(" KEPT") == len(contracts)


def test_a_kernel_importing_the_package_above_breaks_the_contracts(tmp_path):
    root = installed_layout(tmp_path)
    kernel = root / "planar_tui" / "kernels" / "rk4.py"
    kernel.write_text(kernel.read_text() + "\nfrom planar_tui.batch import run_job\n")
    result = lint_imports(root)
    assert result.returncode == 1
    assert "planar_tui.kernels.rk4 -> planar_tui.batch" in result.stdout


def test_the_core_importing_textual_breaks_the_contracts(tmp_path):
    root = installed_layout(tmp_path)
    module = root / "planar_tui" / "csvio.py"
    module.write_text(module.read_text() + "\nimport textual\n")
    result = lint_imports(root)
    assert result.returncode == 1
    assert "planar_tui.csvio -> textual" in result.stdout


def test_no_module_is_part_of_an_import_cycle(tmp_path):
    """Module-level cycles (imports inside functions included) through grimp's graph."""
    code = (
        "import grimp, json\n"
        "graph = grimp.build_graph('planar_tui')\n"
        "edges = {m: sorted(graph.find_modules_directly_imported_by(m)) for m in graph.modules}\n"
        "print(json.dumps(edges))\n"
    )
    root = installed_layout(tmp_path)
    env = dict(os.environ, PYTHONPATH=str(root))
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True
    )
    edges = json.loads(out.stdout)
    cycles = []
    state: dict[str, int] = {}  # 1 = on the stack, 2 = done

    def visit(module: str, stack: list[str]) -> None:
        state[module] = 1
        stack.append(module)
        for imported in edges.get(module, []):
            if state.get(imported) == 1:
                cycles.append([*stack[stack.index(imported) :], imported])
            elif imported not in state:
                visit(imported, stack)
        stack.pop()
        state[module] = 2

    for module in sorted(edges):
        if module not in state:
            visit(module, [])
    assert cycles == [], "\n".join(" -> ".join(cycle) for cycle in cycles)

"""The package as a wheel installs it, laid out from the repository's folders, and the
import contracts checked on it.

The repository keeps the kernels in ``kernels/`` and the presets in ``presets/``; setuptools
installs them as ``planar_tui.kernels`` and ``planar_tui.bundled_presets`` (pyproject's
package-dir mapping). Tools that read the package from disk (import-linter's graph) need
that installed layout, which :func:`installed_layout` copies into a folder; a bare
``lint-imports`` in an editable checkout stops at ``planar_tui.kernels does not exist``.

``python -m tests.installed_layout`` runs ``lint-imports`` with the repository's contracts
on the checkout laid out so (what ``.ci/run`` and docs/development.md run);
its exit code is lint-imports'.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
import tomllib
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
#: ``lint-imports`` run by this interpreter (the console script may not sit beside it).
LINT_IMPORTS = (
    "import sys; from importlinter.cli import lint_imports_command; "
    "sys.argv[0] = 'lint-imports'; lint_imports_command()"
)


def mapped_folders() -> dict[str, str]:
    """Package folder -> repository folder: ``planar_tui`` itself and pyproject's
    ``[tool.setuptools.package-dir]`` (``planar_tui/kernels`` -> ``kernels``)."""
    with open(REPO / "pyproject.toml", "rb") as stream:
        package_dir = tomllib.load(stream)["tool"]["setuptools"]["package-dir"]
    return {"planar_tui": "planar_tui"} | {
        package.replace(".", "/"): folder for package, folder in package_dir.items()
    }


def installed_layout(target: Path) -> Path:
    """Copy the package into ``target`` as it is installed; returns ``target``."""
    ignore = shutil.ignore_patterns("__pycache__", "*.pyc")
    for package, folder in mapped_folders().items():
        shutil.copytree(REPO / folder, target / package, ignore=ignore, dirs_exist_ok=True)
    return target


def lint_imports(root: Path) -> subprocess.CompletedProcess[str]:
    """``lint-imports`` with the repository's contracts on the package under ``root``
    (nothing else of the repository on the path)."""
    env = dict(os.environ, PYTHONPATH=str(root))
    return subprocess.run(
        [
            sys.executable,
            "-c",
            LINT_IMPORTS,
            "--config",
            str(REPO / "pyproject.toml"),
            "--no-cache",
        ],
        capture_output=True,
        text=True,
        env=env,
        cwd=root,
        timeout=120,
    )


def main() -> int:
    """Check the contracts on the checkout (laid out as installed); print lint-imports'
    report; return its exit code."""
    with tempfile.TemporaryDirectory(prefix="planar-tui-layout-") as folder:
        result = lint_imports(installed_layout(Path(folder)))
    sys.stdout.write(result.stdout)
    sys.stderr.write(result.stderr)
    return result.returncode


if __name__ == "__main__":
    sys.exit(main())

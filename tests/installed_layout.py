"""The package as a wheel installs it, laid out from the repository's folders.

The repository keeps the kernels in ``kernels/`` and the presets in ``presets/``; setuptools
installs them as ``planar_tui.kernels`` and ``planar_tui.bundled_presets`` (pyproject's
package-dir mapping). Tools that read the package from disk (import-linter's graph) need
that installed layout, which :func:`installed_layout` copies into a folder.
"""

from __future__ import annotations

import shutil
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent

#: Package name -> repository folder, as in pyproject.toml's [tool.setuptools.package-dir].
MAPPED = {"planar_tui": "planar_tui", "planar_tui/kernels": "kernels",
          "planar_tui/bundled_presets": "presets"}  # fmt: skip


def installed_layout(target: Path) -> Path:
    """Copy the package into ``target`` as it is installed; returns ``target``."""
    ignore = shutil.ignore_patterns("__pycache__", "*.pyc")
    for package, folder in MAPPED.items():
        shutil.copytree(REPO / folder, target / package, ignore=ignore, dirs_exist_ok=True)
    return target

"""The wheel is the product: it holds the kernels under the project's namespace, the bundled
presets and the app's stylesheet, and nothing named ``kernels`` or ``presets`` at the top of
site-packages. (``.ci/run`` also installs it into a fresh virtual environment and runs the
CLI and the app from there.)"""

from __future__ import annotations

import shutil
import subprocess
import sys
import zipfile

import pytest

from tests.installed_layout import REPO, mapped_folders

pytestmark = pytest.mark.slow  # end to end (see pyproject.toml's markers)


@pytest.fixture(scope="module")
def wheel_names(tmp_path_factory) -> set[str]:
    source = tmp_path_factory.mktemp("source")
    ignore = shutil.ignore_patterns(
        ".git", ".venv", "build", "dist", "*.egg-info", "__pycache__", ".*_cache", "out"
    )
    shutil.copytree(REPO, source, ignore=ignore, dirs_exist_ok=True)
    wheels = tmp_path_factory.mktemp("wheels")
    subprocess.run(
        [
            sys.executable,
            "-m",
            "pip",
            "wheel",
            "--no-deps",
            "--no-build-isolation",
            "--quiet",
            "--wheel-dir",
            str(wheels),
            str(source),
        ],
        check=True,
        capture_output=True,
        timeout=300,
    )
    (wheel,) = wheels.glob("planar_tui-*.whl")
    with zipfile.ZipFile(wheel) as archive:
        return set(archive.namelist())


def test_only_the_project_namespace_is_installed(wheel_names):
    tops = {name.split("/", 1)[0] for name in wheel_names}
    assert {t for t in tops if not t.endswith(".dist-info")} == {"planar_tui"}


def test_every_source_module_and_data_file_is_in_the_wheel(wheel_names):
    expected = set()
    for package, folder in mapped_folders().items():
        for path in (REPO / folder).rglob("*"):
            if path.suffix in (".py", ".toml", ".tcss") and "__pycache__" not in path.parts:
                expected.add(f"{package}/{path.relative_to(REPO / folder).as_posix()}")
    assert expected - wheel_names == set()
    assert "planar_tui/kernels/dynamics.py" in wheel_names
    assert "planar_tui/bundled_presets/paper-b-table5.toml" in wheel_names
    assert "planar_tui/app/app.tcss" in wheel_names

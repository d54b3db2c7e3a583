"""Shared by the sensitivity tests: every test gets its own empty design-cache folder.

Import the fixture into a test module (``from tests.sensitivity_support import
isolated_design_cache``) and it applies to every test there (autouse), so no test reads
or writes the user's cache (``~/.cache/planar-tui``) and none passes thanks to an entry a
previous run left.
"""

import pytest


@pytest.fixture(autouse=True)
def isolated_design_cache(tmp_path_factory, monkeypatch):
    """``PLANAR_TUI_CACHE_DIR`` set to a fresh temporary folder; returns it."""
    folder = tmp_path_factory.mktemp("design-cache")
    monkeypatch.setenv("PLANAR_TUI_CACHE_DIR", str(folder))
    return folder

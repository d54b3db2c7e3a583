"""The Textual workbench (imported only when the app opens, never by batch commands)."""

from __future__ import annotations

import os
import sys
from typing import Any

from planar_tui.errors import PresetError
from planar_tui.runtime import configure_process


def last_preset() -> str | None:
    """The preset last opened or saved in the app (:mod:`planar_tui.app.settings`) when
    it is still a file; ``None`` (the bundled default) otherwise."""
    from pathlib import Path

    from planar_tui.app.settings import load_settings

    path = load_settings()[0].last_preset
    return path if path is not None and Path(path).is_file() else None


def _open_bench(workbench: Any, preset_argument: str | None) -> Any:
    """The app's workbench on ``preset_argument``, else on :func:`last_preset`; a
    remembered preset that cannot be read says it came from the settings file."""
    from planar_tui.app.settings import settings_path

    remembered = None if preset_argument else last_preset()
    try:
        return workbench.open_marked(preset_argument or remembered)
    except PresetError as error:
        if remembered is None:
            raise
        where = f"the last preset opened, remembered in {settings_path()}; pass a preset to open"
        raise PresetError(
            error.path, error.key, f"{error.problem} ({where})", error.expected
        ) from None


def run_app(preset_argument: str | None = None, opened: tuple[str, ...] = ()) -> None:
    """Open the workbench on a preset path or bundled name (default: the preset last
    opened or saved, see :func:`last_preset`, else a bundled preset).

    A preset whose values are wrong opens with its problems marked on the tabs (a table
    that is no table as an empty one, :meth:`Workbench.open_marked`); one that cannot be
    read or is no TOML raises the CLI's :class:`~planar_tui.errors.PresetError` before the
    terminal is taken over, so the CLI prints its one-line error and exits with 2 (saying
    so when the preset was the remembered one, :func:`_open_bench`); so does
    a result CSV of ``opened`` (``planar-tui tui --open``) that cannot be read. Those open
    into the run history, which the app shows first.

    The process is set up first, as every front end sets it up
    (:func:`planar_tui.runtime.configure_process`); the app compiles the kernels not yet
    cached in a background thread while the user edits (first run only). Once the app has closed (terminal
    restored, no job thread left: quitting cancels a running job first) the process ends
    with ``os._exit``: tearing down the numerical modules took 0.5-0.8 s after a job,
    which made ``q`` feel slow. Nothing is pending by then (files are written atomically
    when a job or a save finishes).
    """
    configure_process()
    from planar_tui.app.app import WorkbenchApp
    from planar_tui.app.workbench import Workbench

    app = WorkbenchApp(
        _open_bench(Workbench, preset_argument), warm_kernels=True, first_job_tab=True
    )
    app.open_results(list(opened))
    app.run()
    code = app.return_code or 0
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)

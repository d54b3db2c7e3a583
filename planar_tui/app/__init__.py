"""The Textual workbench (imported only when the app opens, never by batch commands)."""

from __future__ import annotations


def run_app(preset_argument: str | None = None) -> None:
    """Open the workbench on a preset path or bundled name (default: a bundled preset).

    A bad preset raises the CLI's :class:`~planar_tui.errors.PresetError` before the
    terminal is taken over, so the CLI prints its one-line error and exits with 2.
    """
    from planar_tui.app.app import WorkbenchApp
    from planar_tui.app.workbench import Workbench

    WorkbenchApp(Workbench.open(preset_argument)).run()

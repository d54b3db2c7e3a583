"""The command palette's entries (``ctrl+p``): every action of the workbench by name,
with its key."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

from textual.app import SystemCommand

from planar_tui.registry import JOB_KINDS


def workbench_commands(app: Any) -> Iterator[SystemCommand]:
    """The workbench's commands (after Textual's own: theme, keys, quit …)."""
    yield SystemCommand("Run job", "Run the job of the current tab (F5)", app.action_run)
    yield SystemCommand("Cancel job", "Stop the running job (escape)", app.action_cancel)
    yield SystemCommand(
        "Run all jobs",
        "Every job of the preset in order, files into a folder, as planar-tui run (F9)",
        app.action_run_all,
    )
    yield SystemCommand(
        "Run as sweep",
        "Vary keys of the current tab's job over values, one row per point (F8)",
        app.action_sweep,
    )
    yield SystemCommand(
        "Show sweep result", "The latest sweep's table and plot", app.action_show_sweep
    )
    yield SystemCommand(
        "Run optimisation",
        "The preset's [[optimise]] table of the current tab's job, generation by generation",
        app.action_optimise,
    )
    yield SystemCommand(
        "Show optimisation",
        "The latest optimisation's evaluations and plot",
        app.action_show_optimisation,
    )
    yield SystemCommand(
        "Go to error", "Jump to the first problem's field (ctrl+g)", app.action_goto_problem
    )
    yield SystemCommand(
        "Run history", "Every run, compare two, open a CSV (F10)", app.action_history
    )
    yield SystemCommand("Open preset", "Open a TOML preset (ctrl+o)", app.action_open)
    yield SystemCommand("Save preset", "Save the preset as TOML (ctrl+s)", app.action_save)
    yield SystemCommand("Save as", "Save the preset under another path", app.action_save_as)
    yield SystemCommand("Undo", "Undo the latest edit (ctrl+z)", app.action_undo)
    yield SystemCommand(
        "Export CSV",
        "Write the result's CSV files into a folder, as planar-tui run (ctrl+e)",
        app.action_export,
    )
    yield SystemCommand(
        "Write figure",
        "Draw the result as a figure beside the CSV Export writes (ctrl+l)",
        app.action_figure,
    )
    yield SystemCommand("Help", "Key bindings (F1)", app.action_help)
    yield SystemCommand(
        "Toggle form", "Hide/show the settings form (ctrl+f)", app.action_toggle_form
    )
    yield SystemCommand(
        "Maximise",
        "Maximise the focused plot or table, or the results (ctrl+b)",
        app.action_maximise,
    )
    for title, name in app.tabs():
        yield SystemCommand(
            f"Show {title} tab",
            f"Switch to the {title} tab",
            lambda n=name: app.action_show_tab(n),
        )
    yield SystemCommand(
        "Add link", "Robot tab: add a link (ctrl+n)", lambda: app.action_pane("robot.add_link")
    )
    yield SystemCommand(
        "Remove link",
        "Robot tab: remove the last link (ctrl+r)",
        lambda: app.action_pane("robot.remove_link"),
    )
    for title, name in app.tabs():
        tab = JOB_KINDS[name].tab if name in JOB_KINDS else None
        if tab is not None and tab.view:
            yield SystemCommand(
                f"{title} view",
                f"{title} tab: {tab.view_help} (ctrl+t)",
                lambda n=name: app.action_pane(f"{n}.toggle_view"),
            )

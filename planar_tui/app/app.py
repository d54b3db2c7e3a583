"""The Textual workbench: four tabs over one preset, jobs run by the batch service.

Jobs run in :class:`~planar_tui.app.job_runner.JobRunner` (a thread worker around
:func:`planar_tui.batch.run_job`, as the CLI runs them); a UI timer shows the runner's
latest progress snapshot every :data:`REFRESH_S` seconds; escape cancels at the runner's
next chunk. The tabs post :mod:`~planar_tui.app.messages` (an edit, Run, Cancel) that the
app handles here; outcomes come back as
:class:`~planar_tui.app.job_runner.JobFinished`; errors open a dialog, never a traceback.
Export names and writes files as ``planar-tui run --out-dir DIR`` does
(:func:`planar_tui.batch.plan_outputs`, :func:`planar_tui.batch.write_result`).
"""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path
from typing import Any, ClassVar

from textual.app import App, ComposeResult, SystemCommand
from textual.binding import Binding
from textual.screen import Screen
from textual.widgets import Footer, Static, TabbedContent, TabPane

from planar_tui.app.file_actions import FileActions
from planar_tui.app.job_runner import JobFinished, JobRunner
from planar_tui.app.messages import CancelRequested, DocumentEdited, RunRequested
from planar_tui.app.screens.dialogs import HelpScreen, MessageDialog
from planar_tui.app.widgets.panes import JobPane, RobotPane
from planar_tui.app.workbench import Workbench
from planar_tui.errors import PresetError

__all__ = ["REFRESH_S", "JobFinished", "WorkbenchApp"]

#: Seconds between two progress refreshes on screen (10 per second).
REFRESH_S = 0.1


class WorkbenchApp(FileActions, App):
    """planar-tui's terminal workbench (open, save, export, undo and quit in
    :class:`~planar_tui.app.file_actions.FileActions`)."""

    CSS_PATH = Path(__file__).with_name("app.tcss")  # absolute: subclasses elsewhere find it
    TITLE = "planar-tui"
    BINDINGS: ClassVar = [
        Binding("q", "quit", "Quit"),
        Binding("f1,question_mark", "help", "Help", key_display="F1"),
        Binding("f5", "run", "Run", key_display="F5"),
        Binding("escape", "cancel", "Cancel"),
        Binding("ctrl+o", "open", "Open", priority=True),
        Binding("ctrl+s", "save", "Save", priority=True),
        Binding("ctrl+z", "undo", "Undo", priority=True, show=False),
        Binding("ctrl+e", "export", "Export", priority=True),
        Binding("ctrl+f", "toggle_form", "Form", priority=True),
        Binding("ctrl+n", "pane_action('add_link')", "Add link", priority=True),
        Binding("ctrl+r", "pane_action('remove_link')", "Del link", priority=True),
        Binding("ctrl+t", "pane_action('toggle_view')", "S1/ST/%", priority=True),
    ]
    TABS = (
        ("Robot", "robot"),
        ("Sensitivity", "sensitivity"),
        ("Workspace", "workspace"),
        ("Simulate", "simulate"),
    )

    def __init__(self, workbench: Workbench, output_dir: Path | str = "."):
        super().__init__()
        self.workbench = workbench
        #: The folder ``ctrl+e`` offers (``planar-tui run --out-dir``'s default is ``.``).
        self.output_dir = Path(output_dir)
        self.jobs = JobRunner(self)

    # -- layout ---------------------------------------------------------------------
    @staticmethod
    def pane_classes() -> dict[str, type]:
        """The dedicated pane of each tab; a job kind without one gets :class:`JobPane`."""
        from planar_tui.app.widgets.sensitivity_pane import SensitivityPane
        from planar_tui.app.widgets.simulate_pane import SimulatePane
        from planar_tui.app.widgets.workspace_pane import WorkspacePane

        return {
            "robot": RobotPane,
            "sensitivity": SensitivityPane,
            "workspace": WorkspacePane,
            "simulate": SimulatePane,
        }

    def compose(self) -> ComposeResult:
        panes = self.pane_classes()
        with TabbedContent(id="tabs"):
            for title, name in self.TABS:
                with TabPane(title, id=f"tab-{name}"):
                    pane = panes.get(name)
                    if pane is None:
                        yield JobPane(self.workbench, kind=name, id=f"pane-{name}")
                    else:
                        yield pane(self.workbench, id=f"pane-{name}")
        yield Static("", id="validation", markup=False)
        yield Footer(compact=True)

    def on_mount(self) -> None:
        self.show_document_state()
        self.set_interval(REFRESH_S, self._refresh_progress)
        self.revalidate()

    # -- state helpers --------------------------------------------------------------
    @property
    def job_running(self) -> bool:
        """Whether a runner thread is still working."""
        return self.jobs.running

    def current_pane(self) -> Any:
        tabs = self.query_one(TabbedContent)
        name = (tabs.active or "tab-robot").removeprefix("tab-")
        return self.query_one(f"#pane-{name}")

    async def on_document_edited(self, message: DocumentEdited) -> None:
        """A tab edited the preset: check it again (and mark it modified)."""
        self.revalidate()
        await self.after_edit()

    def revalidate(self) -> bool:
        """Check the whole document with the CLI's parser; show the first problem."""
        bar = self.query_one("#validation", Static)
        try:
            preset = self.workbench.validate()
        except PresetError as error:
            bar.update(str(error))
            bar.set_class(True, "invalid")
            return False
        count = len(preset.jobs)
        bar.update(f"ok: {self.document_label()}, {count} job{'s' if count != 1 else ''} valid")
        bar.set_class(False, "invalid")
        return True

    # -- running jobs ---------------------------------------------------------------
    def action_run(self) -> None:
        """Run the job of the current tab."""
        self.run_pane_job(self.current_pane())

    def on_run_requested(self, message: RunRequested) -> None:
        """A tab's Run button."""
        self.run_pane_job(message.pane)

    def run_pane_job(self, pane: Any) -> None:
        """Run the job of ``pane`` (a job tab) in the job runner."""
        if not isinstance(pane, JobPane) or not pane.available():
            self.notify("This tab has no job to run: choose Sensitivity, Workspace or Simulate.")
            return
        if self.job_running:
            self.notify("A job is already running (escape cancels it).", severity="warning")
            return
        try:
            job = pane.current_job()
        except PresetError as error:
            self.revalidate()
            self.push_screen(MessageDialog("Invalid preset", str(error)))
            return
        self.revalidate()
        pane.controls().set_running(True)
        pane.controls().status(f"starting {job.label}")
        self.jobs.start(pane, job)
        self.refresh_bindings()

    def _refresh_progress(self) -> None:
        """The UI timer: show the running job's latest progress snapshot."""
        if len(self.screen_stack) > 1:
            return  # a dialog is up: redrawing the screen behind it would only slow it down
        state, pane = self.jobs.latest, self.jobs.pane
        if pane is not None and state is not None and self.job_running:
            pane.show_progress(state)

    def action_cancel(self) -> None:
        """Ask the running job to stop (the runner stops at its next chunk)."""
        if self.jobs.cancel() and self.jobs.pane is not None:
            self.jobs.pane.controls().status("cancelling…")

    def on_cancel_requested(self, message: CancelRequested) -> None:
        """A tab's Cancel button."""
        self.action_cancel()

    def on_unmount(self) -> None:
        """Closing: stop a job still running (its thread must not outlive the app)."""
        self.jobs.cancel()

    def on_job_finished(self, message: JobFinished) -> None:
        """Show a job's outcome on its tab (a dialog for an error)."""
        pane = message.pane
        if not pane.is_attached:
            return
        self.refresh_bindings()
        controls = pane.controls()
        controls.set_running(False)
        if message.cancelled:
            controls.status(f"cancelled after {message.seconds:.2f} s; nothing written")
            self.notify("Job cancelled.")
        elif message.error is not None:
            controls.status("failed")
            error = message.error
            text = (
                str(error) if isinstance(error, PresetError) else f"{type(error).__name__}: {error}"
            )
            self.push_screen(MessageDialog(f"{message.job.label} failed", text))
        else:
            controls.finished()
            controls.status(f"done in {message.seconds:.2f} s")
            pane.show_result(message.job, message.result)

    # -- the screen as text -----------------------------------------------------------
    def export_text(self) -> str:
        """The screen as plain text (for tests, docs and text screenshots), read back from
        Textual's public SVG screenshot (see :mod:`planar_tui.app.screen_text`)."""
        from planar_tui.app.screen_text import svg_screen_text

        width, height = self.size
        return svg_screen_text(self.export_screenshot(), width, height)

    # -- quitting, help, command palette --------------------------------------------
    def action_help(self) -> None:
        """Show the key bindings."""
        if not isinstance(self.screen, HelpScreen):
            self.push_screen(HelpScreen())

    def action_show_tab(self, name: str) -> None:
        """Switch to a tab by name."""
        self.query_one(TabbedContent).active = f"tab-{name}"

    def action_pane(self, action: str) -> None:
        """Switch to a tab and run its own action (for the command palette)."""
        pane_name, method = action.split(".")
        self.action_show_tab(pane_name)
        self.call_later(self.action_pane_action, method)

    def check_action(self, action: str, parameters: tuple[object, ...]) -> bool | None:
        """Show a tab's own bindings only on that tab."""
        if action == "pane_action" and self.is_mounted:
            try:
                pane = self.current_pane()
            except Exception:
                return False
            return hasattr(pane, f"action_{parameters[0]}")
        if action == "cancel":
            return self.job_running
        if action in ("toggle_form", "run") and self.is_mounted:
            try:
                return isinstance(self.current_pane(), JobPane)
            except Exception:
                return False
        return True

    def on_tabbed_content_tab_activated(self) -> None:
        self.refresh_bindings()

    async def action_pane_action(self, method: str) -> None:
        """Run the current tab's own action (add/remove link, sensitivity view)."""
        pane = self.current_pane()
        if hasattr(pane, f"action_{method}"):
            await self.run_action(method, pane)

    def action_toggle_form(self) -> None:
        """Hide or show the settings form of a job tab (more room for results)."""
        self.query_one("#tabs").toggle_class("hide-form")
        for pane in self.query(JobPane):
            self.call_after_refresh(pane.rerender)

    def get_system_commands(self, screen: Screen) -> Iterable[SystemCommand]:
        yield from super().get_system_commands(screen)
        yield SystemCommand("Run job", "Run the job of the current tab (F5)", self.action_run)
        yield SystemCommand("Cancel job", "Stop the running job (escape)", self.action_cancel)
        yield SystemCommand("Open preset", "Open a TOML preset (ctrl+o)", self.action_open)
        yield SystemCommand("Save preset", "Save the preset as TOML (ctrl+s)", self.action_save)
        yield SystemCommand("Save as", "Save the preset under another path", self.action_save_as)
        yield SystemCommand("Undo", "Undo the latest edit (ctrl+z)", self.action_undo)
        yield SystemCommand(
            "Export CSV",
            "Write the result's CSV files into a folder, as planar-tui run (ctrl+e)",
            self.action_export,
        )
        yield SystemCommand("Help", "Key bindings (F1)", self.action_help)
        yield SystemCommand(
            "Toggle form", "Hide/show the settings form (ctrl+f)", self.action_toggle_form
        )
        for title, name in self.TABS:
            yield SystemCommand(
                f"Show {title} tab",
                f"Switch to the {title} tab",
                lambda n=name: self.action_show_tab(n),
            )
        yield SystemCommand(
            "Add link", "Robot tab: add a link (ctrl+n)", lambda: self.action_pane("robot.add_link")
        )
        yield SystemCommand(
            "Remove link",
            "Robot tab: remove the last link (ctrl+r)",
            lambda: self.action_pane("robot.remove_link"),
        )
        yield SystemCommand(
            "Sensitivity view",
            "Sensitivity tab: S1 / ST / percent / confidence (ctrl+t)",
            lambda: self.action_pane("sensitivity.toggle_view"),
        )

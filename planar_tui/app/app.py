"""The Textual workbench: four tabs over one preset, jobs run by the CLI's own runners.

A job runs as ``JOB_KINDS[job.kind].run(job, Progress(...))`` in a thread worker (the
kernels release the GIL). The runner's progress snapshots are kept as they arrive and a
UI timer shows the latest one every :data:`REFRESH_S` seconds; Cancel sets the flag that
``Progress.check()`` polls between chunks, so the runner raises ``Cancelled``. Outcomes
come back as messages; errors open a dialog, never a traceback.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Iterable
from pathlib import Path
from typing import Any, ClassVar

from textual import work
from textual.app import App, ComposeResult, SystemCommand
from textual.binding import Binding
from textual.message import Message
from textual.screen import Screen
from textual.widgets import Footer, Static, TabbedContent, TabPane
from textual.worker import get_current_worker

from planar_tui.app.screens.dialogs import ConfirmDialog, HelpScreen, MessageDialog, PathDialog
from planar_tui.app.widgets.panes import JobPane, RobotPane
from planar_tui.app.workbench import Workbench
from planar_tui.errors import Cancelled, PresetError
from planar_tui.progress import Progress, ProgressState

#: Seconds between two progress refreshes on screen (10 per second).
REFRESH_S = 0.1


class JobFinished(Message):
    """A job ended: ``result`` on success, ``error`` on failure, ``cancelled`` otherwise."""

    def __init__(
        self,
        pane: JobPane,
        job: Any,
        result: Any = None,
        error: BaseException | None = None,
        cancelled: bool = False,
        seconds: float = 0.0,
    ):
        super().__init__()
        self.pane = pane
        self.job = job
        self.result = result
        self.error = error
        self.cancelled = cancelled
        self.seconds = seconds


class WorkbenchApp(App):
    """planar-tui's terminal workbench."""

    CSS_PATH = "app.tcss"
    TITLE = "planar-tui"
    BINDINGS: ClassVar = [
        Binding("q", "quit", "Quit"),
        Binding("f1,question_mark", "help", "Help", key_display="F1"),
        Binding("f5", "run", "Run", key_display="F5"),
        Binding("escape", "cancel", "Cancel"),
        Binding("ctrl+o", "open", "Open", priority=True),
        Binding("ctrl+s", "save", "Save", priority=True),
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
        self.output_dir = Path(output_dir)
        self._latest: ProgressState | None = None
        self._running_pane: JobPane | None = None
        self._thread_done = threading.Event()
        self._thread_done.set()
        self._cancel_requested_at: float | None = None
        #: Measurements for tests and docs: refreshes shown, cancel latencies (s).
        self.progress_refreshes: list[float] = []
        self.cancel_latencies_s: list[float] = []

    # -- layout ---------------------------------------------------------------------
    def compose(self) -> ComposeResult:
        from planar_tui.app.widgets.sensitivity_pane import SensitivityPane
        from planar_tui.app.widgets.simulate_pane import SimulatePane
        from planar_tui.app.widgets.workspace_pane import WorkspacePane

        panes = {
            "robot": RobotPane,
            "sensitivity": SensitivityPane,
            "workspace": WorkspacePane,
            "simulate": SimulatePane,
        }
        with TabbedContent(id="tabs"):
            for title, name in self.TABS:
                with TabPane(title, id=f"tab-{name}"):
                    yield panes[name](id=f"pane-{name}")
        yield Static("", id="validation", markup=False)
        yield Footer(compact=True)

    def on_mount(self) -> None:
        self.sub_title = str(self.workbench.path)
        self.set_interval(REFRESH_S, self._refresh_progress)
        self.revalidate()

    # -- state helpers --------------------------------------------------------------
    @property
    def job_running(self) -> bool:
        """Whether a runner thread is still working."""
        return not self._thread_done.is_set()

    def current_pane(self) -> Any:
        tabs = self.query_one(TabbedContent)
        name = (tabs.active or "tab-robot").removeprefix("tab-")
        return self.query_one(f"#pane-{name}")

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
        bar.update(f"ok: {self.workbench.path.name}, {count} job{'s' if count != 1 else ''} valid")
        bar.set_class(False, "invalid")
        return True

    # -- running jobs ---------------------------------------------------------------
    def action_run(self) -> None:
        """Run the job of the current tab."""
        pane = self.current_pane()
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
        self._latest = None
        self._running_pane = pane
        self._cancel_requested_at = None
        self._thread_done.clear()
        pane.controls().set_running(True)
        self.refresh_bindings()
        pane.controls().status(f"starting {job.label}")
        self._run_worker(pane, job)

    @work(thread=True, exclusive=True, group="job", exit_on_error=False)
    def _run_worker(self, pane: JobPane, job: Any) -> None:
        """Run ``job`` with the CLI's runner; report the outcome as a :class:`JobFinished`."""
        from planar_tui.registry import JOB_KINDS

        worker = get_current_worker()
        started = time.perf_counter()
        progress = Progress(on_update=self._store_progress, should_stop=lambda: worker.is_cancelled)
        try:
            result = JOB_KINDS[job.kind].run(job, progress)
        except Cancelled:
            finished = JobFinished(pane, job, cancelled=True)
        except Exception as error:  # shown in a dialog, never as a traceback
            finished = JobFinished(pane, job, error=error)
        else:
            finished = JobFinished(pane, job, result=result)
        finally:
            if self._cancel_requested_at is not None:
                self.cancel_latencies_s.append(time.perf_counter() - self._cancel_requested_at)
            self._thread_done.set()
        finished.seconds = time.perf_counter() - started
        self.post_message(finished)

    def _store_progress(self, state: ProgressState) -> None:
        """Called in the worker thread: keep the latest snapshot for the UI timer."""
        self._latest = state

    def _refresh_progress(self) -> None:
        state = self._latest
        if len(self.screen_stack) > 1:
            return  # a dialog is up: redrawing the screen behind it would only slow it down
        if self._running_pane is not None and state is not None and self.job_running:
            self._running_pane.show_progress(state)
            self.progress_refreshes.append(time.perf_counter())

    def action_cancel(self) -> None:
        """Ask the running job to stop (the runner stops at its next chunk)."""
        if not self.job_running:
            return
        self._cancel_requested_at = time.perf_counter()
        for worker in self.workers:
            if worker.group == "job":
                worker.cancel()
        if self._running_pane is not None:
            self._running_pane.controls().status("cancelling…")

    def on_job_finished(self, message: JobFinished) -> None:
        pane = message.pane
        if self._running_pane is pane:
            self._running_pane = None
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

    # -- presets and export ---------------------------------------------------------
    def action_open(self) -> None:
        """Open a preset (a path or a bundled preset name)."""
        if self.job_running:
            self.notify("Cancel the running job first.", severity="warning")
            return

        def opened(answer: str | None) -> None:
            if answer:
                self.call_later(self.open_preset, answer)

        self.push_screen(
            PathDialog("Open preset (path or bundled name)", str(self.workbench.path)), opened
        )

    async def open_preset(self, argument: str) -> bool:
        """Load a preset into every tab; a bad one is reported and the current one kept."""
        try:
            bench = Workbench.open(argument)
        except PresetError as error:
            self.push_screen(MessageDialog("Cannot open preset", str(error)))
            return False
        self.workbench = bench
        self.sub_title = str(bench.path)
        await self.recompose()
        self.revalidate()
        self.notify(f"Opened {bench.path}")
        return True

    def action_save(self) -> None:
        """Save the preset as TOML (validated first)."""

        def chosen(answer: str | None) -> None:
            if answer:
                self.save_preset(answer)

        self.push_screen(PathDialog("Save preset as", str(self.workbench.path)), chosen)

    def save_preset(self, target: str | Path) -> Path | None:
        """Write the validated document to ``target`` atomically; ``None`` if invalid."""
        from planar_tui.csvio import write_text_atomic

        try:
            text = self.workbench.to_toml()
        except PresetError as error:
            self.push_screen(MessageDialog("Not saved: the preset is invalid", str(error)))
            return None
        path = write_text_atomic(Path(target), text)
        self.workbench.path = path
        self.sub_title = str(path)
        self.revalidate()
        self.notify(f"Saved {path}")
        return path

    def action_export(self) -> None:
        """Export the table on screen (and workspace boxes) to CSV."""
        pane = self.current_pane()
        tables = pane.export_tables() if isinstance(pane, JobPane) else {}
        if not tables:
            self.notify("Nothing to export: run a job on this tab first.", severity="warning")
            return
        default = self.output_dir / pane.job.output

        def chosen(answer: str | None) -> None:
            if answer:
                self.export_csv(pane, answer)

        hint = "Enter: write   Escape: cancel" + (
            "   (boxes go to FILE-boxes.csv)" if len(tables) > 1 else ""
        )
        self.push_screen(PathDialog("Export CSV to", str(default), hint), chosen)

    def export_csv(self, pane: JobPane, target: str | Path) -> list[Path]:
        """Write the pane's tables with the CLI's atomic CSV writer."""
        from planar_tui.csvio import write_csv_atomic

        target = Path(target)
        written = []
        for suffix, table in pane.export_tables().items():
            path = (
                target.with_name(f"{target.stem}-{suffix}{target.suffix or '.csv'}")
                if suffix
                else target
            )
            written.append(write_csv_atomic(path, table))
        self.notify("Wrote " + ", ".join(map(str, written)))
        return written

    def export_text(self) -> str:
        """The screen as plain text (for tests, docs and text screenshots)."""
        import io

        from rich.console import Console

        width, height = self.size
        console = Console(
            width=width, height=height, file=io.StringIO(), force_terminal=True,
            color_system=None, record=True, legacy_windows=False, safe_box=False,
        )  # fmt: skip
        console.print(
            self.screen._compositor.render_update(full=True, screen_stack=self._background_screens)
        )
        return console.export_text()

    # -- quitting, help, command palette --------------------------------------------
    async def action_quit(self) -> None:
        """Quit; asks first only while a job is running."""
        if not self.job_running:
            self.exit()
            return

        def answered(yes: bool | None) -> None:
            if yes:
                self.action_cancel()
                self.exit()

        self.push_screen(ConfirmDialog("A job is running. Cancel it and quit?"), answered)

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
        yield SystemCommand(
            "Export CSV", "Write the table on screen to CSV (ctrl+e)", self.action_export
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

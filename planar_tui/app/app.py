"""The Textual workbench: a tab per job kind (and the robot's) over one preset, jobs run by the batch service.

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

import asyncio
from collections.abc import Iterable
from pathlib import Path
from typing import Any, ClassVar

from textual.app import App, ComposeResult, SystemCommand
from textual.binding import Binding
from textual.screen import Screen
from textual.widgets import Footer, Static, TabbedContent, TabPane

from planar_tui.app import recent
from planar_tui.app.export_actions import ExportActions
from planar_tui.app.file_actions import FileActions
from planar_tui.app.history_actions import HistoryActions
from planar_tui.app.job_runner import JobFinished, JobRunner
from planar_tui.app.messages import DocumentEdited
from planar_tui.app.optimise_actions import OptimiseActions
from planar_tui.app.palette import workbench_commands
from planar_tui.app.problems import locate, reason, status_line
from planar_tui.app.run_actions import RunActions
from planar_tui.app.screen_text import svg_screen_text
from planar_tui.app.settings import load_settings
from planar_tui.app.sweep_actions import SweepActions
from planar_tui.app.view_actions import ViewActions
from planar_tui.app.warming import preset_kinds, warm_in_background
from planar_tui.app.widgets.panes import JobPane
from planar_tui.app.widgets.robot_pane import RobotPane
from planar_tui.app.workbench import Workbench
from planar_tui.errors import PresetError
from planar_tui.jobkind import resolve
from planar_tui.registry import JOB_KINDS

__all__ = ["REFRESH_S", "JobFinished", "WorkbenchApp"]

#: Seconds between two progress refreshes on screen (10 per second).
REFRESH_S = 0.1


def view_bindings() -> list[Binding]:
    """``ctrl+t`` on each tab whose pane steps through views (its kind's
    :attr:`~planar_tui.jobkind.Tab.view`, the footer's label; its ``view_help`` the help's
    line), shown on that tab alone (:meth:`WorkbenchApp.check_action`)."""
    return [
        Binding(
            "ctrl+t",
            f"pane_view('{name}')",
            kind.tab.view,
            priority=True,
            tooltip=f"{kind.tab.title} tab: {kind.tab.view_help}",
        )
        for name, kind in JOB_KINDS.items()
        if kind.tab is not None and kind.tab.view
    ]


class WorkbenchApp(
    ViewActions,
    RunActions,
    SweepActions,
    OptimiseActions,
    ExportActions,
    FileActions,
    HistoryActions,
    App,
):
    """planar-tui's terminal workbench (running jobs in
    :class:`~planar_tui.app.run_actions.RunActions`; open, save, undo and quit in
    :class:`~planar_tui.app.file_actions.FileActions`, exports in
    :class:`~planar_tui.app.export_actions.ExportActions`; tabs, help, maximising, undo in
    place and the settings in :class:`~planar_tui.app.view_actions.ViewActions`; sweeps in
    :class:`~planar_tui.app.sweep_actions.SweepActions`, optimisations in
    :class:`~planar_tui.app.optimise_actions.OptimiseActions`)."""

    CSS_PATH = Path(__file__).with_name("app.tcss")  # absolute: subclasses elsewhere find it
    TITLE = "planar-tui"
    #: The footer shows the keys that fit 80 columns in every state (a job running and a
    #: problem shown, the ^p palette at the right): q F1 F5 esc ^s ^f ^t ^g; every key is
    #: in the help (F1) and the palette (ctrl+p).
    BINDINGS: ClassVar = [
        Binding("q", "quit", "Quit"),
        Binding("f1,question_mark", "help", "Help", key_display="F1"),
        Binding("f5", "run", "Run", key_display="F5"),
        Binding("escape", "cancel", "Cancel"),
        Binding("ctrl+o", "open", "Open", priority=True, show=False),
        Binding("ctrl+s", "save", "Save", priority=True),
        Binding("ctrl+z", "undo", "Undo", priority=True, show=False),
        Binding("ctrl+e", "export", "Export", priority=True, show=False),
        Binding("ctrl+f", "toggle_form", "Form", priority=True),
        Binding("ctrl+n", "pane_action('add_link')", "Add link", priority=True, show=False),
        Binding("ctrl+r", "pane_action('remove_link')", "Del link", priority=True, show=False),
        Binding("f10", "history", "History", key_display="F10", show=False),
        *view_bindings(),
        Binding("ctrl+g", "goto_problem", "Error", priority=True),
        Binding("ctrl+l", "figure", "Figure", priority=True, show=False),
        Binding("ctrl+b", "maximise", "Maximise", priority=True, show=False),
        Binding("f9", "run_all", "Run all", key_display="F9", show=False),
        Binding("f8", "sweep", "Sweep", key_display="F8", show=False),
        *(
            Binding(str(number), f"digit_tab({number})", f"Tab {number}", show=False)
            for number in range(1, 10)
        ),
        *(
            Binding(key, f"show_tab_number({number})", f"Tab {number}", show=False, priority=True)
            for number, key in enumerate(("f2", "f3", "f4", "f6", "f7", "f12"), start=1)
        ),
        Binding("ctrl+pagedown", "step_tab(1)", "Next tab", show=False, priority=True),
        Binding("ctrl+pageup", "step_tab(-1)", "Previous tab", show=False, priority=True),
    ]

    def __init__(
        self,
        workbench: Workbench,
        output_dir: Path | str | None = None,
        *,
        warm_kernels: bool = False,
        first_job_tab: bool = False,
    ):
        super().__init__()
        self.workbench = workbench
        #: Open on the tab of the preset's first job (``planar-tui tui``; tests start on
        #: the Robot tab unless they ask).
        self.first_job_tab = first_job_tab
        #: Compile the kernels not yet cached in a background thread at start (what
        #: ``planar-tui`` does; tests leave it off to keep their timings their own).
        self.warm_kernels_at_start = warm_kernels
        #: The settings that persist (:mod:`planar_tui.app.settings`) and the warning of a
        #: settings file that could not be used (shown once the app runs).
        self.settings, self.settings_warning = load_settings()
        self.form_hidden = bool(self.settings.form_hidden)
        #: The warning of a recent-files state that could not be used (shown once the app
        #: runs; :mod:`planar_tui.app.recent`).
        self.recent_warning = recent.load_checked()[1]
        #: The folder ``ctrl+e``, ``ctrl+l`` and F9 use: the one given, else the one last
        #: exported or run into (the settings), else ``.`` (as ``planar-tui run``).
        self.output_dir = Path(output_dir or self.settings.output_dir or ".")
        self.jobs = JobRunner(self)
        #: The document's problems as last checked (first one: the validation line).
        self.problems: list[PresetError] = []
        #: Quit was confirmed while a job ran: exit once its worker has stopped.
        self.quitting = False
        #: The latest finished sweep (its screen opens again from the palette).
        self.last_sweep: Any = None

    # -- layout ---------------------------------------------------------------------
    @staticmethod
    def tabs() -> tuple[tuple[str, str], ...]:
        """(title, name) of every tab: Robot, then each job kind's declared
        :class:`~planar_tui.jobkind.Tab` in its order (read from the registry now)."""
        kinds = sorted(
            (kind.tab.order, kind.tab.title, name)
            for name, kind in JOB_KINDS.items()
            if kind.tab is not None
        )
        return (("Robot", "robot"), *((title, name) for _, title, name in kinds))

    @staticmethod
    def pane_classes() -> dict[str, type]:
        """The dedicated pane of each tab (a job kind's ``Tab.pane``, ``module:Class``); a
        job kind without one gets :class:`JobPane`."""
        panes: dict[str, type] = {"robot": RobotPane}
        for name, kind in JOB_KINDS.items():
            if kind.tab is not None and kind.tab.pane is not None:
                panes[name] = resolve(kind.tab.pane)
        return panes

    def compose(self) -> ComposeResult:
        #: The tabs' panes built so far, by name (kept: queried on every edit's check
        #: otherwise): the Robot tab's and those of the preset's job kinds now, any other
        #: tab's when it is first shown (:meth:`on_tabbed_content_tab_activated`), so that
        #: opening a preset composes and styles a few forms, not every kind's.
        self.tab_panes: dict[str, Any] = {}
        with TabbedContent(id="tabs"):
            for title, name in self.tabs():
                with TabPane(title, id=f"tab-{name}"):
                    if name == "robot" or self.workbench.has(name):
                        yield self.new_pane(name)
        self.validation_line = Static("", id="validation", markup=False)
        yield self.validation_line
        yield Footer(compact=True)

    def new_pane(self, name: str) -> Any:
        """The pane of tab ``name`` (its kind's own, else :class:`JobPane`), kept in
        :attr:`tab_panes`, not mounted yet."""
        pane = self.pane_classes().get(name)
        if pane is None:
            pane_widget = JobPane(self.workbench, kind=name, id=f"pane-{name}")
        else:
            pane_widget = pane(self.workbench, id=f"pane-{name}")
        if isinstance(pane_widget, JobPane):  # styled once, when mounted
            pane_widget.set_class(self.form_hidden, "hide-form")
        self.tab_panes[name] = pane_widget
        return pane_widget

    async def show_opened(self) -> None:
        """Show the document just opened (:meth:`open_preset`): the Robot tab's fields take
        its values in place (its forms rebuilt only where its robots' pickers or link
        counts differ), every job tab's pane built so far is dropped (its results and runs
        were the other document's) and those of the new preset's own kinds are built; the
        tab bar, the footer and the validation line stay. Recomposing the whole app
        rebuilt and restyled the Robot tab's 50 fields at each opening."""
        self.screen.minimize()
        robot = self.tab_panes["robot"]
        robot.bench, robot.target = self.workbench, None
        await robot.load_document()
        robot.scroll_home(animate=False)
        dropped = [pane for name, pane in self.tab_panes.items() if name != "robot"]
        self.tab_panes = {"robot": robot}
        for pane in dropped:
            await pane.remove()
        await asyncio.gather(
            *(
                self.query_one(f"#tab-{name}", TabPane).mount(self.new_pane(name))
                for _, name in self.tabs()
                if name != "robot" and self.workbench.has(name)
            )
        )

    def on_mount(self) -> None:
        self.apply_settings()
        if self.settings_warning:
            self.notify(self.settings_warning, title="Settings", severity="warning", timeout=20)
        if self.recent_warning:
            self.notify(self.recent_warning, title="Recent files", severity="warning", timeout=20)
        self.show_document_state()
        if self.first_job_tab:
            self.show_first_job_tab()
        if self.warm_kernels_at_start:
            self.run_worker(
                self._warm_kernels,
                name="warm-up",
                group="warm-up",
                thread=True,
                exit_on_error=False,
            )
        self.set_interval(REFRESH_S, self._refresh_progress)
        self.report_opened(say_valid=False)

    # -- state helpers --------------------------------------------------------------
    @property
    def job_running(self) -> bool:
        """Whether a runner thread is still working."""
        return self.jobs.running

    def current_pane(self) -> Any:
        tabs = self.query_one(TabbedContent)
        name = (tabs.active or "tab-robot").removeprefix("tab-")
        return self.tab_panes[name]

    def job_panes(self) -> list[JobPane]:
        """The job tabs' panes."""
        return [pane for pane in self.tab_panes.values() if isinstance(pane, JobPane)]

    async def on_document_edited(self, message: DocumentEdited) -> None:
        """A tab edited the preset: check it again (and mark it modified)."""
        self.revalidate()
        await self.after_edit()

    def revalidate(self) -> bool:
        """Check every job and robot with the CLI's parser, each job on its own; show the
        first problem (reason first) on the validation line, mark each bad field on its
        tab, and dim the results whose inputs changed."""
        bar = getattr(self, "validation_line", None)
        if bar is None or not bar.is_attached:  # closing, or between two compositions
            return False
        had_problems = bool(self.problems)
        preset, self.problems = self.workbench.check()
        if bool(self.problems) != had_problems:
            self.refresh_bindings()  # the footer's ^g Error, at once
        self.mark_problems()
        for pane in self.job_panes():
            pane.update_stale()
        if self.problems:
            bar.update(status_line(self.problems, self.workbench.display_name()))
            bar.set_class(True, "invalid")
            return False
        count = len(preset.jobs)
        bar.update(f"ok: {self.document_label()}, {count} job{'s' if count != 1 else ''} valid")
        bar.set_class(False, "invalid")
        return True

    def mark_problems(self, panes: Iterable[Any] | None = None) -> None:
        """Mark the fields the problems name, on every tab built (``panes``: these only;
        each tab marks its own)."""
        located = [
            (where, reason(error))
            for error in self.problems
            if (where := locate(error, self.workbench.robot_kinds())) is not None
        ]
        for pane in self.tab_panes.values() if panes is None else panes:
            pane.mark_problems(located)

    async def action_goto_problem(self) -> None:
        """Jump to the first problem's field (switching tab and job if needed)."""
        if not self.problems:
            self.notify("No problem: every job is valid.")
            return
        await self.goto_problem(self.problems[0])

    async def goto_problem(self, error: PresetError) -> None:
        """Show the tab (and the job or robot) of ``error`` and focus its marked field."""
        where = locate(error, self.workbench.robot_kinds())
        pane = self.problem_pane(where) if where is not None else None
        if pane is None:
            self.notify(reason(error), title="Not on a tab", severity="error")
            return
        if isinstance(pane, JobPane) and pane.index != where.index:
            pane.index = where.index
            await pane.recompose()
        elif isinstance(pane, RobotPane):
            target = (where.table, where.index) if where.robot else None
            if pane.target != target:
                pane.target = target
                await pane.recompose()
        self.action_show_tab(pane.id.removeprefix("pane-"))
        self.revalidate()
        marked = pane.query(".-bad")
        if marked:
            self.call_after_refresh(marked.first().focus)
        else:
            self.notify(reason(error), severity="error")

    def problem_pane(self, where: Any) -> Any:
        """The tab that shows the place ``where``; ``None`` when no tab does."""
        if where.robot or where.table in self.workbench.robot_kinds():
            return self.query_one(RobotPane)
        panes = self.query(f"#pane-{where.table}")
        return panes.first() if panes else None

    def _warm_kernels(self) -> None:
        """Worker thread: compile the kernels not cached yet, the preset's kinds first and
        never while a job runs (:func:`planar_tui.app.warming.warm_in_background`); says
        so in two notifications, and stops within 0.05 s when the app closes."""
        from textual.worker import get_current_worker

        worker = get_current_worker()
        first = self.call_from_thread(preset_kinds, self)
        warm_in_background(
            lambda text: self.call_from_thread(self.notify, text),
            first,
            lambda: self.jobs.running,
            lambda: worker.is_cancelled,
        )

    def on_unmount(self) -> None:
        """Closing: stop a job still running (its thread must not outlive the app)."""
        self.jobs.cancel()

    def exit_if_quitting(self) -> bool:
        """Quit was confirmed while a job ran: its worker has stopped now, so exit."""
        if self.quitting:
            self.exit()
        return self.quitting

    def export_csv(self, pane: Any, out_dir: str | Path) -> list[Path]:
        """Export (:class:`~planar_tui.app.export_actions.ExportActions`), then offer that folder next time: the figure of
        ``ctrl+l`` goes beside the CSV just exported."""
        written = super().export_csv(pane, out_dir)
        if written:
            self.remember_output_dir(out_dir)
        return written

    def show_document_state(self) -> None:
        """The title (:class:`FileActions`), and the preset as the last one opened."""
        super().show_document_state()
        if self.workbench.original_text is not None:
            self.remember(last_preset=str(self.workbench.path.resolve()))

    # -- the screen as text -----------------------------------------------------------
    def export_text(self) -> str:
        """The screen as plain text (for tests, docs and text screenshots), read back from
        Textual's public SVG screenshot (see :mod:`planar_tui.app.screen_text`)."""
        width, height = self.size
        return svg_screen_text(self.export_screenshot(), width, height)

    # -- command palette ------------------------------------------------------------
    def action_pane(self, action: str) -> None:
        """Switch to a tab and run its own action (for the command palette)."""
        pane_name, method = action.split(".")
        self.action_show_tab(pane_name)
        self.call_later(self.action_pane_action, method)

    def check_action(self, action: str, parameters: tuple[object, ...]) -> bool | None:
        """Show a tab's own bindings only on that tab (``ctrl+t`` labelled per tab), Cancel
        only while a job runs, the digits only on the tab bar; on a screen of its own
        (history, comparison, sweep) not Save nor the form's Error (its footer fits 80
        columns)."""
        if action in ("save", "goto_problem") and self.on_own_screen():
            return False
        if action in ("pane_action", "pane_view", "toggle_form", "run", "sweep"):
            try:
                pane = self.current_pane() if self.is_mounted else None
            except Exception:  # between two compositions
                pane = None
            if action == "pane_action":
                return hasattr(pane, f"action_{parameters[0]}")
            if action == "pane_view":
                shown = pane is not None and pane.id == f"pane-{parameters[0]}"
                return shown and hasattr(pane, "action_toggle_view")
            return isinstance(pane, JobPane)
        if action == "digit_tab":
            return self.digit_switches_tabs()
        if action == "cancel":
            return self.job_running
        if action == "goto_problem":
            return bool(self.problems)
        return True

    def on_own_screen(self) -> bool:
        """Whether a full screen (not a dialog) is shown over the workbench."""
        from textual.screen import ModalScreen

        return len(self.screen_stack) > 1 and not isinstance(self.screen, ModalScreen)

    async def on_tabbed_content_tab_activated(self, event: TabbedContent.TabActivated) -> None:
        """A tab shown: its pane built and mounted on its first showing (its problems
        marked, its results' staleness shown), its form shown or hidden as the others'."""
        name = (event.pane.id or "").removeprefix("tab-")
        if name not in self.tab_panes and name in {tab for _, tab in self.tabs()}:
            pane = self.new_pane(name)
            await event.pane.mount(pane)
            self.mark_problems([pane])
            if isinstance(pane, JobPane):
                pane.update_stale()
        if name in self.tab_panes:  # this tab's: another may be shown by now
            self.sync_form(self.tab_panes[name])
        self.refresh_bindings()

    async def action_pane_view(self, kind: str) -> None:
        """``ctrl+t``: step the current tab's view (labelled per tab, :func:`view_bindings`)."""
        await self.action_pane_action("toggle_view")

    async def action_pane_action(self, method: str) -> None:
        """Run the current tab's own action (add/remove link, sensitivity view)."""
        pane = self.current_pane()
        if hasattr(pane, f"action_{method}"):
            await self.run_action(method, pane)

    def get_system_commands(self, screen: Screen) -> Iterable[SystemCommand]:
        """Textual's commands, then every action of the workbench by name (ctrl+p)."""
        yield from super().get_system_commands(screen)
        yield from workbench_commands(self)

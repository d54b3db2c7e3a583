"""The workbench's view actions: tabs, the settings form, maximising, help, undo in place
and the settings that persist (mixed into :class:`~planar_tui.app.app.WorkbenchApp`).

- Tabs: ``F2`` ``F3`` ``F4`` ``F6`` ``F7`` ``F12`` and ``ctrl+pageup`` / ``ctrl+pagedown``
  anywhere; the digits ``1``…``9`` only while the focus is on the tab bar (never in a
  form: a digit there is a value, or a job selector's or a button's key).
- ``ctrl+b`` maximises the focused plot or table, else the tab's results area
  (Textual's ``Screen.maximize``); ``ctrl+b`` or escape restores it.
- ``ctrl+z`` restores the previous document into the fields already on screen: the tab,
  the focused field, the results and the status stay (the results marked stale when the
  undone edit made them so); nothing is rebuilt but what changed shape.
- Settings (:mod:`planar_tui.app.settings`): the theme, the last preset, the form shown
  or hidden and the output folder are written when they change and applied at start.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

from planar_tui.app import recent
from planar_tui.app.settings import Settings, load_settings, save_settings, updated

if TYPE_CHECKING:
    from planar_tui.app.workbench import Workbench

__all__ = ["ViewActions"]


class ViewActions:
    """Mixed into :class:`~planar_tui.app.app.WorkbenchApp` (which provides
    ``workbench``, ``output_dir``, ``current_pane``, ``tabs`` and Textual's ``App``)."""

    workbench: Workbench
    output_dir: Path
    settings: Settings
    #: Whether the job tabs' forms are hidden (``ctrl+f``; from the settings at start).
    form_hidden: bool

    # -- tabs -------------------------------------------------------------------------
    def action_show_tab(self, name: str) -> None:
        """Switch to a tab by name."""
        from textual.widgets import TabbedContent

        self.query_one(TabbedContent).active = f"tab-{name}"

    def action_show_tab_number(self, number: int) -> None:
        """Switch to tab ``number`` (1-based: F2-F4, F6, F7, F12; the digits on the tab
        bar)."""
        tabs = self.tabs()
        if 1 <= number <= len(tabs):
            self.action_show_tab(tabs[number - 1][1])
            self.call_after_refresh(self.focus_tab_content)

    def action_digit_tab(self, number: int) -> None:
        """A digit on the tab bar (see :meth:`digit_switches_tabs`)."""
        self.action_show_tab_number(number)

    def digit_switches_tabs(self) -> bool:
        """Whether a digit switches tabs now: only with the focus on the tab bar (or
        nowhere), never in a form (a field, a job selector, a button)."""
        from textual.widgets import Tabs

        return self.focused is None or isinstance(self.focused, Tabs)

    def action_step_tab(self, step: int) -> None:
        """The next (``1``) or previous (``-1``) tab, wrapping (``ctrl+pagedown`` /
        ``ctrl+pageup``)."""
        from textual.widgets import TabbedContent

        names = [name for _, name in self.tabs()]
        active = (self.query_one(TabbedContent).active or "tab-robot").removeprefix("tab-")
        index = names.index(active) if active in names else 0
        self.action_show_tab_number((index + step) % len(names) + 1)

    def focus_tab_content(self) -> None:
        """Put the focus on the tab bar (off a field of the hidden tab), where the digits
        switch tabs."""
        from textual.widgets import TabbedContent, Tabs

        self.query_one(TabbedContent).query_one(Tabs).focus()

    # -- the form, maximising, help -----------------------------------------------------
    def action_toggle_form(self) -> None:
        """Hide or show the settings form of a job tab (more room for results); kept in
        the settings."""
        self.set_form_hidden(not self.form_hidden)

    def set_form_hidden(self, hidden: bool) -> None:
        """Hide or show the job tabs' forms: the current tab's now, each other's when it
        is next shown (:meth:`sync_form`): a class on the tabs' container restyled the
        whole screen's 800 widgets, 8-15 s at load 15 on 2 cores."""
        self.form_hidden = hidden
        self.sync_form(self.current_pane())
        self.remember(form_hidden=hidden)

    def sync_form(self, pane: Any) -> None:
        """Give a job tab's pane the form state (``hide-form``) and redraw its results in
        their new width, when it differs."""
        from planar_tui.app.widgets.panes import JobPane

        if isinstance(pane, JobPane) and pane.has_class("hide-form") != self.form_hidden:
            pane.set_class(self.form_hidden, "hide-form")
            self.call_after_refresh(pane.rerender)

    def action_maximise(self) -> None:
        """Maximise the focused plot or table (a widget of the results that takes the
        focus), else the current tab's results area; again (or escape) restores it."""
        from planar_tui.app.widgets.panes import JobPane, Results

        screen = self.screen
        if screen.maximized is not None:
            screen.minimize()
            return
        pane = self.current_pane()
        if not isinstance(pane, JobPane) or not pane.query(Results):
            self.notify("Nothing to maximise on this tab.", severity="warning")
            return
        results = pane.query_one(Results)
        focused = self.focused
        inside = focused is not None and results in focused.ancestors
        target = focused if inside and focused.allow_maximize else results
        screen.maximize(target, container=False)

    def action_help(self) -> None:
        """Show every key (the app's and each tab's bindings), units and glyphs."""
        from planar_tui.app.screens.dialogs import HelpScreen

        if not isinstance(self.screen, HelpScreen):
            self.push_screen(HelpScreen(self.binding_sources()))

    @classmethod
    def binding_sources(cls) -> list[tuple[str, list[Any]]]:
        """``(where, bindings)``: the app's, then each tab's own, the Torques drawing's, a
        field's, the run history's and the comparison's (for the help screen)."""
        from textual.app import App
        from textual.binding import Binding
        from textual.screen import Screen

        from planar_tui.app.widgets.fields import Field

        textual = [  # Textual's own: ctrl+q, the palette, Tab and shift+Tab
            *(b for b in App.BINDINGS if isinstance(b, Binding) and not b.system),
            Binding(App.COMMAND_PALETTE_BINDING, "command_palette", "the command palette"),
            *(b for b in Screen.BINDINGS if isinstance(b, Binding) and "focus" in b.action),
        ]
        sources: list[tuple[str, list[Any]]] = [("", [*cls.BINDINGS, *textual])]
        titles = {name: title for title, name in cls.tabs()}
        for name, pane in cls.pane_classes().items():
            own = [b for b in vars(pane).get("BINDINGS", []) if not isinstance(b, tuple)]
            if own:
                sources.append((f"{titles.get(name, name)} tab", own))
        from planar_tui.app.widgets.torques_pane import StateView

        sources.append(("Torques tab, its drawing focused", list(StateView.BINDINGS)))
        sources.append(("in a field", list(Field.BINDINGS)))
        from planar_tui.app.screens.history import CompareScreen, HistoryScreen

        sources.append(("Run history (F10)", list(HistoryScreen.BINDINGS)))
        sources.append(("Comparison (c in the history)", list(CompareScreen.BINDINGS)))
        return sources

    # -- undo in place --------------------------------------------------------------------
    async def restore_panes(self) -> None:
        """Show the document (after an undo) in the tabs' fields, in place: the tab, the
        focused field and its job, the results and the status all stay."""
        for pane in self.tab_panes.values():
            await pane.load_document()

    # -- settings -------------------------------------------------------------------------
    def remember(self, **changes: Any) -> None:
        """Keep changed settings in the settings file (a failure to write is a warning);
        a settings file that could not be used at start is left as it is (the user's to
        mend), the changes kept for this session only. Only ``changes`` are written, over
        the file as it is now: another instance's settings saved since this one started
        (its output folder) are kept, not overwritten by this one's older copy."""
        new = updated(self.settings, **changes)
        if new == self.settings:
            return
        self.settings = new
        if self.settings_warning:
            return
        try:
            on_disk, warning = load_settings()
            if warning is None:
                save_settings(updated(on_disk, **changes))
        except OSError as error:
            self.notify(f"Settings not saved: {error}", severity="warning")

    def remember_recent(self, kind: str, path: Path | str) -> None:
        """Put ``path`` first in the recent list ``kind``; a damaged state file set aside
        on the way is a warning (:func:`planar_tui.app.recent.remember`)."""
        note = recent.remember(kind, path)
        if note is not None:
            self.notify(note, title="Recent files", severity="warning", timeout=20)

    def apply_settings(self) -> None:
        """At start: the theme and the form's state from the settings; later theme
        changes are kept."""
        settings = self.settings
        if settings.theme is not None and settings.theme in self.available_themes:
            self.theme = settings.theme
        self.theme_changed_signal.subscribe(self, lambda theme: self.remember(theme=theme.name))

    def remember_output_dir(self, folder: Path | str) -> None:
        """A folder was exported or run into: offer it next time (figures go there)."""
        self.output_dir = Path(folder)
        self.remember(output_dir=str(Path(folder).resolve()))

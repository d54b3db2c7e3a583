"""The workbench's file actions: open, save, save as, undo, and quitting with unsaved
edits; nothing is lost or overwritten without a question (exports:
:mod:`planar_tui.app.export_actions`).

- Unsaved edits show as ``NAME (modified)`` (the app's ``sub_title`` and the ``ok:``
  line); ``ctrl+o`` and quitting (``q``, ``ctrl+q``, the palette's Quit) ask Save /
  Discard / Cancel (:class:`~planar_tui.app.screens.dialogs.UnsavedDialog`).
- ``ctrl+s`` writes the preset back to the file it came from; a bundled preset is
  read-only, so it (and "Save as" in the palette) asks for a path, offering
  ``./NAME.toml``. Writing onto any other existing file asks first; so does an export
  that would overwrite files (they are listed).
- Saving keeps the file's comments, key order and formatting
  (:func:`planar_tui.app.saving.merge_document`).
- ``ctrl+z`` undoes the latest edit (the workbench's history) in the fields on screen.
- Every failure to read, write or check becomes a dialog: the edits are kept.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

from planar_tui.app.saving import (
    SaveFailed,
    check_target,
    default_save_path,
    draft_text,
    existing_files,
    is_bundled,
    write_preset,
)
from planar_tui.app.screens.dialogs import ConfirmDialog, MessageDialog, PathDialog, UnsavedDialog
from planar_tui.app.screens.picker import preset_picker
from planar_tui.app.widgets.panes import JobPane
from planar_tui.app.widgets.robot_pane import RobotPane
from planar_tui.errors import PresetError

if TYPE_CHECKING:
    from planar_tui.app.workbench import Workbench

__all__ = ["FileActions"]


class FileActions:
    """Mixed into :class:`~planar_tui.app.app.WorkbenchApp` (which provides
    ``workbench``, ``output_dir``, ``jobs``, ``revalidate`` and Textual's ``App``)."""

    workbench: Workbench
    output_dir: Path
    quitting: bool

    # -- the modified marker ----------------------------------------------------------
    def dialog_open(self) -> bool:
        """Whether a dialog is on top (the file keys are priority bindings: they must not
        stack a second dialog over it, nor edit the document behind it)."""
        from textual.screen import ModalScreen

        return isinstance(self.screen, ModalScreen)

    def document_label(self) -> str:
        """The preset as a person names it (:meth:`Workbench.display_name`), ``(modified)``
        after an unsaved edit."""
        name = self.workbench.display_name()
        return f"{name} (modified)" if self.workbench.modified else name

    def show_document_state(self) -> None:
        """Put the file name and the modified marker into the title."""
        self.sub_title = self.document_label()

    async def after_edit(self) -> None:
        """A tab edited the document: say what else changed (per-link arrays resized, then
        reload the job tabs so they show it) and update the marker."""
        notes = self.workbench.take_notes()
        if notes:
            await self.reload_panes(robot=False)
            for note in notes:
                self.notify(note, title="Links changed")
        self.show_document_state()

    async def reload_panes(self, robot: bool = True) -> None:
        """Rebuild the tabs' forms from the document (results kept and drawn again; the
        focus stays on the field it was on)."""
        focused = self.focused
        where = [(p.id, focused.id) for p in focused.ancestors if p.id] if focused else []
        panes = list(self.query(JobPane)) + (list(self.query(RobotPane)) if robot else [])
        for pane in panes:
            await pane.recompose()
            if isinstance(pane, JobPane):
                self.call_after_refresh(pane.rerender)
                if self.jobs.running and pane is self.jobs.pane:
                    pane.controls().set_running(True)
                    pane.controls().status("running…")
        for pane_id, field_id in where[:1]:
            found = self.query(f"#{pane_id} #{field_id}") if field_id else []
            if found:
                found.first().focus()

    async def action_undo(self) -> None:
        """Undo the latest edit (``ctrl+z``)."""
        if self.dialog_open():
            return
        if not self.workbench.undo():
            self.notify("Nothing to undo.")
            return
        await self.restore_panes()  # in place: the tab, the field and the results stay
        self.revalidate()
        self.show_document_state()
        self.notify(f"Undone ({len(self.workbench.history)} more step(s) to undo).")

    # -- questions before losing edits ------------------------------------------------
    def unless_unsaved(self, what: str, then: Callable[[], Any]) -> None:
        """``then()`` at once when nothing is unsaved; else ask Save / Discard / Cancel
        first (Save runs ``then`` once written, Cancel drops it)."""
        if not self.workbench.modified:
            then()
            return

        def answered(choice: str | None) -> None:
            if choice == "save":
                self.save_then(then)
            elif choice == "discard":
                then()

        question = f"{self.workbench.path.name} has unsaved changes. Save them before {what}?"
        self.push_screen(UnsavedDialog(question), answered)

    async def action_quit(self) -> None:
        """Quit; asks first about unsaved edits, or while a job is running. Once a quit is
        confirmed during a job, a second quit exits at once."""
        if self.quitting:
            self.exit()
            return
        if self.dialog_open():
            return
        if self.workbench.modified:
            what = "quitting (the running job is cancelled)" if self.jobs.running else "quitting"
            self.unless_unsaved(what, self.quit_now)
        elif self.jobs.running:

            def answered(yes: bool | None) -> None:
                if yes:
                    self.quit_now()

            self.push_screen(ConfirmDialog("A job is running. Cancel it and quit?"), answered)
        else:
            self.quit_now()

    def quit_now(self) -> None:
        """Close the app. A running job is cancelled first and the app exits as soon as its
        worker has stopped (``exit_if_quitting``); the screen says so meanwhile."""
        if not self.jobs.running:
            self.exit()
            return
        self.quitting = True
        self.action_cancel()
        self.notify("Quitting once the job has stopped (q again: quit now).")
        if not self.jobs.running:
            self.exit()

    # -- open -------------------------------------------------------------------------
    def action_open(self) -> None:
        """Open a preset (a path or a bundled name); asks about unsaved edits first."""
        if self.dialog_open():
            return
        if self.jobs.running:
            self.notify("Cancel the running job first.", severity="warning")
            return

        def opened(answer: str | None) -> None:
            if answer:
                self.call_later(self.open_preset, answer)

        def ask_path() -> None:
            self.push_screen(preset_picker(self.workbench.path), opened)

        self.unless_unsaved("opening another preset", ask_path)

    async def open_preset(self, argument: str) -> bool:
        """Load a preset into every tab. One whose values are wrong opens with its
        problems marked (the validation line, ``ctrl+g``); one that cannot be read or is
        no TOML is reported and the current one kept. A preset file opened goes first in
        the picker's recent list (:mod:`planar_tui.app.recent`)."""
        from planar_tui.app.workbench import Workbench

        try:
            bench = Workbench.open_marked(argument)
        except PresetError as error:
            self.push_screen(MessageDialog("Cannot open preset", str(error)))
            return False
        self.workbench = bench
        await self.show_opened()
        self.show_first_job_tab(or_robot=True)
        self.show_document_state()
        if not is_bundled(bench.path):
            self.remember_recent("presets", bench.path)
        self.report_opened()
        return True

    def show_first_job_tab(self, *, or_robot: bool = False) -> None:
        """Show the tab of the preset's first job (in the file's order); a preset of a
        robot alone stays on the tab shown, or shows the Robot tab (``or_robot``)."""
        names = {name for _, name in self.tabs()} - {"robot"}
        first = next((key for key in self.workbench.document if key in names), None)
        if first is not None or or_robot:
            self.action_show_tab(first or "robot")

    def report_opened(self, *, say_valid: bool = True) -> None:
        """Validate the document just opened and say so: opened (unless ``say_valid`` is
        false: the app's start), or opened with its problems marked; a table that was no
        table is said in a warning of its own."""
        valid = self.revalidate()
        for note in self.workbench.take_notes():
            self.notify(note, title="Opened as an empty table", severity="warning", timeout=20)
        path = self.workbench.path
        if valid:
            if say_valid:
                self.notify(f"Opened {path}")
        else:
            count = len(self.problems)
            self.notify(
                f"Opened {path} with {count} problem{'s' if count > 1 else ''}: "
                "marked on the tabs (ctrl+g: go to the first)",
                severity="warning",
            )

    # -- save -------------------------------------------------------------------------
    def action_save(self) -> None:
        """Save the preset back to its file (a bundled one asks for a path)."""
        if self.dialog_open():
            return
        self.save_then(None)

    def action_save_as(self) -> None:
        """Save the preset under a path asked for."""
        if self.dialog_open():
            return
        self.save_then(None, ask=True)

    def save_then(self, then: Callable[[], Any] | None, *, ask: bool = False) -> None:
        """Validate, then write to the preset's own file, or (``ask``, a bundled preset, a
        document without a file) to a path asked for; ``then()`` after a successful
        write. An invalid preset is saved only as a draft, when the question about it is
        answered yes (:meth:`ask_draft`)."""
        try:
            text = self.workbench.to_toml()
        except PresetError as error:
            self.ask_draft(error, lambda draft: self.save_text_then(draft, then, ask=ask))
            return
        except Exception as error:  # the TOML library failing must not lose the edits
            self.push_screen(MessageDialog("Not saved", f"{type(error).__name__}: {error}"))
            return
        self.save_text_then(text, then, ask=ask)

    def ask_draft(self, error: PresetError, save: Callable[[str], Any]) -> None:
        """The preset is invalid: ask whether to save it as a draft anyway (the reason
        shown), then ``save(text)`` with the unvalidated text
        (:func:`~planar_tui.app.saving.draft_text`)."""

        def answered(yes: bool | None) -> None:
            if not yes:
                return
            bench = self.workbench
            try:
                text = draft_text(bench.document, bench.original_text, bench.description)
            except Exception as failure:  # the TOML library failing must not lose the edits
                self.push_screen(MessageDialog("Not saved", f"{type(failure).__name__}: {failure}"))
                return
            save(text)
            self.notify("Saved as a draft: the preset is invalid.", severity="warning")

        dialog = ConfirmDialog(
            "The preset is invalid. Save it as a draft anyway?",
            str(error),
            yes="Save draft (y)",
            no="Cancel (n)",
        )
        self.push_screen(dialog, answered)

    def save_text_then(self, text: str, then: Callable[[], Any] | None, *, ask: bool) -> None:
        """Write ``text`` to the preset's own file, or (``ask``, a bundled preset, a
        document without a file) to a path asked for; ``then()`` after the write."""
        own = self.workbench.path
        if not ask and self.workbench.original_text is not None and not is_bundled(own):
            self.write_then(own, text, then)
            return

        def chosen(answer: str | None) -> None:
            if answer:
                self.confirm_save(Path(answer), text, then)

        hint = "Bundled presets are read-only." if is_bundled(own) else ""
        hint += "\nEnter: save   Escape: cancel"
        dialog = PathDialog("Save preset as", str(default_save_path(own)), hint.strip())
        self.push_screen(dialog, chosen)

    def preset_text(self) -> str | None:
        """The validated document as the file's text; ``None`` (and a dialog) if the
        preset is invalid or cannot be printed."""
        try:
            return self.workbench.to_toml()
        except PresetError as error:
            self.push_screen(MessageDialog("Not saved: the preset is invalid", str(error)))
        except Exception as error:  # the TOML library failing must not lose the edits
            self.push_screen(MessageDialog("Not saved", f"{type(error).__name__}: {error}"))
        return None

    def confirm_save(self, target: Path, text: str, then: Callable[[], Any] | None) -> None:
        """Write to ``target``, asking first when it is another existing file."""
        try:
            check_target(target)
        except SaveFailed as error:
            self.push_screen(MessageDialog("Not saved", str(error)))
            return
        own = self.workbench.path
        if not existing_files([target]) or (target.resolve() == own.resolve()):
            self.write_then(target, text, then)
            return

        def answered(yes: bool | None) -> None:
            if yes:
                self.write_then(target, text, then)

        dialog = ConfirmDialog(
            "This file exists. Overwrite it?", str(target), yes="Overwrite (y)", no="Cancel (n)"
        )
        self.push_screen(dialog, answered)

    def write_then(self, target: Path, text: str, then: Callable[[], Any] | None) -> None:
        """Write ``text`` to ``target``; on success the workbench is saved there and
        ``then()`` runs; a failure opens a dialog and keeps the edits."""
        if self.save_preset(target, text) is not None and then is not None:
            then()

    def save_preset(self, target: str | Path, text: str | None = None) -> Path | None:
        """Write the validated document (or ``text``) to ``target`` atomically, no
        question asked; ``None`` (and a dialog) if invalid or not writable."""
        text = self.preset_text() if text is None else text
        if text is None:
            return None
        try:
            path = write_preset(Path(target), text)
        except SaveFailed as error:
            self.push_screen(MessageDialog("Not saved", str(error)))
            return None
        self.workbench.mark_saved(path, text)
        self.remember_recent("presets", path)
        self.revalidate()
        self.show_document_state()
        self.notify(f"Saved {path}")
        return path

"""Modal screens: a path prompt (open, save, export), a yes/no question, save / discard /
cancel, a message, help. Every dialog fits 80×24 with its buttons whole."""

from __future__ import annotations

from typing import ClassVar

from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Horizontal, Vertical, VerticalScroll
from textual.screen import ModalScreen
from textual.widgets import Button, Input, Label, Static


class PathDialog(ModalScreen[str | None]):
    """Ask for a file path; dismisses with the text, or ``None`` on Escape."""

    BINDINGS: ClassVar = [Binding("escape", "dismiss_none", "Cancel")]

    def __init__(self, title: str, value: str = "", hint: str = ""):
        super().__init__()
        self.title_text = title
        self.value = value
        self.hint = hint

    def compose(self) -> ComposeResult:
        with Vertical(classes="dialog"):
            yield Label(self.title_text, classes="dialog-title")
            yield Input(self.value, id="path-input")
            yield Static(self.hint or "Enter: OK   Escape: cancel", classes="dialog-hint")

    def on_input_submitted(self, event: Input.Submitted) -> None:
        self.dismiss(event.value.strip() or None)

    def action_dismiss_none(self) -> None:
        self.dismiss(None)


class ConfirmDialog(ModalScreen[bool]):
    """A yes/no question: ``y`` / Enter on Yes, ``n`` / Escape for No; ``detail`` (e.g.
    the files an export would overwrite) is shown under the question."""

    BINDINGS: ClassVar = [
        Binding("y", "answer(True)", "Yes"),
        Binding("n,escape", "answer(False)", "No"),
    ]

    def __init__(self, question: str, detail: str = "", yes: str = "Yes (y)", no: str = "No (n)"):
        super().__init__()
        self.question = question
        self.detail = detail
        self.labels = (yes, no)

    def compose(self) -> ComposeResult:
        with Vertical(classes="dialog"):
            yield Label(self.question, classes="dialog-title")
            if self.detail:
                yield Static(self.detail, classes="dialog-detail", markup=False)
            with Horizontal(classes="dialog-buttons"):
                yield Button(self.labels[0], id="yes", variant="error")
                yield Button(self.labels[1], id="no", variant="primary")

    def on_mount(self) -> None:
        self.query_one("#no", Button).focus()

    def on_button_pressed(self, event: Button.Pressed) -> None:
        self.dismiss(event.button.id == "yes")

    def action_answer(self, answer: bool) -> None:
        self.dismiss(answer)


class UnsavedDialog(ModalScreen[str | None]):
    """Unsaved edits: dismisses with ``"save"`` (``s``), ``"discard"`` (``d``) or ``None``
    (Cancel, ``c`` / Escape)."""

    BINDINGS: ClassVar = [
        Binding("s", "answer('save')", "Save"),
        Binding("d", "answer('discard')", "Discard"),
        Binding("c,escape", "answer(None)", "Cancel"),
    ]

    def __init__(self, question: str):
        super().__init__()
        self.question = question

    def compose(self) -> ComposeResult:
        with Vertical(classes="dialog"):
            yield Label(self.question, classes="dialog-title")
            with Horizontal(classes="dialog-buttons"):
                yield Button("Save (s)", id="save", variant="primary")
                yield Button("Discard (d)", id="discard", variant="error")
                yield Button("Cancel (esc)", id="cancel")

    def on_mount(self) -> None:
        self.query_one("#save", Button).focus()

    def on_button_pressed(self, event: Button.Pressed) -> None:
        self.dismiss(None if event.button.id == "cancel" else event.button.id)

    def action_answer(self, answer: str | None) -> None:
        self.dismiss(answer)


class MessageDialog(ModalScreen[None]):
    """A message (a job's error, a preset error) closed with Enter or Escape."""

    BINDINGS: ClassVar = [Binding("escape,enter", "close", "Close")]

    def __init__(self, title: str, message: str):
        super().__init__()
        self.title_text = title
        self.message = message

    def compose(self) -> ComposeResult:
        with Vertical(classes="dialog"):
            yield Label(self.title_text, classes="dialog-title error-title")
            yield Static(self.message, id="message-text", markup=False)
            yield Button("Close (Enter)", id="close", variant="primary")

    def on_mount(self) -> None:
        self.query_one("#close", Button).focus()

    def on_button_pressed(self) -> None:
        self.dismiss(None)

    def action_close(self) -> None:
        self.dismiss(None)


HELP_TEXT = """\
Every action is in the palette (ctrl+p). Tabs: 1 2 3 4 5 6 outside
fields, F2 F3 F4 F6 F7 F12 anywhere. Fields take TOML; enter: next field.
Each job is checked alone: a bad field gets a red border and reason.
  F5          run the job of the current tab (also the Run button)
  F9          run all jobs in order into a folder, as planar-tui run
  F8          run the tab's job as a sweep over keys and values
  escape      cancel the job ("cancelling…" until it has stopped)
  ctrl+g      go to the first error (switches tab, job and robot)
  ctrl+o      open a preset (recent, bundled, or a path; → completes)
  F10         run history: every run, compare two, open a result CSV
  ctrl+s      save (comments kept; a bundled preset asks for a path)
  ctrl+z      undo the latest edit
  ctrl+e      export the result's CSV files to a folder (as the CLI)
  ctrl+l      write the result's figure (PNG, or the plot key) beside
              the CSV that export writes into the output folder
  ctrl+f      hide / show the settings form (room for the results)
  q, ctrl+q   quit (asks about unsaved edits or a running job)
  F1, ?       this help (? outside fields)
  ctrl+n      Robot tab: add a link (a copy of the last one)
  ctrl+r      Robot tab: remove the last link
  ctrl+t      Sensitivity tab: percent / S1 / ST / ± half-width
Dialogs: enter OK, escape cancel or close, keys y, n, s, d answer.
"""


class HelpScreen(ModalScreen[None]):
    """The key bindings and how fields are read."""

    BINDINGS: ClassVar = [Binding("escape,q,f1,question_mark", "close", "Close")]

    def compose(self) -> ComposeResult:
        with VerticalScroll(classes="dialog help", id="help-scroll"):
            yield Label("Help (escape closes)", classes="dialog-title")
            yield Static(HELP_TEXT, markup=False, id="help-text")

    def on_mount(self) -> None:
        self.query_one("#help-scroll").focus()

    def action_close(self) -> None:
        self.dismiss(None)

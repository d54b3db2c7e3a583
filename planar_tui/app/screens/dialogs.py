"""Modal screens: a path prompt (open, save, export), a yes/no question, a message, help."""

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
    """A yes/no question: ``y`` / Enter on Yes, ``n`` / Escape for No."""

    BINDINGS: ClassVar = [
        Binding("y", "answer(True)", "Yes"),
        Binding("n,escape", "answer(False)", "No"),
    ]

    def __init__(self, question: str):
        super().__init__()
        self.question = question

    def compose(self) -> ComposeResult:
        with Vertical(classes="dialog"):
            yield Label(self.question, classes="dialog-title")
            with Horizontal(classes="dialog-buttons"):
                yield Button("Yes (y)", id="yes", variant="error")
                yield Button("No (n)", id="no", variant="primary")

    def on_mount(self) -> None:
        self.query_one("#no", Button).focus()

    def on_button_pressed(self, event: Button.Pressed) -> None:
        self.dismiss(event.button.id == "yes")

    def action_answer(self, answer: bool) -> None:
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
Every action is also in the command palette (ctrl+p). Tabs: 1 2 3 4 5
outside fields, F2 F3 F4 F6 F7 anywhere. tab / shift+tab: focus (▌).
Fields take TOML values (0.25, [0.25, 0.2], singular); enter: next.
Each job is checked alone by the CLI's parser: a bad field gets a red
border and the reason; results older than their inputs say "stale".
  F5          run the job of the current tab (also the Run button)
  F9          run all jobs in order into a folder, as planar-tui run
  escape      cancel the job ("cancelling…" until it has stopped)
  ctrl+g      go to the first error (switches tab, job and robot)
  ctrl+o      open a preset (a path or a bundled name)
  ctrl+s      save the preset (TOML the CLI runs unchanged)
  ctrl+e      export the result's CSV files to a folder (as the CLI)
  ctrl+f      hide / show the settings form (room for the results)
  q, ctrl+q   quit (asks only while a job runs; q outside fields)
  F1, ?       this help (? outside fields)
  ctrl+n      Robot tab: add a link (a copy of the last one)
  ctrl+r      Robot tab: remove the last link
  ctrl+t      Sensitivity tab: percent / S1 / ST / ± half-width
Dialogs: enter OK or close, escape cancel or close, y / n answer.
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

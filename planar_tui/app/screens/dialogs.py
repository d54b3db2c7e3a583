"""Modal screens: a path prompt (open, save, export), a yes/no question, save / discard /
cancel, a message, help. Every dialog fits 80×24 with its buttons whole."""

from __future__ import annotations

import textwrap
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


#: The help text's width (the help dialog's inside at 80 columns).
HELP_WIDTH = 70

#: The help screen's first lines.
HELP_INTRO = """\
Every action is also in the palette (ctrl+p). Fields take TOML values
(0.25, [0.25, 0.2], singular); each job is checked alone, a bad field
gets a red border and its reason under it (▲). Arrows and page keys
scroll the focused area; Tab and shift+Tab move the focus."""

#: A longer line for some actions (the others show their binding's tooltip, else its
#: description).
HELP_DETAILS = {
    "quit": "quit (asks about unsaved edits or a running job; q outside fields)",
    "help": "this help (? outside fields)",
    "run": "run the job of the current tab (also the Run button)",
    "cancel": "cancel the running job (in the footer only while one runs)",
    "open": "open a preset (recent, bundled, or a path; → completes)",
    "history": "run history: every run, compare two, open a result CSV",
    "mark": "mark the highlighted run: A, then B (again: unmark)",
    "compare": "compare the marked runs A and B, else the highlighted run with the "
    "latest other run of its kind",
    "open_result": "open a result CSV into the history",
    "close": "close (back to where it was opened)",
    "state(-1)": "draw the arm at the previous state (theta_deg row)",
    "state(1)": "draw the arm at the next state",
    "state_at(0)": "the first state",
    "state_at(-1)": "the last state",
    "save": "save (comments kept; a bundled preset asks for a path; an invalid one "
    "is saved as a draft if you confirm)",
    "undo": "undo the latest edit, in place (same tab and field; results kept)",
    "export": "export the result's CSV files to a folder (as planar-tui run)",
    "toggle_form": "hide / show the settings form (room for the results; remembered)",
    "pane_action('add_link')": "Robot tab: add a link (a copy of the last one)",
    "pane_action('remove_link')": "Robot tab: remove the last link",
    "goto_problem": "go to the first error (switches tab, job and robot)",
    "figure": "write the result's figure (PNG, or its plot key) beside the CSV export wrote last",
    "maximise": "maximise the focused plot or table, else the results; again or escape restores",
    "run_all": "run all jobs in order into a folder, as planar-tui run",
    "sweep": "run the tab's job as a sweep over keys and values",
    "digit_tab": "show tab 1…9, only with the focus on the tab bar (any tab: ctrl+p, by name)",
    "show_tab_number": "show tab 1…6, anywhere (also in fields)",
    "step_tab(1)": "next tab",
    "step_tab(-1)": "previous tab",
    "next_field": "the next field (a value is one line)",
    "command_palette": "the command palette: every action by name",
    "app.focus_next": "move the focus on (fields, buttons, results)",
    "app.focus_previous": "move the focus back",
}

#: The help screen's last lines: units and glyphs (each filled to the width).
HELP_GLYPHS = (
    "Units are in the keys' names: _m, _cm, _mm lengths; _kg, _g masses; _kgm2 kg m²; "
    "_deg degrees; _rad_s rad/s; _deg_s °/s; _s seconds; _Nm newton metres.",
    "Status: 45% 9.0k/20k eta 3s = percent, done/total (k thousand, M million), the "
    "time left in the stage.",
    "stale: over dimmed results: they came from other inputs (F5 runs it again). "
    "▲ under a field: why it is invalid. A thick bar at the left: the focus.",
    "Sensitivity: red ≥ 50 %, yellow ≥ 20 %, green ≥ 5 %; bold: each row's largest.",
    "Plots: curves marked by joint number 1…n; energies E total, k kinetic, p potential; "
    "Motion: the mean line and the 5-95 % band.",
    "Workspace map: {map}.",
    "Sweep heat map: ' ·░▒▓█' smallest to largest, × a failed point.",
    "Dialogs: enter OK, escape cancel or close; keys y, n, s, d answer.",
)


def key_label(key: str) -> str:
    """A key as the help shows it: ``F5``, ``?``, ``ctrl+t``."""
    if key.startswith("f") and key[1:].isdigit():
        return key.upper()
    return {"question_mark": "?"}.get(key, key)


def help_text(sources: list[tuple[str, list[Binding]]]) -> str:
    """The help screen's text, generated from the bindings: ``(where, bindings)`` pairs
    (the app's first, ``where`` empty; then each tab's and a field's), one line per
    action with all its keys; then units and glyphs."""
    from planar_tui.app.widgets.workspace_explorer import EXACT_ITEM, LEGEND_ITEMS, MODE_ITEM
    from planar_tui.workspace.paving.map import SINGULAR_LEGEND_ITEMS

    map_legend = ", ".join((*LEGEND_ITEMS, EXACT_ITEM, MODE_ITEM, *SINGULAR_LEGEND_ITEMS))
    lines = [HELP_INTRO]
    for where, bindings in sources:
        rows: dict[str, list[str]] = {}
        described: dict[str, str] = {}
        for binding in bindings:
            action = binding.action
            base = action.split("(", 1)[0]
            group = base if base in ("digit_tab", "show_tab_number") else action
            rows.setdefault(group, []).extend(key_label(k) for k in binding.key.split(","))
            described.setdefault(
                group, HELP_DETAILS.get(group, binding.tooltip or binding.description)
            )
        if where:
            lines.append(f"{where}:")
        for group, keys in rows.items():
            shown = " ".join(dict.fromkeys(keys))
            head = f"  {shown:<14}" if len(shown) < 15 else f"  {shown}\n{'':<16}"
            text = textwrap.fill(described[group], HELP_WIDTH - 16)
            lines.append(head + text.replace("\n", "\n" + " " * 16))
    for line in HELP_GLYPHS:
        text = line.format(map=map_legend)
        lines.append(textwrap.fill(text, HELP_WIDTH, subsequent_indent="  "))
    return "\n".join(lines)


class HelpScreen(ModalScreen[None]):
    """Every key (generated from the app's and the tabs' bindings, :func:`help_text`),
    units and glyphs; it scrolls (arrows, page keys)."""

    BINDINGS: ClassVar = [Binding("escape,q,f1,question_mark", "close", "Close")]

    def __init__(self, sources: list[tuple[str, list[Binding]]]):
        super().__init__()
        self.text = help_text(sources)

    def compose(self) -> ComposeResult:
        with VerticalScroll(classes="dialog help", id="help-scroll"):
            yield Label("Help (escape closes; arrows scroll)", classes="dialog-title")
            yield Static(self.text, markup=False, id="help-text")

    def on_mount(self) -> None:
        self.query_one("#help-scroll").focus()

    def action_close(self) -> None:
        self.dismiss(None)

"""Opening files: a preset picker (``ctrl+o``) and a result-CSV dialog (the history's
``o``), each a path field with completion (:class:`PathSuggester`: the rest of a name
shown dimmed, ``→`` or ``End`` takes it) over a list to choose from: recent files
(:mod:`planar_tui.app.recent`) and, for presets, the bundled ones with their one-line
descriptions. Enter in the field opens what it names; Enter on the list opens that entry.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import ClassVar

from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Vertical
from textual.screen import ModalScreen
from textual.suggester import Suggester
from textual.widgets import Input, Label, OptionList, Static
from textual.widgets.option_list import Option

from planar_tui.app.recent import recent
from planar_tui.resources import bundled_presets, preset_description

#: Most directory entries one completion looks at (a huge folder stays quick).
MAX_SCANNED = 2000


def complete_path(text: str, suffixes: tuple[str, ...] = ()) -> str | None:
    """The completion of a partly typed path: the one entry of its folder that starts with
    the typed name (a folder gets a trailing ``/``), or the longest start several share;
    only files ending with one of ``suffixes`` (and folders) when given; hidden entries
    only when the name typed starts with ``.``. ``None`` when nothing longer fits."""
    if not text:
        return None
    expanded = os.path.expanduser(text)
    folder, separator, start = expanded.rpartition(os.sep)
    where = Path(folder or os.sep) if separator else Path(".")
    names = []
    try:
        with os.scandir(where) as entries:
            for count, entry in enumerate(entries):
                if count >= MAX_SCANNED:
                    break
                hidden = entry.name.startswith(".") and not start.startswith(".")
                if hidden or not entry.name.startswith(start):
                    continue
                is_dir = entry.is_dir()
                if is_dir or not suffixes or entry.name.endswith(suffixes):
                    names.append(entry.name + ("/" if is_dir else ""))
    except OSError:
        return None
    if not names:
        return None
    rest = names[0] if len(names) == 1 else os.path.commonprefix(sorted(names))  # noqa: RUF071 (names, not paths)
    if len(rest) <= len(start):
        return None
    typed_folder = text[: len(text) - len(start)]
    return typed_folder + rest


class PathSuggester(Suggester):
    """Textual's suggester over :func:`complete_path` (no cache: the folder may change)."""

    def __init__(self, suffixes: tuple[str, ...] = ()):
        super().__init__(use_cache=False, case_sensitive=True)
        self.suffixes = suffixes

    async def get_suggestion(self, value: str) -> str | None:
        return complete_path(value, self.suffixes)


class FilePicker(ModalScreen[str | None]):
    """A path field with completion over a list of choices (``(label, path)`` pairs, in
    sections with a heading each); dismisses with the path, or ``None`` on Escape."""

    BINDINGS: ClassVar = [
        Binding("escape", "dismiss_none", "Cancel"),
        Binding("down", "to_list", "List", show=False),
    ]
    DEFAULT_CSS = """
    FilePicker > Vertical { width: 90%; max-width: 100; height: 90%; }
    FilePicker OptionList { height: 1fr; }
    """

    def __init__(
        self,
        title: str,
        value: str,
        sections: list[tuple[str, list[tuple[str, str]]]],
        suffixes: tuple[str, ...],
        hint: str = "",
    ):
        super().__init__()
        self.title_text, self.value, self.sections = title, value, sections
        self.suffixes, self.hint = suffixes, hint

    def compose(self) -> ComposeResult:
        options: list[Option | None] = []
        for heading, entries in self.sections:
            if not entries:
                continue
            if options:
                options.append(None)
            options.append(Option(heading, disabled=True))
            options += [Option(f"  {label}", id=path) for label, path in entries]
        with Vertical(classes="dialog"):
            yield Label(self.title_text, classes="dialog-title")
            yield Input(self.value, id="path-input", suggester=PathSuggester(self.suffixes))
            yield OptionList(*options, id="picker-list")
            yield Static(
                self.hint or "Enter: open   ↓: the list   →: complete   Escape: cancel",
                classes="dialog-hint",
                markup=False,
            )

    def on_input_submitted(self, event: Input.Submitted) -> None:
        self.dismiss(event.value.strip() or None)

    def on_option_list_option_selected(self, event: OptionList.OptionSelected) -> None:
        if event.option.id:
            self.dismiss(event.option.id)

    def action_to_list(self) -> None:
        if isinstance(self.focused, Input):
            self.query_one(OptionList).focus()

    def action_dismiss_none(self) -> None:
        self.dismiss(None)


def preset_picker(current: Path) -> FilePicker:
    """The ``ctrl+o`` picker: recent presets, then the bundled ones (name — description)."""
    recent_entries = [(str(p), str(p)) for p in recent("presets")]
    bundled = [(f"{p.stem} — {preset_description(p)}", p.stem) for p in bundled_presets()]
    return FilePicker(
        "Open preset (a path, or pick one)",
        str(current),
        [("Recent", recent_entries), ("Bundled presets", bundled)],
        (".toml",),
    )


def result_picker(folder: Path) -> FilePicker:
    """The history's ``o``: a result CSV (recent ones listed)."""
    entries = [(str(p), str(p)) for p in recent("results")]
    return FilePicker(
        "Open a result CSV into the history",
        f"{folder}{os.sep}",
        [("Recent results", entries)],
        (".csv",),
        "Its sidecar (NAME.csv.json) gives its settings.   Enter: open   Escape: cancel",
    )

"""Form widgets that turn what is typed into plain TOML values (validation is the CLI's).

Text that parses as a TOML value becomes that value (``[1, 2]``, ``"x"``, ``0.5``);
other text stays a string (``singular`` → ``"singular"``), so a typo such as ``0.3.1``
reaches the preset parser as a string and gets the CLI's own message.
"""

from __future__ import annotations

import tomllib
from collections.abc import Collection, Sequence
from typing import Any, ClassVar

from textual import events
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Grid
from textual.message import Message
from textual.widget import Widget
from textual.widgets import Input, Label, Static, TextArea

from planar_tui.preset_writer import format_value
from planar_tui.schema import REQUIRED, declared_keys


def parse_field(text: str) -> Any:
    """A TOML value from a field's text; unparseable text is kept as a string (also text
    the TOML parser chokes on: 600 ``[`` are a ``RecursionError``, an integer of 5000
    digits a ``ValueError``), so the preset parser names the field."""
    text = text.strip()
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except (tomllib.TOMLDecodeError, RecursionError, ValueError):
        return text


class KeysInOrder:
    """Keys typed into a field apply in the order typed, even in a burst the app reads
    faster than the field handles it.

    Textual queues a printable key on the widget focused when the app reads it, but runs
    a key's binding (``end``, ``ctrl+u``) on the widget focused when the key is handled:
    ``200 Tab End ctrl+u 1e-5`` typed quickly gave ``duration_s = 2001e-5`` and emptied
    ``step_s``. Here a field handles every key itself, in its queue's order: Tab and
    shift+Tab move the focus at once, its own bindings run on it, and a key that reaches
    it after the focus has moved on is passed to the widget focused now.
    """

    async def on_key(self, event: events.Key) -> None:
        screen = self.screen
        focused = screen.focused
        if focused is not self:
            if focused is not None:  # typed after a key that moved the focus: follow it
                event.stop()
                event.prevent_default()
                again = events.Key(event.key, event.character)
                again._set_forwarded()  # no public hook: else the app takes it as new input
                focused.post_message(again)
            return
        if event.key in ("tab", "shift+tab"):
            event.stop()
            event.prevent_default()
            screen.focus_next() if event.key == "tab" else screen.focus_previous()
            return
        active = screen.active_bindings.get(event.key)
        if active is not None and active.node is self and not active.binding.priority:
            event.stop()  # the field's own binding (the app ran the priority ones already)
            event.prevent_default()
            await self.run_action(active.binding.action)


class Field(KeysInOrder, TextArea):
    """A one-value text field that wraps long values (``[[20, 70], [110, 160], …]``) onto
    more lines instead of hiding their end; Enter moves to the next field.

    Enter is one of the field's own bindings, handled before the text area inserts a key
    (:class:`KeysInOrder`), so no line break is ever inserted (a value is one line); the
    keys that move and delete to a line's start or end act on the whole value, not on the
    row it wraps onto. A field marked bad (``-bad``) keeps the width its text wraps in:
    its right border takes the place of the padding (the text area re-wraps on a resize
    only, not when a border changes its content width).
    """

    BINDINGS: ClassVar = [
        Binding("enter", "next_field", "Next field", show=False),
        # the whole value, not the row it wraps onto (a value is one line of text)
        Binding("home,ctrl+a", "value_start", "Start of the value", show=False),
        Binding("end,ctrl+e", "value_end", "End of the value", show=False),
        Binding("shift+home", "value_start(True)", "Select to the start", show=False),
        Binding("shift+end", "value_end(True)", "Select to the end", show=False),
        Binding("ctrl+u", "delete_to_value_start", "Delete to the start", show=False),
        Binding("ctrl+k", "delete_to_value_end", "Delete to the end", show=False),
    ]

    DEFAULT_CSS = """
    Field { height: auto; max-height: 6; width: 1fr; padding: 0 1 0 0;
            border: none; border-left: blank; }
    Field:focus { background: $boost; border: none; border-left: thick $accent; }
    Field.-bad { border: tall $error; border-left: thick $error; padding: 0; }
    Field.-bad:focus { border: tall $error; border-left: thick $accent; padding: 0; }
    """

    def __init__(self, value: str = "", **kwargs: Any):
        super().__init__(value, soft_wrap=True, highlight_cursor_line=False, **kwargs)

    @property
    def visible_siblings(self) -> list[Widget]:
        """None: a field hidden while it has the focus (its tab left, its form hidden)
        hands the focus to no other field. Textual hands it to a focusable sibling, the
        next field of the same hidden form (a form's fields are siblings), and that
        field's tab was shown again."""
        return []

    @property
    def value(self) -> str:
        """The text, as :class:`~textual.widgets.Input` calls it."""
        return self.text

    @value.setter
    def value(self, text: str) -> None:
        self.text = text

    def action_next_field(self) -> None:
        """Move the focus on, like Tab in a form."""
        self.screen.focus_next()

    def action_value_start(self, select: bool = False) -> None:
        """The cursor to the value's first character (TextArea's ``home`` stops at the
        start of the wrapped row)."""
        self.move_cursor((0, 0), select=select)

    def action_value_end(self, select: bool = False) -> None:
        """The cursor past the value's last character (not the wrapped row's)."""
        self.move_cursor(self.document.end, select=select)

    def action_delete_to_value_start(self) -> None:
        """Delete from the cursor to the value's start (``ctrl+u``), every wrapped row."""
        self.delete((0, 0), self.cursor_location)

    def action_delete_to_value_end(self) -> None:
        """Delete from the cursor to the value's end (``ctrl+k``), every wrapped row."""
        self.delete(self.cursor_location, self.document.end)


class TableForm(Widget):
    """One labelled input per key of a TOML table (keys absent from the table stay empty
    and are left out, so the parser's defaults apply).

    A key is three widgets side by side in the form (its label, field and error note),
    no container of its own: a container per key made building a form a third slower
    (the Robot tab's 50 keys). The focused field's label is shown bold (``-current``).
    """

    DEFAULT_CSS = """
    TableForm { height: auto; }
    TableForm Label { width: 1fr; color: $text-muted; }
    TableForm Label.-current { color: $text; text-style: bold; }
    TableForm .field-error { color: $text-error; display: none; }
    TableForm .field-error.-shown { display: block; }
    """

    class Changed(Message):
        """The table was edited."""

        def __init__(self, form: TableForm, table: dict[str, Any]):
            super().__init__()
            self.form = form
            self.table = table

        @property
        def control(self) -> TableForm:
            return self.form

    def __init__(
        self,
        keys: Sequence[str],
        table: dict[str, Any],
        required: Collection[str] = (),
        **kwargs: Any,
    ):
        super().__init__(**kwargs)
        self.keys = tuple(keys)
        #: The keys without a default: their empty field says ``(required)``.
        self.required = frozenset(required)
        self.extra = {k: v for k, v in table.items() if k not in self.keys}
        self.initial = table

    def compose(self) -> ComposeResult:
        #: The labels, fields and error notes by key (kept: a query on every keystroke's
        #: check cost more than the check itself).
        self.labels: dict[str, Label] = {}
        self.fields: dict[str, Field] = {}
        self.notes: dict[str, Static] = {}
        for key in self.keys:
            value = self.initial.get(key)
            self.labels[key] = Label(key)
            self.fields[key] = Field(
                "" if value is None else format_value(value),
                placeholder="(required)" if key in self.required else "(default)",
                name=key,
                id=f"field-{key}",
            )
            self.notes[key] = Static("", id=f"error-{key}", classes="field-error", markup=False)
            yield from (self.labels[key], self.fields[key], self.notes[key])

    def on_descendant_focus(self, event: events.DescendantFocus) -> None:
        """The focused field's label in bold."""
        self._show_current(event.widget, True)

    def on_descendant_blur(self, event: events.DescendantBlur) -> None:
        self._show_current(event.widget, False)

    def _show_current(self, widget: Widget, current: bool) -> None:
        label = self.labels.get(widget.name or "")
        if label is not None and self.fields[widget.name or ""] is widget:
            label.set_class(current, "-current")

    def load(self, table: dict[str, Any]) -> None:
        """Show ``table`` in the fields already there (an undo: no rebuild, the focus and
        the fields' cursors stay; no :class:`Changed` is posted for it)."""
        self.extra = {k: v for k, v in table.items() if k not in self.keys}
        self.initial = table
        for key, field in self.fields.items():
            value = table.get(key)
            text = "" if value is None else format_value(value)
            if field.text != text:
                field.text = text
                field.move_cursor(field.document.end)
        self._last = self.table()

    def mark(self, key: str, message: str) -> Field | None:
        """Mark the field of ``key`` as invalid (red border, ``message`` under it); returns
        the field, ``None`` when the form has no such key."""
        if key not in self.keys:
            return None
        field = self.fields[key]
        field.add_class("-bad")
        note = self.notes[key]
        note.update(f"▲ {message}")
        note.add_class("-shown")
        return field

    def clear_marks(self) -> None:
        """Remove every invalid mark."""
        for field in self.fields.values():
            if field.has_class("-bad"):  # (an unchanged class costs nothing to restyle)
                field.remove_class("-bad")
        for note in self.notes.values():
            if note.has_class("-shown"):
                note.remove_class("-shown")

    def table(self) -> dict[str, Any]:
        """The table as typed (empty fields left out)."""
        table = dict(self.extra)
        for key, field in getattr(self, "fields", {}).items():
            if field.value.strip():
                table[key] = parse_field(field.value)
        return table

    def on_mount(self) -> None:
        self._last = self.table()

    def on_text_area_changed(self, event: TextArea.Changed) -> None:
        event.stop()
        table = self.table()
        if table != getattr(self, "_last", table):  # not the inputs' initial values
            self._last = table
            self.post_message(self.Changed(self, table))


class LinkCell(KeysInOrder, Input):
    """A cell of the link table (keys in the order typed, :class:`KeysInOrder`)."""


def required_keys(settings_class: type) -> frozenset[str]:
    """The keys of a settings dataclass that have no default (a job's must-give keys)."""
    return frozenset(
        key.name for _, key in declared_keys(settings_class) if key.default is REQUIRED
    )


class LinkEditor(Widget):
    """The serial robot's links as rows of inputs: length (m), mass (kg), inertia (kg m²).

    An empty inertia column means slender rods (``m l² / 12``, the parser's default).
    """

    DEFAULT_CSS = """
    LinkEditor { height: auto; }
    LinkEditor Grid { grid-size: 4; grid-columns: 6 1fr 1fr 1fr; height: auto;
                      grid-rows: 1; grid-gutter: 0 1; }
    LinkEditor Input, LinkEditor Input:focus { border: none; height: 1; padding: 0 1 0 0;
                                               border-left: blank; }
    LinkEditor Input:focus { background: $boost; text-style: bold; border-left: thick $accent; }
    LinkEditor Input.-bad { text-style: reverse; color: $text-error; }
    LinkEditor #links-error { color: $text-error; display: none; }
    LinkEditor #links-error.-shown { display: block; }
    """

    COLUMNS = (("lengths_m", "length m"), ("masses_kg", "mass kg"), ("inertias_kgm2", "I kg m²"))

    class Changed(Message):
        """The links were edited: ``values`` maps ``lengths_m``/``masses_kg``/
        ``inertias_kgm2`` to lists (inertias left out when every cell is empty)."""

        def __init__(self, editor: LinkEditor, values: dict[str, Any]):
            super().__init__()
            self.editor = editor
            self.values = values

        @property
        def control(self) -> LinkEditor:
            return self.editor

    def __init__(self, robot_table: dict[str, Any], **kwargs: Any):
        super().__init__(**kwargs)
        self.rows = self._rows_of(robot_table)

    @classmethod
    def column_keys(cls) -> tuple[str, ...]:
        """The robot keys the grid edits."""
        return tuple(key for key, _ in cls.COLUMNS)

    @classmethod
    def _rows_of(cls, table: dict[str, Any]) -> list[list[str]]:
        columns = [table.get(key, []) for key, _ in cls.COLUMNS]
        columns = [c if isinstance(c, list) else [c] for c in columns]
        n = max(len(c) for c in columns) if any(columns) else 1
        return [[format_value(c[i]) if i < len(c) else "" for c in columns] for i in range(n)]

    def compose(self) -> ComposeResult:
        #: The cells, row by row, and the error line (kept: each edit's check marks them).
        self.cells: list[LinkCell] = []
        self.error_line = Static("", id="links-error", markup=False)
        with Grid():
            yield Label("link")
            for _, title in self.COLUMNS:
                yield Label(title)
            for i, row in enumerate(self.rows):
                yield Label(f"{i + 1}")
                for (key, title), text in zip(self.COLUMNS, row, strict=True):
                    self.cells.append(
                        LinkCell(text, name=key, id=f"link-{i + 1}-{key}", tooltip=title)
                    )
                    yield self.cells[-1]
        yield self.error_line

    def mark(self, key: str, item: int | None, message: str) -> Input | None:
        """Mark the cell of link ``item`` (1-based) in column ``key``, or the whole column
        when ``item`` is ``None``, with ``message`` under the grid; returns the first
        marked cell (``None`` when ``key`` is not a column)."""
        cells = [
            cell
            for cell in self.cells
            if cell.name == key and (item is None or cell.id == f"link-{item}-{key}")
        ]
        for cell in cells:
            cell.add_class("-bad")
        if not cells:
            return None
        note = self.error_line
        note.update(f"▲ {message}")
        note.add_class("-shown")
        return cells[0]

    def clear_marks(self) -> None:
        """Remove every invalid mark."""
        for cell in self.cells:
            if cell.has_class("-bad"):
                cell.remove_class("-bad")
        self.error_line.remove_class("-shown")

    def current_rows(self) -> list[list[str]]:
        """The text of every cell, row by row."""
        cells = getattr(self, "cells", [])
        width = len(self.COLUMNS)
        return [[c.value for c in cells[i : i + width]] for i in range(0, len(cells), width)]

    def values(self) -> dict[str, Any]:
        """The link arrays as typed (numbers where the text is a number)."""
        rows = self.current_rows()
        values: dict[str, Any] = {}
        for column, (key, _) in enumerate(self.COLUMNS):
            cells = [row[column].strip() for row in rows]
            if key == "inertias_kgm2" and not any(cells):
                continue
            values[key] = [parse_field(cell) if cell else "" for cell in cells]
        return values

    async def set_rows(self, rows: list[list[str]]) -> None:
        """Rebuild the grid with ``rows`` (after adding or removing a link)."""
        self.rows = rows
        await self.recompose()
        self._last = self.values()
        self.post_message(self.Changed(self, self._last))

    async def load(self, robot_table: dict[str, Any]) -> None:
        """Show ``robot_table``'s links (an undo): the cells updated in place, the grid
        rebuilt only when the link count differs; no :class:`Changed` is posted for it."""
        rows = self._rows_of(robot_table)
        if len(rows) != len(self.current_rows()):
            self.rows = rows
            await self.recompose()
        else:
            for cell, text in zip(self.cells, (text for row in rows for text in row), strict=True):
                if cell.value != text:
                    cell.value = text
        self._last = self.values()

    async def add_link(self) -> None:
        """Append a link copying the last one."""
        rows = self.current_rows()
        await self.set_rows([*rows, list(rows[-1]) if rows else ["0.2", "0.5", ""]])

    async def remove_link(self) -> None:
        """Remove the last link (one link always stays)."""
        rows = self.current_rows()
        if len(rows) > 1:
            await self.set_rows(rows[:-1])

    def on_mount(self) -> None:
        self._last = self.values()

    def on_input_changed(self, event: Input.Changed) -> None:
        event.stop()
        values = self.values()
        if values != getattr(self, "_last", values):  # not the inputs' initial values
            self._last = values
            self.post_message(self.Changed(self, values))

"""Form widgets that turn what is typed into plain TOML values (validation is the CLI's).

Text that parses as a TOML value becomes that value (``[1, 2]``, ``"x"``, ``0.5``);
other text stays a string (``singular`` → ``"singular"``), so a typo such as ``0.3.1``
reaches the preset parser as a string and gets the CLI's own message.
"""

from __future__ import annotations

import tomllib
from collections.abc import Sequence
from typing import Any, ClassVar

from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Grid, Vertical
from textual.message import Message
from textual.widget import Widget
from textual.widgets import Input, Label, Static, TextArea

from planar_tui.preset_writer import format_value


def parse_field(text: str) -> Any:
    """A TOML value from a field's text; unparseable text is kept as a string (also text
    the TOML parser chokes on: 600 ``[`` are a ``RecursionError``, an integer of 5000
    digits a ``ValueError``), so the preset parser names the field."""
    text = text.strip()
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except (tomllib.TOMLDecodeError, RecursionError, ValueError):
        return text


class Field(TextArea):
    """A one-value text field that wraps long values (``[[20, 70], [110, 160], …]``) onto
    more lines instead of hiding their end; Enter moves to the next field.

    Enter is a priority binding: Textual checks it before the key reaches the text area,
    so no line break is ever inserted (a value is one line).
    """

    BINDINGS: ClassVar = [
        Binding("enter", "next_field", "Next field", show=False, priority=True),
    ]

    DEFAULT_CSS = """
    Field { height: auto; max-height: 6; width: 1fr; padding: 0 1 0 0;
            border: none; border-left: blank; }
    Field:focus { background: $boost; border: none; border-left: thick $accent; }
    Field.-bad { border: tall $error; border-left: thick $error; }
    Field.-bad:focus { border: tall $error; border-left: thick $accent; }
    """

    def __init__(self, value: str = "", **kwargs: Any):
        super().__init__(value, soft_wrap=True, highlight_cursor_line=False, **kwargs)

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


class TableForm(Widget):
    """One labelled input per key of a TOML table (keys absent from the table stay empty
    and are left out, so the parser's defaults apply)."""

    DEFAULT_CSS = """
    TableForm { height: auto; }
    TableForm Vertical { height: auto; }
    TableForm Label { width: 1fr; color: $text-muted; }
    TableForm Vertical:focus-within > Label { color: $text; text-style: bold; }
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

    def __init__(self, keys: Sequence[str], table: dict[str, Any], **kwargs: Any):
        super().__init__(**kwargs)
        self.keys = tuple(keys)
        self.extra = {k: v for k, v in table.items() if k not in self.keys}
        self.initial = table

    def compose(self) -> ComposeResult:
        for key in self.keys:
            value = self.initial.get(key)
            with Vertical():
                yield Label(key)
                yield Field(
                    "" if value is None else format_value(value),
                    placeholder="(default)",
                    name=key,
                    id=f"field-{key}",
                )
                yield Static("", id=f"error-{key}", classes="field-error", markup=False)

    def mark(self, key: str, message: str) -> Field | None:
        """Mark the field of ``key`` as invalid (red border, ``message`` under it); returns
        the field, ``None`` when the form has no such key."""
        if key not in self.keys:
            return None
        field = self.query_one(f"#field-{key}", Field)
        field.add_class("-bad")
        note = self.query_one(f"#error-{key}", Static)
        note.update(f"▲ {message}")
        note.add_class("-shown")
        return field

    def clear_marks(self) -> None:
        """Remove every invalid mark."""
        for field in self.query(Field).filter(".-bad"):
            field.remove_class("-bad")
        for note in self.query(".field-error.-shown"):
            note.remove_class("-shown")

    def table(self) -> dict[str, Any]:
        """The table as typed (empty fields left out)."""
        table = dict(self.extra)
        for field in self.query(Field):
            if field.value.strip():
                table[field.name] = parse_field(field.value)
        return table

    def on_mount(self) -> None:
        self._last = self.table()

    def on_text_area_changed(self, event: TextArea.Changed) -> None:
        event.stop()
        table = self.table()
        if table != getattr(self, "_last", table):  # not the inputs' initial values
            self._last = table
            self.post_message(self.Changed(self, table))


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
        with Grid():
            yield Label("link")
            for _, title in self.COLUMNS:
                yield Label(title)
            for i, row in enumerate(self.rows):
                yield Label(f"{i + 1}")
                for (key, title), text in zip(self.COLUMNS, row, strict=True):
                    yield Input(text, name=key, id=f"link-{i + 1}-{key}", tooltip=title)
        yield Static("", id="links-error", markup=False)

    def mark(self, key: str, item: int | None, message: str) -> Input | None:
        """Mark the cell of link ``item`` (1-based) in column ``key``, or the whole column
        when ``item`` is ``None``, with ``message`` under the grid; returns the first
        marked cell (``None`` when ``key`` is not a column)."""
        cells = [
            cell
            for cell in self.query(Input)
            if cell.name == key and (item is None or cell.id == f"link-{item}-{key}")
        ]
        for cell in cells:
            cell.add_class("-bad")
        if not cells:
            return None
        note = self.query_one("#links-error", Static)
        note.update(f"▲ {message}")
        note.add_class("-shown")
        return cells[0]

    def clear_marks(self) -> None:
        """Remove every invalid mark."""
        for cell in self.query(Input).filter(".-bad"):
            cell.remove_class("-bad")
        self.query_one("#links-error").remove_class("-shown")

    def current_rows(self) -> list[list[str]]:
        """The text of every cell, row by row."""
        cells = list(self.query(Input))
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

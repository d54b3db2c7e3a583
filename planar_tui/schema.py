"""Preset keys: declared once, read with one clear error per problem, written back.

A robot kind or job kind declares its settings as a frozen dataclass whose fields carry a
:class:`Key` in their metadata (made with :func:`setting`): the key's TOML name, how it is
read and checked (a :class:`TableReader` call with today's messages), its default, and a
one-line meaning. That one declaration drives

* parsing (:func:`parse_settings`: every key in declaration order, then the class's
  optional ``check(values, reader, context)`` hook for rules between keys),
* dumping (:func:`dump_settings`: the TOML table a saved preset holds),
* the allowed keys (:func:`setting_keys`: unknown keys are refused with a suggestion),
* the README's preset tables (:func:`markdown_table`, checked by ``tests/test_schema.py``)
* and the app's form (the keys, in order, with their meaning as a tooltip).

Fields without a :class:`Key` are derived values (e.g. the solved isotropic posture).
"""

from __future__ import annotations

import dataclasses
import difflib
import math
import os
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from planar_tui.errors import PresetError

_MISSING: Any = object()


def type_name(value: Any) -> str:
    """How a TOML value's type is named in messages (``an integer``, ``a table``)."""
    return {
        bool: "a boolean",
        int: "an integer",
        float: "a number",
        str: "a string",
        list: "an array",
        dict: "a table",
    }.get(type(value), type(value).__name__)


#: Largest integer a preset may hold anywhere (a signed 64-bit integer: NumPy and the
#: kernels count in int64).
INT64_MAX = 2**63 - 1
#: Longest file-name component (bytes, UTF-8) and path (bytes) an output may have, where
#: the file system does not say (POSIX ``NAME_MAX`` and Linux ``PATH_MAX``).
NAME_MAX_BYTES = 255
PATH_MAX_BYTES = 4096


def shown(value: Any) -> str:
    """``repr(value)`` for a message, with a very long integer or string shortened."""
    if isinstance(value, int) and not isinstance(value, bool) and abs(value) >= 10**15:
        digits = len(str(abs(value)))
        return f"{str(value)[:6]}... ({digits} digits)"
    text = repr(value)
    return text if len(text) <= 80 else f"{text[:60]}... ({len(text)} characters)"


def file_name_problem(value: str) -> str | None:
    """Why ``value`` cannot be a file path on a usual file system, or ``None``: a NUL
    character, a component longer than :data:`NAME_MAX_BYTES` or a path longer than
    :data:`PATH_MAX_BYTES` (bytes in the file system's encoding, UTF-8 on Linux and macOS)."""
    if "\0" in value:
        return "holds a NUL character"
    try:
        encoded = os.fsencode(value)
    except UnicodeEncodeError:
        return "is not valid text in the file system's encoding"
    if len(encoded) > PATH_MAX_BYTES:
        return f"is {len(encoded)} bytes long, longer than a path may be ({PATH_MAX_BYTES})"
    for part in encoded.split(b"/"):
        if len(part) > NAME_MAX_BYTES:
            return (
                f"has a name of {len(part)} bytes, longer than a file name may be "
                f"({NAME_MAX_BYTES})"
            )
    return None


def suggest(name: str, allowed: Iterable[str]) -> str:
    """``; did you mean X?`` for the closest allowed name, or nothing."""
    close = difflib.get_close_matches(name, list(allowed), n=1, cutoff=0.6)
    return f"; did you mean {close[0]}?" if close else ""


class TableReader:
    """Typed, validated access to one TOML table of a preset.

    Unknown keys are rejected as soon as the reader is made, so a typo is reported as
    such rather than as a missing key. Every getter raises :class:`PresetError` naming
    the file, the dotted key and what was expected.

    Parameters
    ----------
    path
        The preset file (for messages).
    table
        The parsed TOML table.
    prefix
        Dotted name of the table (``"robot"``, ``"simulate[2]"``), prefixed to keys.
    allowed
        Every key the table may hold.
    """

    def __init__(
        self, path: Path | str, table: Mapping[str, Any], prefix: str, allowed: Sequence[str]
    ):
        self.path = Path(path)
        self.table = table
        self.prefix = prefix
        self.allowed = tuple(allowed)
        for name in table:
            if name not in self.allowed:
                raise self.error(
                    name,
                    "unknown key",
                    "one of " + ", ".join(self.allowed) + suggest(name, self.allowed),
                )

    # -- plumbing -----------------------------------------------------------------
    def key(self, name: str) -> str:
        """The dotted key of ``name`` in this table."""
        return f"{self.prefix}.{name}" if self.prefix else name

    def error(self, name: str, problem: str, expected: str | None = None) -> PresetError:
        """A :class:`PresetError` about key ``name`` of this table."""
        return PresetError(self.path, self.key(name), problem, expected)

    def has(self, name: str) -> bool:
        """Whether the table holds key ``name``."""
        return name in self.table

    def raw(self, name: str, default: Any = _MISSING, expected: str = "a value") -> Any:
        """The value of ``name``, ``default`` if absent, or a 'missing key' error."""
        if name in self.table:
            return self.table[name]
        if default is _MISSING:
            raise self.error(name, "missing key", expected)
        return default

    # -- scalars ------------------------------------------------------------------
    def _check_number(
        self,
        name: str,
        value: Any,
        *,
        positive: bool,
        minimum: float | None,
        maximum: float | None,
        where: str = "",
    ) -> float:
        wanted = "a positive number" if positive else "a number"
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise self.error(name, f"{where}is {type_name(value)}", wanted)
        try:
            number = float(value)
        except OverflowError:  # an integer beyond the largest float (about 1.8e308)
            number = math.inf if value > 0 else -math.inf
        if not math.isfinite(number):
            raise self.error(name, f"{where}is {shown(value)}, not a finite number", wanted)
        if positive and number <= 0:
            raise self.error(name, f"{where}is {shown(value)}, must be > 0", wanted)
        if minimum is not None and number < minimum:
            raise self.error(
                name, f"{where}is {shown(value)}, below the minimum", f">= {minimum:g}"
            )
        if maximum is not None and number > maximum:
            raise self.error(
                name, f"{where}is {shown(value)}, above the maximum", f"<= {maximum:g}"
            )
        return number

    def number(
        self,
        name: str,
        default: Any = _MISSING,
        *,
        positive: bool = False,
        minimum: float | None = None,
        maximum: float | None = None,
    ) -> float:
        """A finite float (TOML integer or float), optionally > 0 or within bounds."""
        value = self.raw(name, default, "a positive number" if positive else "a number")
        if value is default and default is not _MISSING:
            return value
        return self._check_number(name, value, positive=positive, minimum=minimum, maximum=maximum)

    def integer(
        self,
        name: str,
        default: Any = _MISSING,
        *,
        minimum: int | None = None,
        maximum: int = INT64_MAX,
    ) -> int:
        """A TOML integer, optionally >= ``minimum``, at most ``maximum`` (64-bit)."""
        wanted = "an integer" if minimum is None else f"an integer >= {minimum}"
        value = self.raw(name, default, wanted)
        if value is default and default is not _MISSING:
            return value
        if isinstance(value, bool) or not isinstance(value, int):
            raise self.error(name, f"is {type_name(value)}", wanted)
        if minimum is not None and value < minimum:
            raise self.error(name, f"is {shown(value)}", wanted)
        if value > maximum:
            raise self.error(
                name, f"is {shown(value)}, above the maximum", f"{wanted} and <= {maximum:,}"
            )
        return value

    def string(
        self, name: str, default: Any = _MISSING, *, choices: Sequence[str] | None = None
    ) -> str:
        """A TOML string, optionally one of ``choices``."""
        wanted = "one of " + ", ".join(choices) if choices else "a string"
        value = self.raw(name, default, wanted)
        if value is default and default is not _MISSING:
            return value
        if not isinstance(value, str):
            raise self.error(name, f"is {type_name(value)}", wanted)
        if choices is not None and value not in choices:
            raise self.error(name, f"is {shown(value)}", wanted + suggest(value, choices))
        return value

    def relative_path(self, name: str, default: Any = _MISSING) -> str:
        """A file name relative to the output folder (not absolute, no ``..``)."""
        value = self.string(name, default)
        if value is default and default is not _MISSING:
            return value
        if not value or Path(value).is_absolute() or ".." in Path(value).parts:
            raise self.error(
                name, f"is {shown(value)}", "a file name relative to the output folder"
            )
        problem = file_name_problem(value)
        if problem is not None:
            raise self.error(name, problem, "a file name the file system accepts")
        return value

    def boolean(self, name: str, default: Any = _MISSING) -> bool:
        """A TOML boolean."""
        value = self.raw(name, default, "true or false")
        if not isinstance(value, bool):
            raise self.error(name, f"is {type_name(value)}", "true or false")
        return value

    # -- arrays -------------------------------------------------------------------
    def numbers(
        self,
        name: str,
        default: Any = _MISSING,
        *,
        length: int | None = None,
        positive: bool = False,
        minimum: float | None = None,
        maximum: float | None = None,
        non_empty: bool = True,
        items_doc: str | None = None,
    ) -> tuple[float, ...]:
        """An array of finite numbers, optionally of a given length and > 0. ``items_doc``
        is what a wrong length is told to expect (default ``"<length>, one per link"``), e.g.
        ``"3 signs, each 1 or -1 (one per leg)"`` or ``"[x, y]"``."""
        kind = "positive numbers" if positive else "numbers"
        wanted = f"an array of {length} {kind}" if length is not None else f"an array of {kind}"
        value = self.raw(name, default, wanted)
        if value is default and default is not _MISSING:
            return value
        if not isinstance(value, list):
            raise self.error(name, f"is {type_name(value)}", wanted)
        if length is not None and len(value) != length:
            raise self.error(
                name, f"has {len(value)} values", items_doc or f"{length}, one per link"
            )
        if non_empty and not value:
            raise self.error(name, "is empty", wanted)
        return tuple(
            self._check_number(
                name,
                item,
                positive=positive,
                minimum=minimum,
                maximum=maximum,
                where=f"item {i + 1} ",
            )
            for i, item in enumerate(value)
        )

    def number_rows(
        self,
        name: str,
        default: Any = _MISSING,
        *,
        columns: int | None = None,
        row_doc: str | None = None,
    ) -> tuple[tuple[float, ...], ...]:
        """A non-empty array of arrays of finite numbers, each with ``columns`` values.
        ``row_doc`` is what a row of the wrong length is told to expect (default
        ``"<columns>, one per link"``), e.g. ``"[min, max]"`` or ``"[x, y]"``."""
        wanted = f"an array of arrays of {columns} numbers" if columns else "an array of arrays"
        value = self.raw(name, default, wanted)
        if value is default and default is not _MISSING:
            return value
        if not isinstance(value, list) or not value:
            raise self.error(name, f"is {type_name(value) if value != [] else 'empty'}", wanted)
        rows = []
        for r, row in enumerate(value):
            if not isinstance(row, list):
                raise self.error(name, f"row {r + 1} is {type_name(row)}", wanted)
            if columns is not None and len(row) != columns:
                raise self.error(
                    name,
                    f"row {r + 1} has {len(row)} values",
                    row_doc or f"{columns}, one per link",
                )
            rows.append(
                tuple(
                    self._check_number(
                        name,
                        item,
                        positive=False,
                        minimum=None,
                        maximum=None,
                        where=f"row {r + 1} ",
                    )
                    for item in row
                )
            )
        return tuple(rows)


class OptionReader(TableReader):
    """Command-line options read with the preset keys' own readers, so that an option is
    checked exactly as its key is (whatever else the run asks for); errors name the file
    ``command line`` and the option (``--samples``)."""

    def __init__(self, options: Mapping[str, Any], option_names: Mapping[str, str]):
        self.option_names = dict(option_names)
        super().__init__("command line", options, "", tuple(options))

    def key(self, name: str) -> str:
        return self.option_names.get(name, "--" + name.replace("_", "-"))


def read_option(settings_class: type, reader: TableReader, attribute: str) -> Any:
    """The value of one declared key of ``settings_class`` read from ``reader`` with the
    key's reader (no default: the option was given)."""
    key = dict(declared_keys(settings_class))[attribute]
    return key.read(reader, key.name, REQUIRED, None, {})


# -- declarations ---------------------------------------------------------------------
#: A key without a default must be present in the table.
REQUIRED: Any = _MISSING

#: ``Numbers(length=PER_LINK)``: one value per link of the job's robot.
PER_LINK = "per-link"


@dataclass(frozen=True)
class Key:
    """How one preset key is read, written and documented.

    ``read(reader, name, default, context, values)`` returns the checked value (``values``
    holds the keys read before it, ``context`` the job's robot or ``None``); ``dump``
    turns a value back into TOML (``None`` values are left out); ``type_doc`` and
    ``default_doc`` are the README's "type" and "default" cells.
    """

    name: str
    read: Callable[..., Any]
    doc: str
    type_doc: str
    default: Any = REQUIRED
    default_doc: str | None = None
    dump: Callable[[Any], Any] | None = None

    def default_value(self, context: Any, values: Mapping[str, Any]) -> Any:
        """The default (a callable default is called with the context and earlier values)."""
        if callable(self.default):
            return self.default(context, values)
        return self.default

    def to_toml(self, value: Any) -> Any:
        """The value as TOML data: tuples become lists, NumPy scalars Python scalars."""
        return plain(self.dump(value) if self.dump is not None else value)

    def documented_default(self) -> str:
        if self.default_doc is not None:
            return self.default_doc
        if self.default is REQUIRED:
            return "required"
        if self.default is None:
            return "(none)"
        value = plain(self.default)
        return f"`{_toml_literal(value)}`"


def plain(value: Any) -> Any:
    """Nested tuples as lists and NumPy scalars as Python scalars (TOML-ready data)."""
    if isinstance(value, tuple | list):
        return [plain(item) for item in value]
    if isinstance(value, Mapping):
        return {k: plain(v) for k, v in value.items()}
    if hasattr(value, "item") and not isinstance(value, str):
        return value.item()
    return value


def _toml_literal(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, list):
        return "[" + ", ".join(_toml_literal(v) for v in value) + "]"
    return f"{value:g}" if isinstance(value, float) else str(value)


def setting(
    read: Callable[..., Any],
    *,
    doc: str,
    type_doc: str,
    default: Any = REQUIRED,
    default_doc: str | None = None,
    name: str | None = None,
    dump: Callable[[Any], Any] | None = None,
) -> Any:
    """A dataclass field declaring one preset key (``name`` defaults to the field's name).

    A static default becomes the field's default too; a callable default (depending on
    the robot, e.g. one zero per link) or a required key leaves the field without one.
    """
    key = {"read": read, "doc": doc, "type_doc": type_doc, "default": default}
    key |= {"default_doc": default_doc, "dump": dump, "name": name}
    metadata = {"key": key}
    if default is REQUIRED or callable(default):
        return dataclasses.field(metadata=metadata)
    if isinstance(default, list | dict):
        raise TypeError("use a tuple for a sequence default")
    return dataclasses.field(default=default, metadata=metadata)


def declared_keys(settings_class: type) -> tuple[tuple[str, Key], ...]:
    """``(attribute, Key)`` pairs of a settings dataclass, in declaration order."""
    cached = settings_class.__dict__.get("_declared_keys")
    if cached is not None:
        return cached
    pairs = []
    for field in dataclasses.fields(settings_class):
        spec = field.metadata.get("key")
        if spec is not None:
            pairs.append((field.name, Key(**{**spec, "name": spec["name"] or field.name})))
    result = tuple(pairs)
    settings_class._declared_keys = result  # type: ignore[attr-defined]
    return result


def setting_keys(settings_class: type) -> tuple[str, ...]:
    """The preset keys of a settings dataclass, in declaration order."""
    return tuple(key.name for _, key in declared_keys(settings_class))


def parse_settings(settings_class: type, reader: TableReader, context: Any = None) -> Any:
    """Read every declared key of ``settings_class`` from ``reader``, then run the class's
    ``check(values, reader, context) -> values`` hook if it has one, and build it."""
    values: dict[str, Any] = {}
    for attribute, key in declared_keys(settings_class):
        default = key.default_value(context, values) if key.default is not REQUIRED else REQUIRED
        values[attribute] = key.read(reader, key.name, default, context, values)
    check = getattr(settings_class, "check", None)
    if check is not None:
        values = check(values, reader, context)
    return settings_class(**values)


def dump_settings(settings: Any) -> dict[str, Any]:
    """The settings as a TOML table: every declared key whose value is not ``None``."""
    table = {}
    for attribute, key in declared_keys(type(settings)):
        value = getattr(settings, attribute)
        if value is not None:
            table[key.name] = key.to_toml(value)
    return table


def markdown_table(settings_class: type, extra_rows: Sequence[str] = ()) -> str:
    """The README's table of a settings dataclass: key, type, default, meaning (then
    ``extra_rows``, already formatted)."""
    lines = ["| key | type | default | meaning |", "|---|---|---|---|"]
    for _, key in declared_keys(settings_class):
        default = key.documented_default()
        lines.append(f"| `{key.name}` | {key.type_doc} | {default} | {key.doc} |")
    return "\n".join([*lines, *extra_rows])


# -- readers: one per kind of value -----------------------------------------------------
def _length(length: Any, context: Any, values: Mapping[str, Any]) -> int | None:
    if length == PER_LINK:
        return context.n_links
    if isinstance(length, str):
        return len(values[length])
    return length


def number(*, positive: bool = False, minimum: float | None = None, maximum=None):
    """A finite number (TOML integer or float), optionally > 0 or within bounds."""

    def read(reader, name, default, context, values):
        return reader.number(name, default, positive=positive, minimum=minimum, maximum=maximum)

    return read


def integer(*, minimum: int | None = None, maximum: int = INT64_MAX):
    """A TOML integer, optionally >= ``minimum``, at most ``maximum``."""

    def read(reader, name, default, context, values):
        return reader.integer(name, default, minimum=minimum, maximum=maximum)

    return read


def string(*, choices: Sequence[str] | None = None):
    """A TOML string, optionally one of ``choices``."""

    def read(reader, name, default, context, values):
        return reader.string(name, default, choices=choices)

    return read


def boolean():
    """A TOML boolean."""

    def read(reader, name, default, context, values):
        return reader.boolean(name, default)

    return read


def relative_path():
    """A file name relative to the output folder."""

    def read(reader, name, default, context, values):
        return reader.relative_path(name, default)

    return read


def numbers(
    *,
    length: Any = None,
    positive: bool = False,
    minimum: float | None = None,
    maximum: float | None = None,
):
    """An array of finite numbers, optionally > 0 or within bounds; ``length`` is a count,
    :data:`PER_LINK` or the name of an earlier key whose array it must match."""

    def read(reader, name, default, context, values):
        n = _length(length, context, values)
        return reader.numbers(
            name, default, length=n, positive=positive, minimum=minimum, maximum=maximum
        )

    return per_link(read, "list") if length == PER_LINK else read


#: The figure formats a ``plot`` key or ``--plot`` takes, by file suffix.
FIGURE_SUFFIXES = (".svg", ".png", ".pdf")


def figure_suffix_problem(value: str) -> str | None:
    """Why ``value`` cannot name a figure file (its suffix is not one of
    :data:`FIGURE_SUFFIXES`, case-insensitive), or ``None``."""
    suffix = Path(value).suffix
    if suffix.lower() in FIGURE_SUFFIXES:
        return None
    return f"has the suffix {suffix!r}" if suffix else "has no suffix"


def figure_path():
    """A figure file name relative to the output folder, ending ``.svg``, ``.png`` or
    ``.pdf`` (the format)."""

    def read(reader, name, default, context, values):
        value = reader.relative_path(name, default)
        if value is default:
            return value
        problem = figure_suffix_problem(value)
        if problem is not None:
            allowed = ", ".join(FIGURE_SUFFIXES)
            raise reader.error(name, f"is {shown(value)}: {problem}", f"a file ending {allowed}")
        return value

    return read


def plot_setting() -> Any:
    """The ``plot`` key every job table takes (declared here once; each settings class
    holds ``plot: str | None = plot_setting()``): the figure of the job's result, written
    beside its CSV (:mod:`planar_tui.figures`)."""
    return setting(
        figure_path(),
        default=None,
        type_doc="relative path ending `.svg`, `.png` or `.pdf`",
        default_doc="(none)",
        doc="figure of the result, format from the suffix (`--plot FILE` on the command line)",
    )


def number_rows(*, columns: Any = None):
    """A non-empty array of arrays of finite numbers (``columns`` as for :func:`numbers`)."""

    def read(reader, name, default, context, values):
        return reader.number_rows(name, default, columns=_length(columns, context, values))

    return per_link(read, "rows") if columns == PER_LINK else read


def per_link(read: Callable[..., Any], shape: str) -> Callable[..., Any]:
    """Mark a reader as reading one value per link of the robot (``shape`` ``"list"``) or
    rows of one value per link (``"rows"``): what must follow the robot when it gains or
    loses a link (:func:`per_link_keys`)."""
    read.per_link = shape  # type: ignore[attr-defined]
    return read


def per_link_keys(settings_class: type) -> dict[str, str]:
    """The keys of a settings dataclass holding one value per link (``"list"``) or rows of
    them (``"rows"``), by key name, from their readers (:func:`per_link`)."""
    return {
        key.name: getattr(key.read, "per_link")  # noqa: B009 (set by per_link, untyped)
        for _, key in declared_keys(settings_class)
        if getattr(key.read, "per_link", None)
    }


def per_link_zeros(context: Any, values: Mapping[str, Any]) -> tuple[float, ...]:
    """Default of a per-link array: one zero per link."""
    return (0.0,) * context.n_links

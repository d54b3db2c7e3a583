"""Preset keys: declared once, read with one clear error per problem, written back.

A robot kind or job kind declares its settings as a frozen dataclass whose fields carry a
:class:`Key` in their metadata (made with :func:`setting`): the key's TOML name, how it is
read and checked (a :class:`TableReader` call with today's messages), its default, and a
one-line meaning. That one declaration drives

* parsing (:func:`parse_settings`: every key in declaration order, then the class's
  optional ``check(values, reader, context)`` hook for rules between keys),
* dumping (:func:`dump_settings`: the TOML table a saved preset holds),
* the allowed keys (:func:`setting_keys`: unknown keys are refused with a suggestion),
* the preset reference (``docs/gen_reference.py`` writes ``docs/reference/presets.md``)
* and the app's form (the keys, in order, with their meaning as a tooltip).

Fields without a :class:`Key` are derived values (e.g. the solved isotropic posture).
:class:`~planar_tui.reader.TableReader` (and the message helpers, re-exported here for the
key readers of the kinds) lives in :mod:`planar_tui.reader`.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from planar_tui.reader import _MISSING, INT64_MAX
from planar_tui.reader import TableReader as TableReader
from planar_tui.reader import shown as shown
from planar_tui.reader import suggest as suggest
from planar_tui.reader import type_name as type_name

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
    ``default_doc`` are the preset reference's "type" and "default" cells.
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


def mass_setting(doc: str) -> Any:
    """A parallel robot's mass, inertia or gravity key (SI units, the dynamics of its path
    jobs): a number >= 0, default 0 (a massless robot, a horizontal machine)."""
    return setting(number(minimum=0.0), default=0.0, type_doc="number >= 0", doc=doc)


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

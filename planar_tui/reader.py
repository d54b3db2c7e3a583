"""Typed, validated access to one TOML table of a preset (:class:`TableReader`): every
getter checks the value's type and range and raises :class:`~planar_tui.errors.PresetError`
naming the file, the dotted key and what was expected; plus the wording helpers of those
messages (:func:`shown`, :func:`type_name`, :func:`suggest`) and the file-name check
(:func:`file_name_problem`). The key declarations that call it are in
:mod:`planar_tui.schema`.
"""

from __future__ import annotations

import difflib
import math
import os
import stat
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any, BinaryIO

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


class BoundedReadError(OSError):
    """A file :func:`open_bounded` refuses: not a regular file, or larger than its bound
    (the message says which, in words)."""


def _size(n_bytes: int) -> str:
    """``4 MiB``, ``512 KiB``: a bound for messages."""
    return f"{n_bytes / 2**20:.3g} MiB" if n_bytes >= 2**20 else f"{n_bytes / 2**10:.3g} KiB"


def open_bounded(path: Path | str, max_bytes: int, what: str) -> BinaryIO:
    """A binary stream on the regular file ``path`` of at most ``max_bytes`` bytes.

    The file is opened without blocking (a FIFO with no writer does not hang the open)
    and checked on its descriptor before a byte is read: anything but a regular file (a
    FIFO, ``/dev/zero``, a folder) or a file larger than ``max_bytes`` raises
    :class:`BoundedReadError` (``is 4.1e+03 MiB, more than the 4 MiB a preset may have``:
    ``what`` names the file's role). ``FileNotFoundError`` and other ``OSError`` pass.
    """
    descriptor = os.open(path, os.O_RDONLY | os.O_NONBLOCK)
    try:
        status = os.fstat(descriptor)
        if not stat.S_ISREG(status.st_mode):
            raise BoundedReadError("is not a regular file (a device, FIFO or socket)")
        if status.st_size > max_bytes:
            raise BoundedReadError(
                f"is {_size(status.st_size)}, more than the {_size(max_bytes)} {what} may have"
            )
        os.set_blocking(descriptor, True)
        return os.fdopen(descriptor, "rb")
    except BaseException:
        os.close(descriptor)
        raise


def read_bounded_text(path: Path | str, max_bytes: int, what: str) -> str:
    """The UTF-8 text of ``path`` (:func:`open_bounded`); at most ``max_bytes + 1`` bytes
    are ever read, a file that grew past the bound meanwhile is refused too.
    ``UnicodeDecodeError`` when the bytes are not UTF-8."""
    with open_bounded(path, max_bytes, what) as stream:
        data = stream.read(max_bytes + 1)
    if len(data) > max_bytes:
        raise BoundedReadError(f"grew past the {_size(max_bytes)} {what} may have")
    return data.decode("utf-8")


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

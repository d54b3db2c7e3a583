"""Reading a robot file's XML safely, and the refusals' one-line format.

The standard library's XML parser (``xml.parsers.expat`` building
``xml.etree.ElementTree`` elements, with each element's line kept for messages), from one
local file, never the network. A file holding a ``<!DOCTYPE`` or ``<!ENTITY`` is refused
before it is parsed (checked in the raw text, and again by the parser's handlers), so no
entity is ever expanded (no "billion laughs", no external entity); so is one over
:data:`MAX_BYTES` or not UTF-8. :class:`XmlReader` words every refusal of
``planar-tui import`` as one line naming the file, the element (and its line) and why
(:class:`planar_tui.errors.PresetError`); the rules are in :mod:`.robot_import`.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from collections.abc import Sequence
from pathlib import Path
from xml.parsers import expat

import numpy as np

from planar_tui.errors import PresetError

#: Largest file read (bytes): robot descriptions are kilobytes; meshes are not read.
MAX_BYTES = 16 * 1024 * 1024

_FORBIDDEN = ("<!DOCTYPE", "<!ENTITY")


class XmlReader:
    """Errors about one file: ``error(element, problem, expected)``, the element named by
    its tag, its ``name`` and its line."""

    def __init__(self, path: Path | str, lines: dict):
        self.path = path
        self.lines = lines

    @staticmethod
    def named(element: ET.Element) -> str:
        """``<tag name="...">`` (``<tag>`` without a name)."""
        name = element.get("name")
        return f'<{element.tag} name="{name}">' if name is not None else f"<{element.tag}>"

    def where(self, element: ET.Element) -> str:
        """:meth:`named` after the element's line: ``line 12: <joint name="elbow">``."""
        line = self.lines.get(element)
        return f"line {line}: {self.named(element)}" if line else self.named(element)

    def error(self, element: ET.Element | None, problem: str, expected: str | None = None):
        where = "(file)" if element is None else self.where(element)
        return PresetError(self.path, where, problem, expected)

    def numbers(
        self, element: ET.Element, attribute: str, count: int, default: Sequence[float] | None
    ) -> np.ndarray:
        """``count`` finite numbers of an attribute (space-separated), or the default."""
        text = element.get(attribute)
        if text is None:
            if default is None:
                raise self.error(element, f"no {attribute} attribute", f"{count} number(s)")
            return np.array(default, dtype=np.float64)
        try:
            values = [float(item) for item in text.split()]
        except ValueError:
            values = []
        if len(values) != count or not all(math.isfinite(v) for v in values):
            raise self.error(element, f"{attribute} is {text!r}", f"{count} finite number(s)")
        return np.array(values, dtype=np.float64)

    def number(self, element: ET.Element, attribute: str, default: float | None) -> float:
        return float(self.numbers(element, attribute, 1, None if default is None else [default])[0])


def read_xml(path: Path | str) -> tuple[ET.Element, XmlReader]:
    """The file's root element and a :class:`XmlReader` for its messages.

    Refused (:class:`PresetError`): a missing or unreadable file, one over
    :data:`MAX_BYTES`, one not UTF-8, and any ``<!DOCTYPE``/``<!ENTITY`` (checked in the
    raw text before parsing: no entity is ever expanded)."""
    path = Path(path)
    try:
        with open(path, "rb") as stream:
            raw = stream.read(MAX_BYTES + 1)
    except FileNotFoundError:
        raise PresetError(path, "(file)", "no such file", "a URDF or MJCF file") from None
    except OSError as error:
        raise PresetError(path, "(file)", f"cannot be read: {error.strerror or error}") from None
    if len(raw) > MAX_BYTES:
        raise PresetError(
            path,
            "(file)",
            f"is larger than {MAX_BYTES >> 20} MiB",
            "a robot description (meshes are not read)",
        )
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as error:
        raise PresetError(
            path,
            "(file)",
            f"is not UTF-8 text ({error.reason} at byte {error.start})",
            "a UTF-8 XML file",
        ) from None
    upper = text.upper()
    for marker in _FORBIDDEN:
        at = upper.find(marker)
        if at >= 0:
            line = text.count("\n", 0, at) + 1
            raise PresetError(
                path,
                f"line {line}",
                f"has a {marker[2:]} declaration: refused, entities are never expanded",
                "plain URDF or MJCF without a DTD",
            )
    return _parse(path, text)


def _parse(path: Path, text: str) -> tuple[ET.Element, XmlReader]:
    """Parse with expat into ElementTree elements, keeping each element's line."""
    parser = expat.ParserCreate()
    lines: dict[ET.Element, int] = {}
    stack: list[ET.Element] = []
    roots: list[ET.Element] = []

    def start(tag, attributes):
        element = ET.Element(tag, attributes)
        lines[element] = parser.CurrentLineNumber
        (stack[-1].append(element) if stack else roots.append(element))
        stack.append(element)

    def end(tag):
        stack.pop()

    def refuse(*args):  # a DTD slipped past the text check: never expand it
        raise ValueError("a DTD or entity declaration")

    parser.StartElementHandler = start
    parser.EndElementHandler = end
    parser.StartDoctypeDeclHandler = refuse
    parser.EntityDeclHandler = refuse
    parser.ExternalEntityRefHandler = refuse
    try:
        parser.Parse(text.encode("utf-8"), True)
    except expat.ExpatError as error:
        raise PresetError(
            path,
            f"line {error.lineno}",
            f"is not well-formed XML: {expat.ErrorString(error.code)}",
            "a URDF or MJCF file",
        ) from None
    except ValueError as error:
        raise PresetError(
            path, "(file)", f"has {error}: refused", "plain URDF or MJCF without a DTD"
        ) from None
    return roots[0], XmlReader(path, lines)

"""The bundled presets (package data) and how a preset argument is resolved.

The presets live in the repository's ``presets/`` folder, installed as the package
``planar_tui.bundled_presets`` (``pyproject.toml``'s package-dir mapping), and are read
with :mod:`importlib.resources`, so an editable install and one from the wheel see the
same files.
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path

from planar_tui.errors import PresetError

PRESETS_PACKAGE = "planar_tui.bundled_presets"


def bundled_presets_folder() -> Path:
    """The folder holding the bundled ``*.toml`` presets."""
    return Path(str(resources.files(PRESETS_PACKAGE)))


def bundled_presets() -> list[Path]:
    """The bundled preset files, sorted by name."""
    return sorted(bundled_presets_folder().glob("*.toml"))


def preset_description(path: Path) -> str:
    """A preset's description: its first comment paragraph (the comment lines before the
    first empty comment line or other line), joined into one line; a sentence that goes
    on to the next line is not cut."""
    words: list[str] = []
    for line in path.read_text(encoding="utf-8").splitlines():
        text = line.lstrip("#").strip()
        if not line.startswith("#") or not text:
            if words or line.strip() not in ("", "#"):
                break
            continue
        words.append(text)
    return " ".join(words)


def resolve_preset(argument: str | Path) -> Path:
    """A preset path as given, or a bundled preset by name (``paper-a-table1``)."""
    path = Path(argument)
    if path.is_file():
        return path
    name = path.name if path.suffix == ".toml" else f"{path.name}.toml"
    bundled = bundled_presets_folder() / name
    if path.parent == Path(".") and bundled.is_file():
        return bundled
    names = ", ".join(p.stem for p in bundled_presets())
    raise PresetError(path, "(file)", "no such file", f"a preset path or a bundled preset: {names}")


def bundled_preset(name: str) -> Path:
    """The bundled preset ``name`` (with or without ``.toml``); an unknown name is a
    :class:`PresetError` listing them."""
    stem = name[:-5] if name.endswith(".toml") else name
    for path in bundled_presets():
        if path.stem == stem:
            return path
    names = ", ".join(p.stem for p in bundled_presets())
    raise PresetError("command line", "NAME", f"is {name!r}, no bundled preset", f"one of {names}")

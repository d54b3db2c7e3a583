"""Where the bundled presets live and how a preset argument is resolved."""

from __future__ import annotations

from pathlib import Path

from planar_tui.errors import PresetError

#: The repository's ``presets/`` folder (the project is installed editable).
BUNDLED_PRESETS = Path(__file__).resolve().parent.parent / "presets"


def bundled_presets() -> list[Path]:
    """The bundled preset files, sorted by name."""
    return sorted(BUNDLED_PRESETS.glob("*.toml"))


def preset_description(path: Path) -> str:
    """The first comment line of a preset (its one-line description)."""
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.startswith("#"):
            return line.lstrip("# ").strip()
        if line.strip():
            break
    return ""


def resolve_preset(argument: str | Path) -> Path:
    """A preset path as given, or a bundled preset by name (``paper-a-table1``)."""
    path = Path(argument)
    if path.is_file():
        return path
    name = path.name if path.suffix == ".toml" else f"{path.name}.toml"
    bundled = BUNDLED_PRESETS / name
    if path.parent == Path(".") and bundled.is_file():
        return bundled
    names = ", ".join(p.stem for p in bundled_presets())
    raise PresetError(path, "(file)", "no such file", f"a preset path or a bundled preset: {names}")

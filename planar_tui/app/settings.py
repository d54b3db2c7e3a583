"""The workbench's settings that persist between sessions (no Textual here).

The theme, the last preset opened or saved, whether the settings form is hidden
(``ctrl+f``) and the output folder (the last one exported or run into) live in one JSON
file, :func:`settings_path`: ``settings.json`` in ``platformdirs.user_config_dir
("planar-tui")`` (``~/.config/planar-tui`` on Linux), or in the folder that the
environment variable :data:`CONFIG_DIR_VARIABLE` names (the tests' own folder).

A missing file gives the defaults; a file that cannot be read (not a regular file, larger
than :data:`MAX_STATE_BYTES`: neither is read) or holds something else than the keys below gives the defaults and a one-line warning (never a crash); the app
then leaves the file as it is (changed settings last for the session). The file is written atomically (a
temporary file in the same folder, then a rename:
:func:`planar_tui.csvio.write_text_atomic`), so a crash mid-write never leaves
half a file.
"""

from __future__ import annotations

import dataclasses
import json
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from planar_tui import csvio
from planar_tui.reader import read_bounded_text

#: The environment variable naming the folder of the settings file (instead of the
#: platform's configuration folder).
CONFIG_DIR_VARIABLE = "PLANAR_TUI_CONFIG_DIR"

#: The settings file's name in that folder.
SETTINGS_FILE = "settings.json"

#: Largest settings or state file read (bytes; they hold a few paths of at most 4 096
#: bytes each, up to 3 times longer as JSON escapes): anything larger, and anything but a
#: regular file (a FIFO, ``/dev/zero``), is not read and gives the defaults.
MAX_STATE_BYTES = 512 * 1024


@dataclass(frozen=True)
class Settings:
    """What the workbench remembers; ``None``: not set (the app's default applies)."""

    #: The Textual theme (``textual-dark``, ``nord`` …; the palette's "Change theme").
    theme: str | None = None
    #: The preset last opened or saved (``planar-tui`` without a preset opens it again).
    last_preset: str | None = None
    #: Whether the job tabs' settings form is hidden (``ctrl+f``).
    form_hidden: bool = False
    #: The folder last exported or run into (Export, figures and Run all offer it).
    output_dir: str | None = None


#: Each setting's allowed type (for the check of a file read back).
TYPES: dict[str, tuple[type, ...]] = {
    "theme": (str, type(None)),
    "last_preset": (str, type(None)),
    "form_hidden": (bool,),
    "output_dir": (str, type(None)),
}


def settings_path() -> Path:
    """The settings file: in ``$PLANAR_TUI_CONFIG_DIR`` when set, else in the
    platform's configuration folder for ``planar-tui``."""
    folder = os.environ.get(CONFIG_DIR_VARIABLE)
    if not folder:
        from platformdirs import user_config_dir

        folder = user_config_dir("planar-tui")
    return Path(folder) / SETTINGS_FILE


def load_settings(path: Path | None = None) -> tuple[Settings, str | None]:
    """The settings in ``path`` (default :func:`settings_path`) and ``None``, or the
    defaults and a one-line warning naming the file when it cannot be used."""
    path = settings_path() if path is None else path
    try:
        text = read_bounded_text(path, MAX_STATE_BYTES, "a settings file")
    except FileNotFoundError:
        return Settings(), None
    except (OSError, UnicodeDecodeError) as error:
        return Settings(), f"{path}: cannot be read ({error}); using the default settings"
    try:
        data = json.loads(text)
    except (ValueError, RecursionError) as error:
        return Settings(), f"{path}: not JSON ({error}); using the default settings"
    if not isinstance(data, dict):
        return Settings(), f"{path}: not a JSON object; using the default settings"
    for key, value in data.items():
        if key not in TYPES:
            allowed = ", ".join(TYPES)
            return Settings(), f"{path}: unknown key {key!r} (allowed: {allowed}); using defaults"
        if not isinstance(value, TYPES[key]):
            expected = " or ".join("null" if t is type(None) else t.__name__ for t in TYPES[key])
            return Settings(), f"{path}: {key} must be {expected}; using the default settings"
    return Settings(**data), None


def save_settings(settings: Settings, path: Path | None = None) -> Path:
    """Write ``settings`` to ``path`` (default :func:`settings_path`) atomically,
    creating its folder; raises ``OSError`` when it cannot be written."""

    path = settings_path() if path is None else path
    csvio.write_text_atomic(path, json.dumps(dataclasses.asdict(settings), indent=2) + "\n")
    return path


def updated(settings: Settings, **changes: Any) -> Settings:
    """``settings`` with ``changes`` (keys of :class:`Settings`)."""
    return dataclasses.replace(settings, **changes)

"""Recently opened presets and results, kept between sessions in a small state file
(``recent.json`` in the platform's user state folder, platformdirs'
``user_state_dir("planar-tui")``; ``$PLANAR_TUI_STATE_DIR`` overrides the folder, as the
tests do). Plain data, no Textual here.

The file is written atomically (:func:`planar_tui.csvio.write_text_atomic`). A file that
cannot be used (not a regular file, larger than
:data:`~planar_tui.app.settings.MAX_STATE_BYTES`: neither is read; no JSON; not an object
of the lists below, each a list of text) gives empty lists and a one-line warning
(:func:`load_checked`, shown once by the app); it is never overwritten: the next
:func:`remember` first renames it to ``recent.json.damaged`` (``.damaged.2`` … when that
exists) and says so. A folder that cannot be written only loses the list, never an action.
"""

from __future__ import annotations

import contextlib
import json
import os
from pathlib import Path

from planar_tui import csvio
from planar_tui.app.settings import MAX_STATE_BYTES
from planar_tui.reader import read_bounded_text

#: Entries kept per list.
MAX_ENTRIES = 10

#: The lists kept: preset files opened or saved, result CSVs opened.
LISTS = ("presets", "results")


def state_dir() -> Path:
    """The folder of the state file: ``$PLANAR_TUI_STATE_DIR``, else platformdirs' user
    state folder for planar-tui (``~/.local/state/planar-tui`` on Linux)."""
    override = os.environ.get("PLANAR_TUI_STATE_DIR")
    if override:
        return Path(override)
    import platformdirs

    return Path(platformdirs.user_state_dir("planar-tui", appauthor=False))


def recent_path() -> Path:
    """The state file: ``recent.json`` in :func:`state_dir`."""
    return state_dir() / "recent.json"


def _problem(path: Path) -> tuple[dict[str, list[str]], str | None]:
    """The lists in ``path`` and ``None``, or empty lists and what is wrong with the file
    (``None`` too when there is no file)."""
    empty: dict[str, list[str]] = {name: [] for name in LISTS}
    try:
        text = read_bounded_text(path, MAX_STATE_BYTES, "a state file")
    except FileNotFoundError:
        return empty, None
    except (OSError, UnicodeDecodeError) as error:
        return empty, f"cannot be read ({error})"
    try:
        data = json.loads(text)
    except (ValueError, RecursionError) as error:
        return empty, f"not JSON ({error})"
    allowed = f"an object of {' and '.join(LISTS)}, each a list of paths"
    if not isinstance(data, dict) or not set(data) <= set(LISTS):
        return empty, f"not {allowed}"
    for name, entries in data.items():
        if not isinstance(entries, list) or not all(isinstance(e, str) for e in entries):
            return empty, f"{name} is not a list of paths (expected {allowed})"
    return {name: data.get(name, [])[:MAX_ENTRIES] for name in LISTS}, None


def load_checked() -> tuple[dict[str, list[str]], str | None]:
    """Every list (absolute paths, newest first) and ``None``, or empty lists and a
    one-line warning naming the file when it cannot be used (module docstring)."""
    path = recent_path()
    lists, problem = _problem(path)
    if problem is None:
        return lists, None
    return lists, (
        f"{path}: {problem}; the recent lists start empty, and the file is kept as "
        f"{path.name}{DAMAGED_SUFFIX} when a file is next remembered"
    )


def load() -> dict[str, list[str]]:
    """Every list (absolute paths, newest first); empty lists when there is no usable file."""
    return load_checked()[0]


#: What a damaged state file's name is given when it is set aside (then ``.2``, ``.3`` …).
DAMAGED_SUFFIX = ".damaged"


def _set_aside(path: Path) -> Path:
    """Rename ``path`` to the first free ``NAME.damaged``, ``NAME.damaged.2`` …"""
    target = path.with_name(path.name + DAMAGED_SUFFIX)
    number = 1
    while target.exists() or target.is_symlink():
        number += 1
        target = path.with_name(f"{path.name}{DAMAGED_SUFFIX}.{number}")
    os.rename(path, target)
    return target


def remember(kind: str, path: Path | str) -> str | None:
    """Put ``path`` first in the list ``kind`` (``"presets"`` or ``"results"``), once;
    a state folder that cannot be written is ignored (the list is a convenience). A state
    file that cannot be used is first renamed (:func:`_set_aside`), never overwritten:
    the line saying so is returned (else ``None``); when it cannot be renamed, the list is
    not written."""

    state = recent_path()
    lists, problem = _problem(state)
    note = None
    if problem is not None:
        try:
            aside = _set_aside(state)
        except OSError:
            return None
        note = f"{state}: {problem}; kept as {aside}, a new recent list started"
    entry = str(Path(path).absolute())
    lists[kind] = [entry, *(e for e in lists[kind] if e != entry)][:MAX_ENTRIES]
    with contextlib.suppress(OSError):
        csvio.write_text_atomic(state, json.dumps(lists, indent=2))
    return note


def recent(kind: str) -> list[Path]:
    """The list ``kind``, newest first, only the files that still exist."""
    return [Path(e) for e in load()[kind] if Path(e).is_file()]

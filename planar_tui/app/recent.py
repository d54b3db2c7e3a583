"""Recently opened presets and results, kept between sessions in a small state file
(``recent.json`` in the platform's user state folder, platformdirs'
``user_state_dir("planar-tui")``; ``$PLANAR_TUI_STATE_DIR`` overrides the folder, as the
tests do). Plain data, no Textual here.

The file is written atomically (:func:`planar_tui.csvio.write_text_atomic`); a file that
cannot be read or parsed, is not a regular file or is larger than
:data:`~planar_tui.app.settings.MAX_STATE_BYTES` (neither is read) counts as empty (it is
rewritten on the next open), and a folder that cannot be written only loses the list,
never an action.
"""

from __future__ import annotations

import contextlib
import json
import os
from pathlib import Path

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


def load() -> dict[str, list[str]]:
    """Every list (absolute paths, newest first); empty lists when there is no usable file."""
    try:
        data = json.loads(read_bounded_text(recent_path(), MAX_STATE_BYTES, "a state file"))
    except (OSError, UnicodeDecodeError, ValueError, RecursionError):
        data = {}
    if not isinstance(data, dict):
        data = {}
    lists = {}
    for name in LISTS:
        entries = data.get(name)
        good = [e for e in entries if isinstance(e, str)] if isinstance(entries, list) else []
        lists[name] = good[:MAX_ENTRIES]
    return lists


def remember(kind: str, path: Path | str) -> None:
    """Put ``path`` first in the list ``kind`` (``"presets"`` or ``"results"``), once;
    a state folder that cannot be written is ignored (the list is a convenience)."""
    from planar_tui.csvio import write_text_atomic

    lists = load()
    entry = str(Path(path).absolute())
    lists[kind] = [entry, *(e for e in lists[kind] if e != entry)][:MAX_ENTRIES]
    with contextlib.suppress(OSError):
        write_text_atomic(recent_path(), json.dumps(lists, indent=2))


def recent(kind: str) -> list[Path]:
    """The list ``kind``, newest first, only the files that still exist."""
    return [Path(e) for e in load()[kind] if Path(e).is_file()]

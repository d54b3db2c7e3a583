"""New files only, written whole: what ``export``, ``import``, ``--export-problem`` and
``--format netcdf`` write never replaces a file that exists.

A file is written to a hidden temporary name in its folder (as
:func:`planar_tui.csvio.write_atomic` does), then hard-linked to its name, which fails if
the name exists (``os.link`` never replaces), and the temporary name is removed: the file
appears whole or not at all, and an existing one is refused with one line. On a file
system without hard links the temporary file is renamed instead, after checking again.
"""

from __future__ import annotations

import os
import secrets
from collections.abc import Callable, Sequence
from pathlib import Path

from planar_tui.errors import PresetError


def existing_problem(path: Path, option: str) -> PresetError:
    """The one-line refusal of an output that exists."""
    what = "a folder" if path.is_dir() else "a file"
    return PresetError(
        path,
        option,
        f"is {what} that exists: nothing is overwritten",
        "a new file name (delete or move the old one first)",
    )


def refuse_existing(paths: Sequence[Path], option: str) -> None:
    """Refuse (:class:`PresetError`) the first of ``paths`` that exists (a dangling link too)."""
    for path in paths:
        if path.exists() or path.is_symlink():
            raise existing_problem(path, option)


def write_new(path: Path, write: Callable[[Path], None], option: str = "(file)") -> Path:
    """Create ``path`` by ``write(temporary_path)``; refuse if it exists (before and at
    the end, atomically); on any error, Ctrl-C included, nothing is left behind. An
    operating-system error (a folder that cannot be created or written, a full disk) is
    a :class:`PresetError` naming the path and the option."""
    path = Path(path)
    refuse_existing([path], option)
    temp = path.with_name(f".{path.name[:64]}.{secrets.token_hex(4)}.tmp")
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        write(temp)
        try:
            os.link(temp, path)
        except FileExistsError:
            raise existing_problem(path, option) from None
        except OSError:  # no hard links here (some network and FAT file systems)
            refuse_existing([path], option)
            os.replace(temp, path)
    except OSError as error:
        raise PresetError(
            path,
            option,
            f"cannot be written: {error.strerror or error}",
            "a path in a writable folder",
        ) from None
    finally:
        temp.unlink(missing_ok=True)
    return path


def write_new_text(path: Path, text: str, option: str = "(file)") -> Path:
    """Create a UTF-8 text file (see :func:`write_new`)."""

    def write(temp: Path) -> None:
        with open(temp, "x", encoding="utf-8", newline="") as stream:
            stream.write(text)

    return write_new(path, write, option)

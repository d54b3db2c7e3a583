"""Saving a preset without losing the user's file: comments kept, bundled presets
read-only, write errors turned into messages (no Textual here).

A preset opened from a file keeps that file's text; saving parses it with ``tomlkit``
(a style-preserving TOML library) and applies the edited values into it
(:func:`merge_document`): changed keys are updated in place (a line's trailing comment
stays), new keys and tables are appended, removed ones deleted, and everything else (the
comments, the order of the keys, the spacing) is left as the user wrote it.
"""

from __future__ import annotations

import os
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

from planar_tui import csvio
from planar_tui.batch import check_writable
from planar_tui.errors import PresetError
from planar_tui.preset_writer import dump_document
from planar_tui.resources import bundled_presets_folder


class SaveFailed(Exception):
    """A preset or a result could not be written (the message says where and why)."""


def is_bundled(path: Path | str) -> bool:
    """Whether ``path`` is one of the presets bundled with planar-tui (read-only)."""
    folder = bundled_presets_folder().resolve()
    return Path(path).resolve().is_relative_to(folder)


def default_save_path(path: Path | str) -> Path:
    """Where save offers to write: the preset's own file, or ``./NAME.toml`` in the current
    folder for a bundled preset (those are read-only)."""
    path = Path(path)
    return Path(path.name) if is_bundled(path) else path


def same_value(a: Any, b: Any) -> bool:
    """Equal values of the same TOML types (``1`` and ``1.0``, or ``1`` and ``true``, are
    different values in a file even though Python calls them equal)."""
    a = a.unwrap() if hasattr(a, "unwrap") else a
    if isinstance(a, Mapping) and isinstance(b, Mapping):
        return a.keys() == b.keys() and all(same_value(a[k], b[k]) for k in a)
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(same_value(x, y) for x, y in zip(a, b, strict=True))
    return type(a) is type(b) and a == b


def _is_table_list(value: Any) -> bool:
    return isinstance(value, list) and bool(value) and all(isinstance(v, Mapping) for v in value)


def merge_values(target: Any, values: Mapping[str, Any]) -> None:
    """Make the tomlkit table ``target`` hold ``values``, keeping what did not change.

    Keys missing from ``values`` are deleted; a sub-table or an array of tables is merged
    key by key (so its comments survive); any other changed value replaces the old one in
    place (its line's trailing comment stays); new keys are appended.
    """
    import tomlkit.items

    for key in [key for key in target if key not in values]:
        del target[key]
    for key, value in values.items():
        old = target.get(key)
        if old is None:
            target[key] = value
        elif isinstance(value, Mapping) and isinstance(old, Mapping):
            merge_values(old, value)
        elif _is_table_list(value) and isinstance(old, tomlkit.items.AoT):
            _merge_tables(old, value)
        elif not same_value(old, value):
            target[key] = value


def _merge_tables(old: Any, tables: list[Mapping[str, Any]]) -> None:
    """Merge an array of tables element by element (extra ones appended or removed)."""
    for index, table in enumerate(tables):
        if index < len(old):
            merge_values(old[index], table)
        else:
            old.append(table)
    while len(old) > len(tables):
        del old[len(old) - 1]


def merge_document(original_text: str, document: Mapping[str, Any]) -> str:
    """The preset file ``original_text`` with ``document``'s values applied (see
    :func:`merge_values`): the comments, key order and formatting of what did not change
    are kept."""
    import tomlkit

    toml = tomlkit.parse(original_text)
    merge_values(toml, document)
    return tomlkit.dumps(toml)


def draft_text(document: Mapping[str, Any], original_text: str | None, description: str) -> str:
    """The document as TOML text without validating it (an invalid preset saved as a
    draft, after a question): applied into the file's text when there is one
    (:func:`merge_document`), else printed as it stands
    (:func:`planar_tui.preset_writer.dump_document`). ``planar-tui run`` of it gives the
    same one-line error the app showed."""
    if original_text is not None:
        return merge_document(original_text, document)

    return dump_document(document, description)


def existing_files(paths: Iterable[Path]) -> list[Path]:
    """The paths that already exist (what writing would overwrite)."""
    return [path for path in paths if os.path.lexists(path)]


def check_target(path: Path) -> None:
    """Refuse a save target that cannot be written (:class:`SaveFailed`): a bundled
    preset, a folder, a path inside no writable folder."""
    if is_bundled(path):
        raise SaveFailed(f"{path}: bundled presets are read-only (choose another path)")
    if path.is_dir():
        raise SaveFailed(f"{path}: is a folder (expected a file path)")
    try:
        check_writable(path)
    except PresetError as error:
        raise SaveFailed(error.message) from None


def write_preset(path: Path, text: str) -> Path:
    """Write ``text`` to ``path`` atomically; any failure is a :class:`SaveFailed`."""

    check_target(path)
    try:
        return csvio.write_text_atomic(path, text)
    except (OSError, ValueError) as error:
        reason = getattr(error, "strerror", None) or str(error)
        raise SaveFailed(f"{path}: cannot write: {reason}") from None

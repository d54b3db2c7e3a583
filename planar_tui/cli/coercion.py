"""Typer's option-value coercion without pydantic for the common cases (issue 21, start-up).

Typer (0.29) builds a pydantic adapter for every option on its first value, even an absent
one, and importing pydantic alone costs about 0.1 s of CPU per command. This module
replaces that coercion for ``str``, ``list[str]`` and ``Path`` values given as text. It
uses Typer's private modules ``typer._coercion`` and ``typer._param_types``, so it imports
only under the Typer releases it was checked with (:data:`CHECKED_TYPER`); under any other
it raises ``ImportError`` and :mod:`planar_tui.cli.output` leaves Typer's own coercion in
place (same values, pydantic imported). ``tests/test_cli_presentation.py`` compares both
side by side.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import typer

#: The Typer minor releases whose private coercion API this module was checked against.
CHECKED_TYPER = ("0.29.",)

if not typer.__version__.startswith(CHECKED_TYPER):
    raise ImportError(f"typer {typer.__version__}: its private coercion API is not checked")

from typer._coercion import RuntimeParam, build_runtime_param  # noqa: E402
from typer._param_types import coerce_cli_path  # noqa: E402


def install_common_values(param) -> None:
    """Give a Typer parameter :class:`CommonValues` as its value coercion (unless it has
    one already): Typer builds a pydantic adapter per parameter on its first value, even
    ``None``, and importing pydantic alone is about 0.1 s CPU of every command."""
    descriptor = getattr(param, "type_descriptor", None)
    if descriptor is not None and getattr(param, "_runtime_param", 0) is None:
        param._runtime_param = CommonValues(
            parameter_info=descriptor.parameter_info,
            annotation=descriptor.annotation,
            descriptor=descriptor,
        )


@dataclass(frozen=True)
class CommonValues(RuntimeParam):
    """Typer's value coercion with the common cases done without pydantic, giving what
    Typer's pydantic adapter gives (``tests/test_cli_presentation.py`` compares them): a
    ``str`` for a ``str``, the list of a ``list[str]``'s strings, and a ``Path`` made of a
    ``str`` then checked by Typer's own :func:`typer._param_types.coerce_cli_path`; an
    absent value (``None``) is answered by the base class without coercion. Everything
    else (numbers, choices, bad values and their messages) goes to the adapter Typer
    builds (:func:`typer._coercion.build_runtime_param`)."""

    descriptor: Any = None

    def _coerce_value(self, value, param, ctx):
        annotation, info = self.annotation, self.parameter_info
        if info.parser is None:
            if annotation is str and type(value) is str:
                return value
            if (
                annotation == list[str]
                and isinstance(value, list | tuple)
                and all(type(item) is str for item in value)
            ):
                return list(value)
            if annotation is Path and info.path_type is None and type(value) is str:
                return coerce_cli_path(Path(value), info, path_type=Path, param=param, ctx=ctx)
        return build_runtime_param(self.descriptor)._coerce_value(value, param=param, ctx=ctx)

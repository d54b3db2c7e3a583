"""The uncertain inputs of a parallel robot and a design row as a robot.

An input is one number of the robot table: a length field (cm; a tuple field gives one
input per entry, ``distal_cm[2]``, a tuple of points one per coordinate,
``platform_points_cm[1].x``), a body's mass (kg) or inertia (kg m²). Lengths are uniform
on ``nominal ± δl`` (``tolerance_length_mm``), masses on ``nominal ± δm``
(``tolerance_mass_g``) and, with ``tolerance_inertia_kgm2``, inertias on ``nominal ± δI``.
A mass or inertia whose nominal value is 0 (a body the robot does not have) is no input.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any

#: What kind of number an input is: its unit in the robot table.
LENGTH, MASS, INERTIA = "length", "mass", "inertia"


@dataclass(frozen=True)
class Input:
    """One uncertain number: its name, the robot field and the position in it (``()`` for
    a scalar field, ``(i,)`` or ``(i, j)`` in a tuple), its kind, its nominal value (the
    robot table's unit) and the half-width of its range."""

    name: str
    field: str
    position: tuple[int, ...]
    kind: str
    nominal: float
    half_width: float


def _entries(value: Any, position: tuple[int, ...] = ()) -> list[tuple[tuple[int, ...], float]]:
    """Every number of a scalar, tuple or tuple of tuples, with its position."""
    if isinstance(value, tuple):
        return [e for i, v in enumerate(value) for e in _entries(v, (*position, i))]
    return [(position, float(value))]


def _label(field: str, position: tuple[int, ...]) -> str:
    """``distal_cm``, ``distal_cm[2]``, ``platform_points_cm[1].x`` (1-based)."""
    if not position:
        return field
    text = f"{field}[{position[0] + 1}]"
    return text + ("." + "xy"[position[1]] if len(position) > 1 else "")


def robot_inputs(
    robot: Any,
    length_fields: tuple[str, ...],
    tolerance_length_cm: float,
    tolerance_mass_kg: float,
    tolerance_inertia_kgm2: float | None,
    names: dict[str, str] | None = None,
) -> tuple[Input, ...]:
    """The inputs of ``robot``: its ``length_fields`` (``None`` fields left out), then every
    field ending ``_mass_kg`` with a positive value, then (with an inertia tolerance) every
    ``_inertia_kgm2`` one; ``names`` maps a field to its preset key where they differ."""
    names = names or {}
    inputs = []
    for field in length_fields:
        value = getattr(robot, field)
        if value is None:
            continue
        for position, nominal in _entries(value):
            label = _label(names.get(field, field), position)
            inputs.append(Input(label, field, position, LENGTH, nominal, tolerance_length_cm))
    spreads = [("_mass_kg", MASS, tolerance_mass_kg)]
    if tolerance_inertia_kgm2 is not None:
        spreads.append(("_inertia_kgm2", INERTIA, tolerance_inertia_kgm2))
    for suffix, kind, half_width in spreads:
        for field in (f.name for f in dataclasses.fields(robot)):
            value = getattr(robot, field)
            if field.endswith(suffix) and value > 0:
                inputs.append(Input(field, field, (), kind, float(value), half_width))
    return tuple(inputs)


def _placed(value: Any, position: tuple[int, ...], number: float) -> Any:
    """``value`` with the entry at ``position`` replaced by ``number``."""
    if not position:
        return number
    items = list(value)
    items[position[0]] = _placed(items[position[0]], position[1:], number)
    return tuple(items)


def robot_at(robot: Any, inputs: tuple[Input, ...], row: Any) -> Any:
    """The robot whose inputs take the values ``row`` (one design row, in the inputs'
    units): ``dataclasses.replace`` of the nominal robot."""
    changed: dict[str, Any] = {}
    for item, number in zip(inputs, row, strict=True):
        current = changed.get(item.field, getattr(robot, item.field))
        changed[item.field] = _placed(current, item.position, float(number))
    return dataclasses.replace(robot, **changed)

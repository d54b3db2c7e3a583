"""The settings of a parallel robot's workspace job over one orientation or an orientation
range, with manufacturing tolerances (the 3-RPR's and the 3-PRR's): the keys and checks
they share, declared once.

A robot's spec subclasses :class:`RangedSpec`, adds its own keys (``leg_limits_cm``) and
its tolerance keys (:func:`~planar_tui.workspace.paving.tolerance.tolerance_fields`), and
names its :class:`~planar_tui.workspace.paving.mechanism.Mechanism`, its job kind, the box
form a tolerance or a range takes (:attr:`RangedSpec.box_form`) and the bounds of its
tolerance (:meth:`RangedSpec.tolerance_bounds`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar

from planar_tui.schema import TableReader
from planar_tui.workspace.paving.runner import PlanarSpec, check_range_and_reference
from planar_tui.workspace.paving.settings import orientation_mode_setting, orientation_setting
from planar_tui.workspace.paving.tolerance import check_tolerance


@dataclass(frozen=True, kw_only=True)
class RangedSpec(PlanarSpec):
    """:class:`~planar_tui.workspace.paving.runner.PlanarSpec` with ``orientation_deg``
    a number or a range ``[lo, hi]`` and its ``orientation_mode``."""

    orientation_deg: float | tuple[float, float] = orientation_setting()
    orientation_mode: str | None = orientation_mode_setting()

    #: The only form a tolerance or an orientation range takes (the kind's box form).
    box_form: ClassVar[str] = "natural"

    @classmethod
    def tolerance_bounds(cls, robot: Any) -> dict[str, float]:
        """Each tolerance key's bound below which its half-width must stay (none here)."""
        return {}

    @classmethod
    def check(cls, values: dict[str, Any], reader: TableReader, robot: Any) -> dict[str, Any]:
        """A tolerance (:func:`~planar_tui.workspace.paving.tolerance.check_tolerance`,
        within :meth:`tolerance_bounds`) takes the :attr:`box_form`, no singularities and
        no geometric reference (the nominal robot's exact area is not the
        tolerance-certified one's: off by default, refused if asked for); an orientation
        range the 3-RRR's ``orientation_mode`` checks, the :attr:`box_form`, no
        singularities and no geometric reference either
        (:func:`~planar_tui.workspace.paving.runner.check_range_and_reference`); then the
        shared checks."""
        check_tolerance(values, reader, cls.tolerance_keys, cls.tolerance_bounds(robot))
        check_range_and_reference(values, reader, cls.box_form)
        return super().check(values, reader, robot)


__all__ = ["RangedSpec"]

"""The 3-PRR's separator (:class:`~planar_tui.workspace.paving.mechanism.LegMechanism`), the
:class:`~planar_tui.workspace.paving.runner.PlanarSpec` of its job names."""

from __future__ import annotations

from collections.abc import Callable
from types import MappingProxyType
from typing import Any

from planar_tui.workspace.paving.mechanism import LegMechanism
from planar_tui.workspace.prr import orientation, singularity
from planar_tui.workspace.prr import robot as prr
from planar_tui.workspace.prr.tolerance import TOLERANCE_KEYS_3PRR


class Mechanism3PRR(LegMechanism):
    """The 3-PRR's separator: the slider test of :mod:`planar_tui.kernels.workspace3prr`, its
    singularities (:mod:`.singularity`) and orientation ranges (:mod:`.orientation`)."""

    name = "3-PRR"
    tolerance_keys = TOLERANCE_KEYS_3PRR
    singular_boxes_per_step = 10.0
    tolerance_boxes = MappingProxyType({"all": 5.0, "some": 16.0})
    robot_module = prr
    singularity_module = singularity
    orientation_module = orientation

    def level_kernel(self) -> Callable[..., None]:
        from planar_tui.kernels.workspace3prr import prr_level

        return prr_level

    def resolve_centre(self, job: Any) -> object:
        return singularity.resolve_circle(job)


MECHANISM = Mechanism3PRR()

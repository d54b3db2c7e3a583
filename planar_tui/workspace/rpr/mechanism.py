"""The 3-RPR's separator (:class:`~planar_tui.workspace.paving.mechanism.LegMechanism`), the
:class:`~planar_tui.workspace.paving.runner.PlanarSpec` of its job names."""

from __future__ import annotations

from collections.abc import Callable
from types import MappingProxyType
from typing import Any

from planar_tui.workspace.paving.mechanism import LegMechanism
from planar_tui.workspace.rpr import orientation, singularity
from planar_tui.workspace.rpr import robot as rpr
from planar_tui.workspace.rpr.tolerance import TOLERANCE_KEYS_3RPR


class Mechanism3RPR(LegMechanism):
    """The 3-RPR's separator: the annulus test of :mod:`planar_tui.kernels.workspace3rpr`, its
    singularities (:mod:`.singularity`) and orientation ranges (:mod:`.orientation`)."""

    name = "3-RPR"
    tolerance_keys = TOLERANCE_KEYS_3RPR
    singular_boxes_per_step = 10.0
    tolerance_boxes = MappingProxyType({"all": 5.0, "some": 5.0})
    robot_module = rpr
    singularity_module = singularity
    orientation_module = orientation

    def level_kernel(self) -> Callable[..., None]:
        from planar_tui.kernels.workspace3rpr import rpr_level

        return rpr_level

    def resolve_centre(self, job: Any) -> object:
        return singularity.resolve_centre(job)


MECHANISM = Mechanism3RPR()

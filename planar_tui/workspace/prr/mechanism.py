"""The 3-PRR's separator (:class:`~planar_tui.workspace.paving.mechanism.LegMechanism`):
the slider test of :mod:`planar_tui.kernels.workspace3prr`, its singularities
(:mod:`.singularity`) and orientation ranges (:mod:`.orientation`); the
:class:`~planar_tui.workspace.paving.runner.PlanarSpec` of its job names it."""

from __future__ import annotations

from collections.abc import Callable
from types import MappingProxyType

from planar_tui.workspace.paving.mechanism import LegMechanism
from planar_tui.workspace.prr import orientation, singularity
from planar_tui.workspace.prr import robot as prr
from planar_tui.workspace.prr.tolerance import TOLERANCE_KEYS_3PRR


def level_kernel() -> Callable[..., None]:
    """The leg test kernel (:func:`planar_tui.kernels.workspace3prr.prr_level`; numba)."""
    from planar_tui.kernels.workspace3prr import prr_level

    return prr_level


MECHANISM = LegMechanism(
    name="3-PRR",
    tolerance_keys=TOLERANCE_KEYS_3PRR,
    singular_boxes_per_step=10.0,
    tolerance_boxes=MappingProxyType({"all": 5.0, "some": 16.0}),
    leg_parameters=prr.leg_parameters,
    kernel=level_kernel,
    reach=prr.reach_box,
    outline=prr.workspace_polygon,
    centre=singularity.resolve_circle,
    singular=singularity.compute_singularities,
    orientation_range=orientation.compute_range,
)

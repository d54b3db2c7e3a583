"""The 3-RPR's separator (:class:`~planar_tui.workspace.paving.mechanism.LegMechanism`):
the annulus test of :mod:`planar_tui.kernels.workspace3rpr`, its singularities
(:mod:`.singularity`) and orientation ranges (:mod:`.orientation`); the
:class:`~planar_tui.workspace.paving.runner.PlanarSpec` of its job names it."""

from __future__ import annotations

from collections.abc import Callable
from types import MappingProxyType

from planar_tui.workspace.paving.mechanism import LegMechanism
from planar_tui.workspace.rpr import orientation, singularity
from planar_tui.workspace.rpr import robot as rpr
from planar_tui.workspace.rpr.tolerance import TOLERANCE_KEYS_3RPR


def level_kernel() -> Callable[..., None]:
    """The leg test kernel (:func:`planar_tui.kernels.workspace3rpr.rpr_level`; numba)."""
    from planar_tui.kernels.workspace3rpr import rpr_level

    return rpr_level


MECHANISM = LegMechanism(
    name="3-RPR",
    tolerance_keys=TOLERANCE_KEYS_3RPR,
    singular_boxes_per_step=10.0,
    tolerance_boxes=MappingProxyType({"all": 5.0, "some": 5.0}),
    leg_parameters=rpr.leg_parameters,
    kernel=level_kernel,
    reach=rpr.reach_box,
    outline=rpr.workspace_polygon,
    centre=singularity.resolve_centre,
    singular=singularity.compute_singularities,
    orientation_range=orientation.compute_range,
)

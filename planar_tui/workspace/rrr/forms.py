"""The workspace's forms of the inclusion test, and the kernel code of each interval form.

One home for the names a preset's ``form`` takes and for what the kernels
(:mod:`planar_tui.kernels.workspace3rrr`) call them; imports nothing heavy (the CLI reads
the names to build its help).
"""

from __future__ import annotations

#: The interval forms (paper B, eqs. 20-23) by name, with their kernel constant's name.
INTERVAL_FORMS = {"natural": "NATURAL", "mean-value": "MEAN_VALUE", "slope": "SLOPE"}
#: Every form: the interval ones, the exact leg-wise test, the exact area only.
FORMS = (*INTERVAL_FORMS, "arc-distance", "geometric")


def kernel_form(form: str, expanded: bool = False) -> int:
    """The kernels' code of an interval form (``natural`` with ``expanded``: the paper's
    expanded eqs. 22-23, ``NATURAL_EXPANDED``)."""
    from planar_tui.kernels import workspace3rrr

    code: int = getattr(workspace3rrr, "NATURAL_EXPANDED" if expanded else INTERVAL_FORMS[form])
    return code

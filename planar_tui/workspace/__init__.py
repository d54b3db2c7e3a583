"""Workspaces of the parallel robots by interval analysis.

:mod:`.paving` is the core (the paver, naming no robot); each robot is one subpackage
(:mod:`.rrr`, :mod:`.rpr`, :mod:`.prr`, :mod:`.fivebar`) providing its
:class:`~planar_tui.workspace.paving.mechanism.Mechanism` and job kind, registered by one
line each in :mod:`planar_tui.registry`. Nothing here imports numba or shapely at module
level; the kernels are ``planar_tui.kernels.workspace*`` and ``planar_tui.kernels.interval``.
"""

"""3-RRR workspace by interval analysis (paper B).

:mod:`.robot` (the ``[robot3rrr]`` model), :mod:`.job` (the ``[workspace]`` job kind),
:mod:`.compute` (bisection stages, certified bracket, union areas), :mod:`.geometry` (the
exact shapely reference), :mod:`.map` (the character-cell map). Nothing here imports numba
or shapely at module level; the kernels are ``planar_tui.kernels.workspace*`` and
``planar_tui.kernels.interval``.
"""

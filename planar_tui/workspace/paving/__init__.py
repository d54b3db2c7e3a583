"""The paving core of the parallel robots' workspaces, naming no robot.

One paver, many separators (as codac/pyIbex compose them): a robot subpackage
(:mod:`planar_tui.workspace.rrr`, :mod:`~planar_tui.workspace.rpr`,
:mod:`~planar_tui.workspace.prr`, :mod:`~planar_tui.workspace.fivebar`) provides one
:class:`~planar_tui.workspace.paving.mechanism.Mechanism`; this package paves with it.

:mod:`.levels` (the box budget, the paving in levels, the certified bracket),
:mod:`.settings` (the shared keys, declared once), :mod:`.runner` (the generic runner),
:mod:`.orientation` (orientation-range paving), :mod:`.tolerance` (tolerance layers),
:mod:`.estimate` (a job's boxes, memory and time before it runs), :mod:`.columns` (sweep
columns), :mod:`.map` (the character-cell map), :mod:`.boxes`, :mod:`.geometry` (exact
shapely references), :mod:`.circle` (the singularity-free circle), :mod:`.layout` (three-leg
layouts), :mod:`.result` (the result and its terminal view). Nothing here imports a robot
subpackage (an import contract in ``pyproject.toml``).
"""

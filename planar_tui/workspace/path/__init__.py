"""The path core, naming no robot: a quintic rest-to-rest platform path, the path job's
settings, runner, columns and summary, and the forward dynamics in platform coordinates.
A robot plugs in through its :class:`~planar_tui.workspace.paving.mechanism.Mechanism`
(``path_model``, ``inverse_dynamics``)."""

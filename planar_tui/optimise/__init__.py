"""Optimisations: the values of a preset job's keys that maximise or minimise columns of
its summary under constraints (``[[optimise]]`` tables), by pymoo on the sweep machinery.

* :mod:`~planar_tui.optimise.problem` — one optimisation, checked
  (:class:`~planar_tui.optimise.problem.Optimisation`);
* :mod:`~planar_tui.optimise.spec` — the ``[[optimise]]`` table read and checked;
* :mod:`~planar_tui.optimise.evaluations` — the run's record: evaluations, optimum or
  Pareto set, tables and figure data;
* :mod:`~planar_tui.optimise.run` — the ask-and-tell loop, its generations run as sweep
  points (in-process or on Dask), checkpointed, then the optimum certified.

Importing this package imports neither NumPy, pymoo nor Dask.
"""

#: The preset's top-level table of optimisations.
TABLE = "optimise"

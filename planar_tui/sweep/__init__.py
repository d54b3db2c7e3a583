"""Sweeps: one job of a preset run over many values of its keys (``[[sweep]]`` tables).

The package sits between the front ends and the batch service:

* :mod:`~planar_tui.sweep.paths` — key paths (``orientation_deg``, ``robot.lengths_m[2]``)
  and applying a point's values to the job's and robot's TOML tables;
* :mod:`~planar_tui.sweep.spec` — the ``[[sweep]]`` table read and checked
  (:class:`~planar_tui.sweep.spec.Sweep`), or built by the app without a file;
* :mod:`~planar_tui.sweep.points` — the points (grid, zip, Sobol'/LHS/uniform sample), each
  validated as a preset job before anything runs;
* :mod:`~planar_tui.sweep.worker` — one point run (what a Dask task carries and returns);
* :mod:`~planar_tui.sweep.execute` — running the points in-process or on Dask;
* :mod:`~planar_tui.sweep.checkpoint` — finished points saved as they arrive, for ``--resume``;
* :mod:`~planar_tui.sweep.table` — the sweep CSV (one row per point, in point order);
* :mod:`~planar_tui.sweep.service` — the whole run for both front ends.

Importing this package imports neither NumPy nor Dask.
"""

#: The preset's top-level table of sweeps.
TABLE = "sweep"

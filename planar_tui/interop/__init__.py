"""Robots in and out of other tools: MJCF and URDF export and import, the SALib hand-off
and the motion job's results as a NetCDF dataset (``docs/interop.md``).

The conventions every file of this package shares are in :mod:`.conventions`. Nothing here
imports MuJoCo, Pinocchio, xarray or SALib: the files are plain XML, JSON, NumPy and
NetCDF, and the optional readers and writers are imported only when called.
"""

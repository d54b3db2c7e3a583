"""How tolerances move a parallel robot's actuator efforts along a path: the
``[[path3rrr_sensitivity]]``, ``[[path5r_sensitivity]]``, ``[[path3rpr_sensitivity]]``
and ``[[path3prr_sensitivity]]`` jobs.

Every uncertain input (a length or platform dimension of the robot table, a body's mass,
optionally its inertia) is uniform on ``nominal ± tolerance``; each design row is a robot
(``dataclasses.replace``) whose efforts along the path job's quintic come from its
mechanism's ``inverse_dynamics``; the estimators are the serial arm's
(:mod:`planar_tui.sensitivity`: Sobol', eFAST, PCE). This package sits beside
:mod:`planar_tui.motion`, above both :mod:`planar_tui.sensitivity` and
:mod:`planar_tui.workspace`, the only layer that may use the estimators on a parallel
robot.

Modules: :mod:`.inputs` (the uncertain inputs of a robot, a design row as a robot),
:mod:`.sizes` (a job's inputs and sample sizes), :mod:`.engine` (the efforts of every
design row, the peak, RMS and per-step outputs), :mod:`.analysis` (the runner and its
result), :mod:`.job` (settings, checks, view: the kinds' factory), :mod:`.rrr`,
:mod:`.fivebar`, :mod:`.rpr`, :mod:`.prr` (one job kind per robot). Nothing here imports numba, SALib or scipy at
module level.
"""

"""Global sensitivity of the joint torques to link lengths and masses (paper A, section 3).

Sobol' (Saltelli design) and eFAST indices of every joint torque of an n-link planar robot
with respect to its link lengths and masses (and optionally inertias), each uniform on
``nominal ± tolerance``. SALib samples (each unit design once, then from a disk cache);
the model is one batched Numba inverse-dynamics call over the whole sample matrix; the
indices come from jitted/vectorised estimators that equal SALib's on the same samples
(SALib stays the reference, see ``tests/``).

Modules: :mod:`.postures` (singular, isotropic, explicit), :mod:`.optimise` (the small
minimisers of the isotropic search), :mod:`.estimators` (indices), :mod:`.engine` (sample,
evaluate, analyse), :mod:`.design_cache` (SALib's designs on disk), :mod:`.results` (CSV
rows, percent),
:mod:`.tables` (Table-4-shaped tables), :mod:`.bars` (Fig 5/6 bars), :mod:`.job` (the
``[sensitivity]`` job kind: settings, runner, result, terminal view),
:mod:`.paper` (comparison with paper A's Tables 4-5). Nothing here imports numba, SALib or
scipy at module level.
"""

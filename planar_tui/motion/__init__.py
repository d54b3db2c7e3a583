"""How manufacturing tolerances move the robot: the ``[motion_uncertainty]`` job.

Robots sampled over the tolerances of their link lengths and masses (Monte Carlo, Sobol',
eFAST designs of :mod:`planar_tui.sensitivity`), each integrated by RK4 (batched Numba
kernel on every core, or a CUDA kernel), giving the band of the motion over time and the
Sobol'/eFAST indices of the joint angles and the tip at chosen times.

Modules: :mod:`.device` (cpu / cuda / auto), :mod:`.engine` (designs, integration, outputs,
band), :mod:`.results` (indices per time, CSV tables, terminal view, sweep figures),
:mod:`.job` (the job kind). Nothing here imports numba, SALib or scipy at module level.
"""

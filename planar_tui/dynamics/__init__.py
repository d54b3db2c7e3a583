"""Dynamics of n-link planar serial revolute robots (paper A, section 2).

:mod:`.robot` (the ``[robot]`` model), :mod:`.simulate` (the ``[simulate]`` job: RK4
forward dynamics), :mod:`.torques` (the ``[torques]`` job: inverse dynamics). The
kernels are in :mod:`planar_tui.kernels.dynamics` and :mod:`planar_tui.kernels.rk4`.
"""

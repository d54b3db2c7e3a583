"""Baselines shared by the benchmarks: the same inverse dynamics without Numba."""

import numpy as np


def numpy_newton_euler(lengths, masses, inertias, gravity, theta, omega, alpha):
    """Vectorised over samples (S, n), looping over links: the same recursion in NumPy."""
    phi, rate, accel = np.cumsum(theta), np.cumsum(omega), np.cumsum(alpha)
    ux, uy = np.cos(phi), np.sin(phi)
    bx = -accel * uy - rate**2 * ux
    by = accel * ux - rate**2 * uy
    n = lengths.shape[1]
    fx, fy = np.empty_like(lengths), np.empty_like(lengths)
    ax = np.zeros(lengths.shape[0])
    ay = np.full(lengths.shape[0], gravity)
    for i in range(n):
        fx[:, i] = masses[:, i] * (ax + 0.5 * lengths[:, i] * bx[i])
        fy[:, i] = masses[:, i] * (ay + 0.5 * lengths[:, i] * by[i])
        ax = ax + lengths[:, i] * bx[i]
        ay = ay + lengths[:, i] * by[i]
    tau = np.empty_like(lengths)
    big_fx = np.zeros_like(ax)
    big_fy = np.zeros_like(ax)
    moment = np.zeros_like(ax)
    for i in range(n - 1, -1, -1):
        hx, hy = 0.5 * lengths[:, i] * ux[i], 0.5 * lengths[:, i] * uy[i]
        moment = moment + inertias[:, i] * accel[i] + hx * fy[:, i] - hy * fx[:, i]
        moment = moment + 2.0 * (hx * big_fy - hy * big_fx)
        big_fx = big_fx + fx[:, i]
        big_fy = big_fy + fy[:, i]
        tau[:, i] = moment
    return tau

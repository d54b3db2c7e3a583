"""Sobol' indices of a polynomial chaos expansion from its coefficients (Sudret 2008):
a term's variance share is its squared coefficient over the sum of the squares of every
non-constant term's; S1 sums the terms of one input alone, ST every term that holds it.

Kept apart from :mod:`planar_tui.sensitivity.pce` so that the compressed fit
(:mod:`planar_tui.sensitivity.pce_compress`) and the expansion share it without a cycle.
"""

from __future__ import annotations

import numpy as np


def indices_from_coefficients(indices: np.ndarray, coefficients: np.ndarray):
    """S1 and ST (..., T, D) from the multi-indices (k, D) and coefficients (..., k, T)
    (zeros for an output without variance)."""
    active = indices > 0
    order = active.sum(axis=1)
    energy = coefficients**2  # (..., k, T)
    energy[..., order == 0, :] = 0.0
    variance = energy.sum(axis=-2)[..., None]  # (..., T, 1)
    total = np.swapaxes(energy, -1, -2) @ active  # (..., T, D)
    first = np.swapaxes(energy, -1, -2) @ (active & (order == 1)[:, None])
    safe = np.where(variance > 0.0, variance, 1.0)
    return first / safe, total / safe

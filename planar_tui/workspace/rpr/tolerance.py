"""Tolerance-certified 3-RPR workspaces (issue 25, item 2; the interface of
:mod:`planar_tui.workspace.paving.tolerance`).

Every robot within the tolerances has, per leg and independently, the base joint
:math:`A_i + a` (:math:`|a_x|, |a_y| \\le t_A`, ``base_joints_cm``) and the platform point
:math:`q_i + b` (:math:`|b_x|, |b_y| \\le t_q`, ``platform_points_cm``); the leg limits
:math:`[lo_i, hi_i]` are actuator strokes and stay exact. At the platform position
:math:`v` with :math:`u = v + R(\\varphi) q_i - A_i` the robot's leg distance is
:math:`d_\\pi = |u + \\delta|`, :math:`\\delta = R(\\varphi) b - a`. The set :math:`S` of
:math:`\\delta` is the Minkowski sum of the square of half-width :math:`t_A` and the rotated
square of half-width :math:`t_q`, so

* :math:`|\\delta| \\le \\sigma = \\sqrt2\\,(t_A + t_q)` (the squares' half-diagonals): by
  the triangle inequality :math:`|d_\\pi - d| \\le \\sigma` for every robot;
* :math:`S` holds the disc of radius :math:`\\gamma = t_A + t_q` (each square holds its
  inscribed disc): some robot has :math:`\\delta = \\gamma u/|u|`, so
  :math:`\\max_\\pi d_\\pi \\ge d + \\gamma`, and one has :math:`\\delta = -\\min(\\gamma, d)
  u / |u|`, so :math:`\\min_\\pi d_\\pi \\le \\max(0, d - \\gamma)`; :math:`S` is connected,
  so every distance in between is some robot's.

With :math:`[d_{lo}, d_{hi}]` the nominal leg distance's range over the (x, y) box
:math:`B` (the kernel's exact range, :mod:`planar_tui.kernels.workspace3rpr`), per leg:

* ``all`` (:math:`\\forall \\pi\\, \\forall v \\in B: v \\in W(\\pi)`): **inside** iff every
  leg has :math:`[d_{lo}, d_{hi}] \\subseteq [lo + \\sigma, hi - \\sigma]` (then
  :math:`d_\\pi \\in [d - \\sigma, d + \\sigma] \\subseteq [lo, hi]`); **outside**
  (:math:`\\forall v\\, \\exists \\pi: v \\notin W(\\pi)`) iff some leg has
  :math:`d_{lo} > hi - \\gamma` (at each :math:`v` the robot lengthening the leg by
  :math:`\\gamma` exceeds :math:`hi`) or :math:`d_{hi} < lo - \\ldots`, precisely
  :math:`d_{hi} < lo + \\gamma` with :math:`lo > 0` (the robot shortening it has
  :math:`\\max(0, d - \\gamma) < lo`).
* ``some`` (:math:`\\forall v \\in B\\, \\exists \\pi: v \\in W(\\pi)`): **inside** iff every
  leg has :math:`[d_{lo}, d_{hi}] \\subseteq [lo - \\gamma, hi + \\gamma]` (at each
  :math:`v` the robots' distances fill :math:`[\\max(0, d - \\gamma), d + \\gamma]`, which
  meets :math:`[lo, hi]`; the legs' parameters are independent, so one robot serves all
  three); **outside** (:math:`\\forall \\pi\\, \\forall v: v \\notin W(\\pi)`) iff some leg
  has :math:`d_{lo} > hi + \\sigma` or :math:`d_{hi} < lo - \\sigma`.

These are the kernel's four thresholds per leg (:func:`leg_thresholds`), each rounded
outward (a threshold that tightens a certificate is nudged one ulp further after each
addition); negative ones are 0 (a distance is never below 0). At zero tolerance
:math:`\\sigma = \\gamma = 0` and the thresholds are :math:`lo, hi` exactly: the nominal
labels, bit for bit.

**Bound.** The robust workspace holds the nominal one *eroded in leg length* by
:math:`\\sigma` (the points with every :math:`d \\in [lo + \\sigma, hi - \\sigma]`); the
"some" workspace lies in the one *dilated* by :math:`\\sigma`.
"""

from __future__ import annotations

import math
from typing import Any

from planar_tui.workspace.paving.tolerance import plus, shift_bounds_cm, tolerance_of

#: The 3-RPR's toleranced quantities (keys of ``tolerances_cm``).
TOLERANCE_KEYS_3RPR = ("base_joints_cm", "platform_points_cm")


def leg_thresholds(
    lo: float, hi: float, mode: str | None, t_base_cm: float, t_platform_cm: float
) -> tuple[float, float, float, float]:
    """``(out_lo, out_hi, in_lo, in_hi)`` of one leg (module docstring; ``mode`` ``None``:
    the nominal robot)."""
    inf = math.inf
    if mode is None:
        return lo, hi, lo, hi
    sigma, gamma = shift_bounds_cm(t_base_cm, t_platform_cm)
    if mode == "all":
        out_lo = plus(lo, gamma, -inf) if lo > 0.0 else 0.0
        in_lo = plus(lo, sigma, inf) if lo > 0.0 else 0.0  # d >= 0 holds for every robot
        return out_lo, plus(hi, -gamma, inf), in_lo, plus(hi, -sigma, -inf)
    return (
        plus(lo, -sigma, -inf),
        plus(hi, sigma, inf),
        plus(lo, -gamma, inf),
        plus(hi, gamma, -inf),
    )


def spec_thresholds(spec: Any) -> list[tuple[float, float, float, float]]:
    """:func:`leg_thresholds` of every leg of a 3-RPR spec."""
    tolerance = tolerance_of(spec, TOLERANCE_KEYS_3RPR)
    if tolerance is None:
        return [(lo, hi, lo, hi) for lo, hi in spec.leg_limits_cm]
    t_a, t_q = tolerance.of("base_joints_cm"), tolerance.of("platform_points_cm")
    return [leg_thresholds(lo, hi, tolerance.mode, t_a, t_q) for lo, hi in spec.leg_limits_cm]

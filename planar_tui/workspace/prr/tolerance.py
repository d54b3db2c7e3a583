"""Tolerance-certified 3-PRR workspaces (issue 25, item 2; the interface of
:mod:`planar_tui.workspace.paving.tolerance`, the bounds of :mod:`planar_tui.workspace.rpr.tolerance`).

Every robot within the tolerances has, per leg and independently, the slider line's point
:math:`B_i + a` (:math:`|a_x|, |a_y| \\le t_B`, ``slider_points_cm``), the platform point
:math:`q_i + b` (:math:`|b_x|, |b_y| \\le t_q`, ``platform_points_cm``) and the distal
:math:`l_i + \\kappa` (:math:`|\\kappa| \\le t_l`, ``distal_cm``); the line directions and
strokes are exact. Moving the stroke's segment by :math:`a` is moving the platform joint by
:math:`-a`, so the robot's leg sees :math:`C_i + \\delta`, :math:`\\delta = R(\\varphi) b - a`,
and closes iff :math:`d_{seg}(C_i + \\delta) \\le l_i + \\kappa \\le d_{end}(C_i + \\delta)`
(:mod:`planar_tui.kernels.workspace3prr`). As for the 3-RPR, :math:`|\\delta| \\le \\sigma =
\\sqrt2 (t_B + t_q)` and every :math:`|\\delta| \\le \\gamma = t_B + t_q` is some robot's;
:math:`d_{seg}` and :math:`d_{end}` are 1-Lipschitz, and moving :math:`C` by :math:`\\gamma`
along the normal from its nearest segment point raises :math:`d_{seg}` by exactly
:math:`\\gamma` (the projection on a convex set is constant along that ray).

Per leg, with the kernel's bounds over the box :math:`B` (:math:`\\min/\\max d_{seg}`,
:math:`\\min/\\max d_{end}` of the nominal robot):

* ``all`` (:math:`\\forall \\pi\\, \\forall v`): **inside** iff every leg has
  :math:`\\max d_{seg} \\le l - t_l - \\sigma` and :math:`\\min d_{end} \\ge l + t_l + \\sigma`;
  **outside** (:math:`\\forall v\\, \\exists \\pi`) iff some leg has :math:`\\min d_{seg} > l -
  t_l - \\gamma` (at each :math:`v` the robot raising :math:`d_{seg}` by :math:`\\gamma` with
  the shortest distal misses) or :math:`\\max d_{end} < l + t_l` (the nominal geometry with
  the longest distal misses every point).
* ``some`` (:math:`\\forall v\\, \\exists \\pi`): **inside** iff every leg has
  :math:`\\max d_{seg} \\le l + t_l` and :math:`\\min d_{end} \\ge l - t_l` (at each :math:`v` a
  distal in :math:`[d_{seg}, d_{end}] \\cap [l - t_l, l + t_l]` exists); **outside**
  (:math:`\\forall \\pi\\, \\forall v`) iff some leg has :math:`\\min d_{seg} > l + t_l +
  \\sigma` or :math:`\\max d_{end} < l - t_l - \\sigma`.

The ``some``-inside and ``all``-outside-by-:math:`d_{end}` certificates use the distal's
tolerance alone (sound, looser by up to :math:`\\gamma`). Each threshold is rounded the safe
way (:func:`~planar_tui.workspace.paving.tolerance.shift_bounds_cm`); at zero tolerance all four
are :math:`l` exactly: the nominal labels bit for bit.
"""

from __future__ import annotations

import math
from typing import Any

from planar_tui.workspace.paving.tolerance import plus, shift_bounds_cm, tolerance_of

#: The 3-PRR's toleranced quantities (keys of ``tolerances_cm``).
TOLERANCE_KEYS_3PRR = ("slider_points_cm", "platform_points_cm", "distal_cm")


def leg_thresholds(
    length: float, mode: str | None, t_slider_cm: float, t_platform_cm: float, t_distal_cm: float
) -> tuple[float, float, float, float]:
    """``(out_seg, out_end, in_seg, in_end)`` of one leg (module docstring; ``mode``
    ``None``: the nominal robot)."""
    if mode is None:
        return length, length, length, length
    sigma, gamma = shift_bounds_cm(t_slider_cm, t_platform_cm)
    up, down = math.inf, -math.inf
    short_down, long_down = plus(length, -t_distal_cm, down), plus(length, t_distal_cm, down)
    short_up, long_up = plus(length, -t_distal_cm, up), plus(length, t_distal_cm, up)
    if mode == "all":
        return (
            plus(short_down, -gamma, down),
            long_down,
            plus(short_down, -sigma, down),
            plus(long_up, sigma, up),
        )
    return plus(long_up, sigma, up), plus(short_down, -sigma, down), long_down, short_up


def spec_thresholds(robot: Any, spec: Any) -> list[tuple[float, float, float, float]]:
    """:func:`leg_thresholds` of every leg of a 3-PRR robot and spec."""
    tolerance = tolerance_of(spec, TOLERANCE_KEYS_3PRR)
    if tolerance is None:
        return [leg_thresholds(length, None, 0.0, 0.0, 0.0) for length in robot.distal_cm]
    t = tolerance.of
    widths = (t("slider_points_cm"), t("platform_points_cm"), t("distal_cm"))
    return [leg_thresholds(length, tolerance.mode, *widths) for length in robot.distal_cm]

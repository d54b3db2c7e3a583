"""The piece tests of the 3-RPR and the 3-PRR over a range of orientations (the 3-RRR's
paving of :mod:`kernels.workspace_orientation` with ``mechanism = RPR`` or ``PRR``).

At the platform position :math:`p` and orientation :math:`\\varphi` leg ``i``'s platform
point is :math:`C_i = p + R(\\varphi) q_i`. For a piece :math:`[m - h, m + h]`
(:math:`h \\le \\pi`) of the range, :math:`|R(\\varphi) q_i - R(m) q_i| = 2 |q_i|
\\sin(|\\varphi - m| / 2) \\le 2 |q_i| \\sin(h / 2) =: \\delta_i` (the chord of the arc), so
every distance :math:`d` of the leg test that is 1-Lipschitz in :math:`C_i` obeys
:math:`d(p + R(\\varphi) q_i) \\in [d(p + R(m) q_i) - \\delta_i, d(p + R(m) q_i) +
\\delta_i]` over the box :math:`X` and the piece. The test at :math:`m` is written on the
platform position with the base features shifted by :math:`-R(m) q_i` (the
one-orientation kernels' convention), and its thresholds are moved by :math:`\\delta_i`:

* **3-RPR** (:mod:`kernels.workspace3rpr`): leg ``i`` closes iff :math:`lo_i \\le |p +
  R(\\varphi) q_i - A_i| \\le hi_i`. With :math:`c_i(m) = A_i - R(m) q_i` and :math:`[D_{lo},
  D_{hi}]` the exact range of :math:`|p - c_i(m)|` over :math:`X`, the leg length over
  :math:`X \\times [m - h, m + h]` lies in :math:`[D_{lo} - \\delta_i, D_{hi} + \\delta_i]`:
  the leg is ``OUT`` if :math:`D_{hi} < lo_i - \\delta_i` or :math:`D_{lo} > hi_i +
  \\delta_i`, ``IN`` if :math:`[D_{lo}, D_{hi}] \\subseteq [lo_i + \\delta_i, hi_i -
  \\delta_i]`: :func:`kernels.workspace3rpr.leg_label` with ``out = (max(0, lo - δ), hi +
  δ)``, ``in = (lo + δ, max(0, hi - δ))`` (with ``hi - δ < 0`` nothing is ``IN``: ``slo >=
  (lo + δ)² >= δ² > 0``).
* **3-PRR** (:mod:`kernels.workspace3prr`): leg ``i`` closes iff :math:`d_{seg}(C_i) \\le
  l_i \\le d_{end}(C_i)` (the distance to the stroke segment and the larger one to its
  ends, both 1-Lipschitz): ``OUT`` if :math:`\\min_X d_{seg} > l_i + \\delta_i` or
  :math:`\\max_X d_{end} < l_i - \\delta_i`, ``IN`` if :math:`\\max_X d_{seg} \\le l_i -
  \\delta_i` and :math:`\\min_X d_{end} \\ge l_i + \\delta_i`:
  :func:`kernels.workspace3prr.prr_leg_label` with ``out_seg = l + δ``, ``out_end = l -
  δ``, ``in_seg = l - δ``, ``in_end = l + δ`` (its certified box bounds).

The piece is *all in* when every leg is ``IN``, *out* when one leg is ``OUT``; the box
classification (maximal, total) is :func:`kernels.workspace_orientation.classify_box_range`'s.

**Rounding.** Over a piece (``h > 0``) :math:`\\delta_i` is enlarged by ``TOLERANCE_CM``
(1e-9 cm), far above the round-off of the chord, of the shifted features' cos/sin and of the
threshold sums at robot scale (about 1e-14 cm at 100 cm). At a point orientation (``h = 0``:
a degenerate range, the midpoint tests) :math:`\\delta = 0` and the shifted features are
computed by the same float formulas as :meth:`planar_tui.workspace.rpr.robot.Robot3RPR.centres_cm`
and :meth:`planar_tui.workspace.prr.robot.Robot3PRR.shifted_ends_cm`: the test is then the
constant-orientation job's bit for bit, trusting the same cos/sin.

Geometry vector ``g`` (the 3-RRR's layout, :func:`planar_tui.workspace.paving.runner.
platform_and_base_vector`): ``[0, 0, qx1, qy1, qx2, qy2, qx3, qy3, bx1, by1, bx2, by2, bx3,
by3]`` (cm; ``b`` the base joints :math:`A_i` of a 3-RPR, the slider line points
:math:`B_i` of a 3-PRR). ``limits``: a 3-RPR's (3, 2) leg limits ``[lo, hi]``; a 3-PRR's
(3, 5) ``ux, uy, s_lo, s_hi, l`` per leg (the line's unit direction, the stroke, the distal
length; cm).
"""

import math

from ._jit import kernel
from .workspace3prr import prr_leg_label
from .workspace3rpr import leg_label, squared_distance_range
from .workspace_arc import INSIDE, OUTSIDE, TOLERANCE_CM

#: Piece verdicts (the values of :mod:`kernels.workspace_orientation`'s ``PIECE_*``).
PIECE_OUT = 0
PIECE_UNKNOWN = 1
PIECE_IN = 2


@kernel
def _rpr_leg(xlo, xhi, ylo, yhi, cx, cy, limits, leg, delta):
    """The 3-RPR's leg label about the shifted centre ``(cx, cy)`` (module docstring)."""
    slo, shi = squared_distance_range(xlo, xhi, ylo, yhi, cx, cy)
    lo = limits[leg, 0]
    hi = limits[leg, 1]
    return leg_label(slo, shi, max(0.0, lo - delta), hi + delta, lo + delta, max(0.0, hi - delta))


@kernel
def _prr_leg(xlo, xhi, ylo, yhi, ox, oy, limits, leg, delta):
    """The 3-PRR's leg label about the shifted line point ``(ox, oy)`` (module docstring)."""
    ux = limits[leg, 0]
    uy = limits[leg, 1]
    lo = limits[leg, 2]
    hi = limits[leg, 3]
    length = limits[leg, 4]
    return prr_leg_label(
        xlo,
        xhi,
        ylo,
        yhi,
        ox + lo * ux,
        oy + lo * uy,
        ox + hi * ux,
        oy + hi * uy,
        length + delta,
        length - delta,
        length - delta,
        length + delta,
    )


@kernel
def parallel_piece_status(prismatic_first, xlo, xhi, ylo, yhi, phi_mid, phi_half, g, limits):
    """``PIECE_IN``, ``PIECE_OUT`` or ``PIECE_UNKNOWN`` over the box and the orientations
    ``[phi_mid - phi_half, phi_mid + phi_half]`` of a 3-PRR (``prismatic_first``) or a
    3-RPR (module docstring)."""
    c = math.cos(phi_mid)
    s = math.sin(phi_mid)
    chord = 2.0 * math.sin(0.5 * min(phi_half, math.pi)) if phi_half > 0.0 else 0.0
    all_in = True
    for leg in range(3):
        qx = g[2 + 2 * leg]
        qy = g[3 + 2 * leg]
        delta = chord * math.hypot(qx, qy) + TOLERANCE_CM if phi_half > 0.0 else 0.0
        bx = g[8 + 2 * leg] - (c * qx - s * qy)
        by = g[9 + 2 * leg] - (s * qx + c * qy)
        if prismatic_first:
            label = _prr_leg(xlo, xhi, ylo, yhi, bx, by, limits, leg, delta)
        else:
            label = _rpr_leg(xlo, xhi, ylo, yhi, bx, by, limits, leg, delta)
        if label == OUTSIDE:
            return PIECE_OUT
        all_in = all_in and label == INSIDE
    return PIECE_IN if all_in else PIECE_UNKNOWN
